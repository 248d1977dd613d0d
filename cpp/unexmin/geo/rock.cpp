#include <unexmin/geo/rock.h>

#include <unexmin/core/error.h>

#include <cmath>

namespace unexmin {
namespace geo {

Eigen::Vector3d Rock::fluorescenceAt(double excitation_nm) const {
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  for (const auto& f : fluorescence)
    if (f.excitedBy(excitation_nm))
      out += f.yield * f.emission;
  return out;
}

Rock mixRock(const MineralTable& table, const std::vector<Component>& components, const std::string& where) {
  if (components.empty())
    throw ConfigError("'" + where + "' is empty: expected a list of {mineral, fraction} summing to 1");
  Rock r;
  r.components = components;
  double sum = 0.0, mass = 0.0, k = 0.0, u = 0.0, th = 0.0;
  for (std::size_t i = 0; i < components.size(); ++i) {
    const Component& c = components[i];
    const std::string at = where + "[" + formatNumber(static_cast<double>(i)) + "].";
    const Mineral* m = table.find(c.mineral);
    if (!m) {
      std::string known;
      for (const auto& n : table.names())
        known += (known.empty() ? "" : ", ") + n;
      throw ConfigError("'" + at + "mineral' = '" + c.mineral + "': not in the mineral table " + table.file() + " (" +
                        known + ")");
    }
    if (!(c.fraction > 0.0 && c.fraction <= 1.0))
      throw ConfigError("'" + at + "fraction' = " + formatNumber(c.fraction) +
                        ": expected a volume fraction in (0, 1]");
    for (std::size_t j = 0; j < i; ++j)
      if (components[j].mineral == c.mineral)
        throw ConfigError("'" + at + "mineral' = '" + c.mineral + "' is listed twice in '" + where + "'");
    sum += c.fraction;
    r.density += c.fraction * m->density;
    r.susceptibility += c.fraction * m->susceptibility;
    r.remanence += c.fraction * m->remanence;
    const double w = c.fraction * m->density;
    mass += w;
    k += w * m->potassium;
    u += w * m->uranium;
    th += w * m->thorium;
    r.reflectance.addScaled(m->reflectance, c.fraction);
    if (m->fluorescence.yield > 0.0) {
      Fluorescence f = m->fluorescence;
      f.yield *= c.fraction;
      r.fluorescence.push_back(f);
    }
  }
  if (std::abs(sum - 1.0) > 1e-6)
    throw ConfigError("'" + where + "' fractions sum to " + formatNumber(sum) + ": expected 1 (within 1e-6)");
  r.potassium = k / mass;
  r.uranium = u / mass;
  r.thorium = th / mass;
  r.albedo = r.reflectance.rgb();
  return r;
}

}  // namespace geo
}  // namespace unexmin
