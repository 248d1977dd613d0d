#include <unexmin/sensors/vision/water_optics.h>

#include <unexmin/core/error.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace sensors {
namespace vision {

Eigen::Vector3d WaterOptics::transmission(double range) const {
  const Eigen::Vector3d cc = c();
  return Eigen::Vector3d(std::exp(-cc.x() * range), std::exp(-cc.y() * range), std::exp(-cc.z() * range));
}

double WaterOptics::phase(double cos_psi) const {
  const double d = 1.0 + g * g - 2.0 * g * cos_psi;
  return (1.0 - g * g) / (4.0 * M_PI * d * std::sqrt(d));
}

WaterOptics WaterOptics::fromVisibility(const std::string& level, const Eigen::Vector3d& colour) {
  double a_green = 0.0, b = 0.0;
  if (level == "none")
    a_green = 0.114, b = 0.037;
  else if (level == "low")
    a_green = 0.179, b = 0.219;
  else if (level == "medium")
    a_green = 0.300, b = 0.900;
  else if (level == "high")
    a_green = 0.600, b = 3.400;
  else
    throw ConfigError("visibility level '" + level + "': expected none|low|medium|high");
  for (int k = 0; k < 3; ++k)
    if (!(colour[k] > 0.0 && colour[k] <= 1.0))
      throw ConfigError("visibility colour (" + formatNumber(colour.x()) + ", " + formatNumber(colour.y()) + ", " +
                        formatNumber(colour.z()) + "): expected three numbers in (0, 1]");
  WaterOptics w;
  for (int k = 0; k < 3; ++k)
    w.a[k] = a_green * colour.y() / colour[k];
  w.b = Eigen::Vector3d::Constant(b);
  return w;
}

WaterOptics WaterOptics::fromTurbidity(double ntu, const Eigen::Vector3d& colour) {
  if (!(ntu >= 0.0) || !std::isfinite(ntu))
    throw ConfigError("turbidity " + formatNumber(ntu) + " NTU: expected a finite number >= 0");
  const WaterOptics clear = fromVisibility("none", colour);
  const double a_green = clear.a.y() + 0.1 * ntu;  // assumed per NTU (water_optics.h)
  WaterOptics w;
  for (int k = 0; k < 3; ++k)
    w.a[k] = a_green * colour.y() / colour[k];
  w.b = clear.b + Eigen::Vector3d::Constant(0.6 * ntu);
  return w;
}

WaterOptics WaterOptics::fromWorld(const sim::WorldConfig& config, double turbidity) {
  if (config.visibility == "water")
    return fromTurbidity(std::max(0.0, turbidity), config.visibility_colour);
  return fromVisibility(config.visibility, config.visibility_colour);
}

double opticalTurbidity(const sim::WorldConfig& config, const Eigen::Vector3d& p, double time) {
  if (config.visibility != "water")
    return -1.0;
  if (!config.water_column)
    throw ConfigError(config.file + ": 'visibility.level' is 'water': expected a 'water.profile'");
  const double t = config.water_column->at(p, time).turbidity;
  if (t < 0.01)
    return 0.0;
  const double step = std::log(1.02);
  return std::max(0.01, std::round(std::exp(std::round(std::log(t) / step) * step) * 100.0) / 100.0);
}

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin
