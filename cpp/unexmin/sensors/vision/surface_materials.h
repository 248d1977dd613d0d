// The materials of a world's meshes as the cameras and the SLS lasers see them: per mesh of the world file, its
// RockTexture (textured kinds) and the mesh frame, so that a hit point in the world frame gives the albedo and the
// shading normal there (docs/vision.md "Materials"). A plain mesh gives its one albedo and the face's normal.
// Knows no ROS.
#pragma once

#include <unexmin/sensors/vision/rock_texture.h>
#include <unexmin/sim/world_config.h>

#include <Eigen/Geometry>

#include <memory>
#include <vector>

namespace unexmin {
namespace sensors {
namespace vision {

class SurfaceMaterials {
public:
  /// One entry per mesh of `config` (the index of a raycast::Hit of kind mesh).
  explicit SurfaceMaterials(const sim::WorldConfig& config);

  /// The materials of `config` held by `cache`: built on first use and again for another world configuration.
  static const SurfaceMaterials& of(const sim::WorldConfig& config, std::unique_ptr<SurfaceMaterials>& cache);

  std::size_t size() const { return meshes_.size(); }
  /// Whether mesh `mesh` has a texture (else its albedo is one number per channel and its normal the face's).
  bool textured(std::size_t mesh) const { return meshes_.at(mesh).texture != nullptr; }
  /// The mesh's mean albedo (R, G, B, 0) [-].
  const Eigen::Array4f& meanAlbedo(std::size_t mesh) const { return meshes_[mesh].albedo; }
  /// Albedo (R, G, B) of mesh `mesh` at world point `p` [m].
  Eigen::Array3f albedo(std::size_t mesh, const Eigen::Vector3f& p) const;
  /// Albedo (into albedo[0..2]) and unit shading normal (world frame, into `shading`) of mesh `mesh` at world
  /// point `p` [m] of unit face normal `n` (world frame).
  void shade(std::size_t mesh, const Eigen::Vector3f& p, const Eigen::Vector3f& n, float* albedo,
             Eigen::Vector3f& shading) const;

  /// shade() of n points of the textured mesh `mesh` at once, given in a frame A whose pose in the world is
  /// (`rotation`, `translation`) (a camera's): points px, py, pz [m] and unit face normals nx, ny, nz (frame A,
  /// replaced by the shading normals, frame A); albedo into albedo[c][0..n). `simd`: eight at a time where the CPU can
  /// (RockTexture::shadeManyFrom).
  void shadeMany(std::size_t mesh, const Eigen::Matrix3f& rotation, const Eigen::Vector3f& translation, int n,
                 const float* px, const float* py, const float* pz, float* nx, float* ny, float* nz,
                 float* const albedo[3], bool simd) const;

private:
  struct Mesh {
    Eigen::Array4f albedo;
    std::unique_ptr<RockTexture> texture;
    Eigen::Matrix3f to_mesh;  ///< rotation world -> mesh frame
    Eigen::Vector3f origin;   ///< the mesh frame's origin in the world [m]
  };
  std::vector<Mesh> meshes_;
  const sim::WorldConfig* config_;  ///< the world configuration they were built from
};

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin
