// The AVX2 + FMA builds of the shading kernels (compiled with -mavx2 -mfma, see CMakeLists.txt; called only on
// CPUs that have both, see ImageFormation::radiance). Nothing else lives here: any function of this file may use
// AVX2 instructions.
#include <unexmin/sensors/vision/shading_kernels.h>

namespace unexmin {
namespace sensors {
namespace vision {
namespace shading {

#if defined(__AVX2__) && defined(__FMA__)
void directAvx2(const Pixels& p, const Light* lights, int count, const Tables& t)
{
  direct<lanes::F8>(p, lights, count, t);
}
void backscatterAvx2(const Pixels& p, const Backscatter& b) { backscatter<lanes::F8>(p, b); }
void sensorAvx2(const Sensor& s, int n, float* const radiance[3], const std::int32_t* const noise[3],
                std::int32_t* const code[3])
{
  sensor<lanes::F8>(s, n, radiance, noise, code);
}
bool avx2Built() { return true; }
#else
// Not an x86-64 build with AVX2: the one-lane kernels, never called (avx2Built() is false).
void directAvx2(const Pixels& p, const Light* lights, int count, const Tables& t)
{
  direct<lanes::F1>(p, lights, count, t);
}
void backscatterAvx2(const Pixels& p, const Backscatter& b) { backscatter<lanes::F1>(p, b); }
void sensorAvx2(const Sensor& s, int n, float* const radiance[3], const std::int32_t* const noise[3],
                std::int32_t* const code[3])
{
  sensor<lanes::F1>(s, n, radiance, noise, code);
}
bool avx2Built() { return false; }
#endif

}  // namespace shading
}  // namespace vision
}  // namespace sensors
}  // namespace unexmin
