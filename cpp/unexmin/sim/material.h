// The material of a world mesh as the world file gives it (key `material:` of a mesh, docs/worlds.md): a mean
// diffuse albedo per channel and, for the textured kinds, the parameters of a procedural solid texture evaluated at
// the hit point in the mesh's frame (sensors/vision/rock_texture.h holds the model). Knows no ROS.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace unexmin {
namespace sim {

struct Material {
  /// plain (one albedo, no texture) | rock | painted | rusty (materialKinds()): a kind is a set of defaults and of
  /// weights of the texture's components; checkerboard: a calibration target (square, rows, columns, dark, border).
  /// image | vertex_colours: the albedo is the mesh's image texture at the hit's texture coordinates, or its vertex
  /// colours interpolated at the hit, times `albedo`.
  std::string kind = "plain";
  /// Mean diffuse (Lambertian) reflectance per RGB channel, in [0, 1]: the texture modulates around it.
  Eigen::Vector3d albedo{0.3, 0.3, 0.3};
  std::uint64_t seed = 0;  ///< seed of the texture's hash (>= 0)
  double contrast = 0.0;   ///< [-] in [0, 1]: standard deviation of albedo / mean albedo (before clipping to [0, 1])
  double relief = 0.0;     ///< [-] >= 0: slope of the shading normal per unit slope of the texture's height field
  double grain = 0.0;      ///< [m] >= 0 (0: off): size of the grains
  double cracks = 0.0;     ///< [m] >= 0 (0: off): spacing of the cracks (thin dark lines)
  double strata = 0.0;     ///< [m] >= 0 (0: off): thickness of the strata bands (along the mesh frame's z)
  double stains = 0.0;     ///< [m] >= 0 (0: off): size of the stains
  double region = 0.0;     ///< [m] >= 0 (0: off): size of the regions of another hue (levels, chambers)
  double tint = 0.0;       ///< [-] in [0, 1]: relative change of a channel's albedo between regions (its std)
  /// Weights of grain, cracks, strata and stains in the texture [-], set by the kind (not a world-file key).
  Eigen::Vector4d weights{0, 0, 0, 0};
  // Checkerboard (kind checkerboard): rows x columns squares in the mesh frame's x-y plane, centred on its origin;
  // the square at the most negative x and y is dark. `albedo` is the light squares' and the border's.
  double square = 0.0;            ///< [m] > 0: side of a square
  int rows = 0;                   ///< squares along the mesh frame's y (inner corners: rows - 1)
  int columns = 0;                ///< squares along the mesh frame's x (inner corners: columns - 1)
  Eigen::Vector3d dark{0, 0, 0};  ///< albedo of the dark squares and of the plate beyond the border, in [0, 1]
  double border = 0.0;            ///< [m] >= 0: width of the light margin around the squares

  /// The image texture of kind `image`: the PNG or JPEG file, resolved against the world file's folder [path].
  std::string image;

  /// A procedural texture evaluated at the hit (rock, painted, rusty, checkerboard).
  bool textured() const { return kind != "plain" && !mapped(); }
  bool checkerboard() const { return kind == "checkerboard"; }
  /// The albedo comes from the mesh's own data at the hit (image texture or vertex colours).
  bool mapped() const { return kind == "image" || kind == "vertex_colours"; }
};

/// The material kinds a world file can name.
const std::vector<std::string>& materialKinds();

/// The defaults of material kind `kind` (albedo, contrast, relief, scales; a checkerboard's squares) [docs/worlds.md];
/// throws ParameterError "'<prefix>kind' = '<kind>': expected plain|rock|painted|rusty|checkerboard|image|
/// vertex_colours" for any other name.
Material materialDefaults(const std::string& kind, const std::string& prefix = "");

/// Checks every value of `m`; throws ParameterError "'<prefix><key>' = <value>: expected <range>" naming the first
/// bad key (unknown kind, albedo outside [0, 1], negative or non-finite scale, contrast or tint outside [0, 1],
/// negative relief; a checkerboard's square, rows, columns, dark or border out of range, or a rock key on it; kind
/// image without an image file or an image file with another kind).
void checkMaterial(const Material& m, const std::string& prefix = "");

/// Albedo (R, G, B) of checkerboard `m` at point `p` of the mesh frame [m].
Eigen::Vector3f checkerboardAlbedo(const Material& m, const Eigen::Vector3f& p);

}  // namespace sim
}  // namespace unexmin
