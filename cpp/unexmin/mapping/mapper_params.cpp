#include <unexmin/mapping/mapper_params.h>

#include <unexmin/core/error.h>

#include <cmath>
#include <string>
#include <utility>

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

void MapperSources::resolve(double max_range) {
  const bool limited = max_range > 0.0;
  const std::string expected =
      limited ? "(0, max_range = " + formatNumber(max_range) + "] m" : "a finite number of m (<= 0: no limit)";
  const std::pair<const char*, double*> ranges[] = {{"m3_max_range", &m3_max_range},
                                                    {"sls_max_range", &sls_max_range},
                                                    {"sonar_max_range", &sonar_max_range},
                                                    {"dvl_max_range", &dvl_max_range}};
  for (const auto& [name, range] : ranges) {
    if (std::isnan(*range))
      *range = max_range;
    // A source's range may only be shorter than max_range (its rays carve no farther than max_range anyway).
    check(name, *range, !limited || (*range > 0.0 && *range <= max_range), expected);
  }
  check("sls_units", sls_units, sls_units >= 0 && sls_units <= 16, "0..16");
  if (sonar && (sonar_topic.empty() || sonar_topic[0] == '/'))
    throw ParameterError("mapper: parameter 'sonar_topic' = '" + sonar_topic +
                         "': expected a topic relative to /<robot>/ (e.g. imaging_sonar/points)");
}

}  // namespace mapping
}  // namespace unexmin
