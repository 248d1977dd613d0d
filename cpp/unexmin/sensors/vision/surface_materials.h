// The materials of a world's meshes as the cameras and the SLS lasers see them: per mesh of the world file, its
// RockTexture (textured kinds) and the mesh frame, so that a hit point in the world frame gives the albedo and the
// shading normal there (docs/vision.md "Materials"). A plain mesh gives its one albedo and the face's normal, a
// checkerboard its square's albedo and the face's normal. Where the world has a geology, a rock-kind mesh takes its
// colour from the rock behind the wall at each point (the texture's pattern about that rock's albedo instead of the
// material's), so a vein reads as a vein and a malachite stain as green.
// Knows no ROS.
#pragma once

#include <unexmin/raycast/ray_caster.h>
#include <unexmin/sensors/vision/rock_texture.h>
#include <unexmin/sim/world.h>

#include <Eigen/Geometry>

#include <memory>
#include <vector>

namespace unexmin {
namespace sensors {
namespace vision {

class SurfaceMaterials {
public:
  /// Albedo (R, G, B) of a robot hull as the cameras and the SLS lasers see it [assumed: the UX-1's yellow paint,
  /// urdf hull_rgba].
  static const Eigen::Vector3d kHullAlbedo;

  /// One entry per mesh of `config` (the index of a raycast::Hit of kind mesh). Throws ConfigError naming the key of
  /// a material of kind image or vertex_colours: those need the world's meshes (the constructor below).
  explicit SurfaceMaterials(const sim::WorldConfig& config);
  /// The same for the world's configuration, with the image textures and vertex colours of its meshes (the world
  /// must outlive the materials).
  explicit SurfaceMaterials(const sim::World& world);

  /// The materials of `config` held by `cache`: built on first use and again for another world configuration.
  static const SurfaceMaterials& of(const sim::WorldConfig& config, std::unique_ptr<SurfaceMaterials>& cache);
  /// The same for `world`, with its image textures and vertex colours.
  static const SurfaceMaterials& of(const sim::World& world, std::unique_ptr<SurfaceMaterials>& cache);

  std::size_t size() const { return meshes_.size(); }
  /// Whether mesh `mesh` has a texture or a checkerboard (else its albedo is one number per channel and its normal
  /// the face's).
  bool textured(std::size_t mesh) const {
    return meshes_.at(mesh).texture != nullptr || meshes_[mesh].board != nullptr;
  }
  /// The mesh's mean albedo (R, G, B, 0) [-].
  const Eigen::Array4f& meanAlbedo(std::size_t mesh) const { return meshes_[mesh].albedo; }
  /// Whether mesh `mesh` takes its colour from the world's geology (a rock-kind mesh of a world with a geology).
  bool geological(std::size_t mesh) const { return !meshes_.at(mesh).tint.empty(); }
  /// Albedo (R, G, B) of mesh `mesh` at world point `p` [m] (its mean where it is mapped: albedo(hit, p) below).
  Eigen::Array3f albedo(std::size_t mesh, const Eigen::Vector3f& p) const;
  /// Albedo (R, G, B) at `hit`, a hit of kind mesh at world point `p` [m]: from its triangle and barycentric
  /// coordinates where the mesh is mapped, else as albedo(mesh, p).
  Eigen::Array3f albedo(const raycast::Hit& hit, const Eigen::Vector3f& p) const;
  /// Whether mesh `mesh`'s albedo comes from its image texture or vertex colours at each hit (mappedAlbedo()).
  bool mapped(std::size_t mesh) const { return meshes_[mesh].data != nullptr; }
  /// Albedo (R, G, B) into out[0..2] of the mapped mesh hit by `hit` (Hit::primitive, u, v): the image texture at the
  /// interpolated texture coordinates (bilinear), or the interpolated vertex colours, times the material's albedo
  /// (docs/vision.md "Materials"). Returns `out`.
  const float* mappedAlbedo(const raycast::Hit& hit, float* out) const;
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
    std::unique_ptr<sim::Material> board;      ///< a checkerboard (sim::checkerboardAlbedo; no relief)
    Eigen::Matrix3f to_mesh;                   ///< rotation world -> mesh frame
    Eigen::Vector3f origin;                    ///< the mesh frame's origin in the world [m]
    const sim::TriangleMesh* data = nullptr;   ///< mapped: the mesh's texture coordinates or vertex colours
    const sim::TextureImage* image = nullptr;  ///< kind image: its texture
    /// Per geology body id (0: the host), the rock's albedo over the material's, per channel: the factor that turns
    /// the texture's albedo about the material's mean into one about the rock's. Empty: not from the geology.
    std::vector<Eigen::Array3f> tint;
  };
  /// The tint of mesh `m` at world point `p` (1 where it has none).
  Eigen::Array3f tintAt(const Mesh& m, const Eigen::Vector3f& p) const;
  SurfaceMaterials(const sim::WorldConfig& config, const sim::World* world);
  std::vector<Mesh> meshes_;
  const sim::WorldConfig* config_;  ///< the world configuration they were built from
  const sim::World* world_;         ///< the world they were built from (null: from a configuration alone)
};

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin
