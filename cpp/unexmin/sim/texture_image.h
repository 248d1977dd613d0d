// An image texture of a world mesh (a material of kind `image`, docs/worlds.md): a PNG or JPEG file decoded once at
// start-up into 8-bit sRGB, sampled at texture coordinates (u, v) with bilinear filtering in linear light. Knows no
// ROS.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace unexmin {
namespace sim {

class TextureImage {
public:
  /// Decodes the PNG (any bit depth, palette, grey or alpha: converted to RGB, alpha dropped) or baseline/progressive
  /// JPEG at `path`, told apart by their first bytes. Throws ConfigError("<path>: ...") when the file cannot be read,
  /// is neither or is damaged.
  static TextureImage load(const std::string& path);
  /// An image of `width` x `height` texels from 8-bit sRGB `rgb` (3 per texel, rows top first); throws
  /// ConfigError on a size that does not match.
  TextureImage(int width, int height, std::vector<std::uint8_t> rgb);

  int width() const { return width_; }    ///< [texels]
  int height() const { return height_; }  ///< [texels]
  /// Linear RGB in [0, 1] (sRGB decoded) at texture coordinates (u, v): u from the left edge (0) to the right (1),
  /// v from the bottom row (0) to the top (1), as OBJ, PLY and assimp write them; repeated outside [0, 1). Bilinear
  /// between the four texels around the point, texel centres at ((i + 0.5) / width, 1 - (j + 0.5) / height).
  Eigen::Array3f sample(float u, float v) const;
  /// Linear value in [0, 1] of an 8-bit sRGB code (IEC 61966-2-1).
  static float linear(std::uint8_t code);

private:
  int width_ = 0, height_ = 0;
  std::vector<std::uint8_t> rgb_;
};

}  // namespace sim
}  // namespace unexmin
