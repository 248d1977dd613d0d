// The ray caster's unit of work, in a header of its own with no other include (no Eigen): code compiled with
// other instruction sets, such as the camera's AVX2 shading kernels, sizes its arrays by it.
#pragma once

#include <cstddef>

namespace unexmin {
namespace raycast {

/// Rays per work block of RayCaster::cast(): blocks start at multiples of it whatever the thread count, so every
/// ray is cast in the same packet with the same neighbours and results are identical for any number of threads.
/// The camera casts, shades and encodes one tile of 8 x 8 pixels as one block.
constexpr std::size_t kBlock = 64;

}  // namespace raycast
}  // namespace unexmin
