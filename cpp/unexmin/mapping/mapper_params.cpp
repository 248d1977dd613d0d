#include <unexmin/mapping/mapper_params.h>

#include <unexmin/core/error.h>

#include <cmath>
#include <string>

namespace unexmin {
namespace mapping {

namespace {

void check(const char* name, double value, bool ok, const std::string& expected) {
  if (!std::isfinite(value) || !ok) {
    throw ParameterError(std::string("mapper: parameter '") + name + "' = " + formatNumber(value) + ": expected " +
                         expected);
  }
}

}  // namespace

void MapperParams::validate() const {
  check("resolution", resolution, resolution >= 0.001 && resolution <= 10.0, "[0.001, 10] m");
  check("max_range", max_range, true, "a finite number of metres (<= 0: no limit)");
  check("prob_hit", prob_hit, prob_hit > 0.5 && prob_hit < 1.0, "(0.5, 1)");
  check("prob_miss", prob_miss, prob_miss > 0.0 && prob_miss < 0.5, "(0, 0.5)");
  check("clamp_min", clamp_min, clamp_min > 0.0 && clamp_min <= prob_miss,
        "(0, prob_miss = " + formatNumber(prob_miss) + "]");
  check("clamp_max", clamp_max, clamp_max >= prob_hit && clamp_max < 1.0,
        "[prob_hit = " + formatNumber(prob_hit) + ", 1)");
}

}  // namespace mapping
}  // namespace unexmin
