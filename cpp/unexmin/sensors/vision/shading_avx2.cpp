// The AVX2 + FMA builds of the shading kernels (compiled with -mavx2 -mfma, see CMakeLists.txt; called only on
// CPUs that have both, see ImageFormation::radiance). Nothing else lives here: any function of this file may use
// AVX2 instructions.
#include <unexmin/sensors/vision/shading_kernels.h>

namespace unexmin {
namespace sensors {
namespace vision {
namespace shading {

#if defined(__AVX2__) && defined(__FMA__)
using Lanes = lanes::F8;
constexpr bool kBuilt = true;
#else
using Lanes = lanes::F1;  // not an x86-64 build with AVX2: one lane, never called (avx2Built() is false)
constexpr bool kBuilt = false;
#endif

void directAvx2(Pixels& p, int n, const Light* lights, int count, const Tables& t) {
  direct<Lanes>(p, n, lights, count, t);
}
void backscatterAvx2(Pixels& p, int n, const Backscatter& b) {
  backscatter<Lanes>(p, n, b);
}
void sensorResponseAvx2(const SensorResponse& s, int n, float* const radiance[3], const std::int32_t* const noise[3],
                        std::int32_t* const code[3]) {
  sensorResponse<Lanes>(s, n, radiance, noise, code);
}
bool avx2Built() {
  return kBuilt;
}

}  // namespace shading
}  // namespace vision
}  // namespace sensors
}  // namespace unexmin
