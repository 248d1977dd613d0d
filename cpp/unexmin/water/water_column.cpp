#include <unexmin/water/water_column.h>

#include <unexmin/core/error.h>
#include <unexmin/water/seawater.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace unexmin {
namespace water {
namespace {

/// The rows' fields interpolated at rest depth z (linear, or the layer's row).
WaterRow interpolate(const Profile& p, double z) {
  const auto& rows = p.rows;
  if (z <= rows.front().depth)
    return rows.front();
  if (z >= rows.back().depth)
    return rows.back();
  // first row deeper than z: rows[k-1].depth <= z < rows[k].depth (of two rows at one depth, the deeper holds)
  const auto it =
      std::upper_bound(rows.begin(), rows.end(), z, [](double d, const WaterRow& r) { return d < r.depth; });
  const WaterRow& a = *(it - 1);
  if (p.layers)
    return a;
  const WaterRow& b = *it;
  const double w = (z - a.depth) / (b.depth - a.depth);
  auto mix = [w](double x, double y) { return x + w * (y - x); };
  WaterRow r;
  r.depth = z;
  r.temperature = mix(a.temperature, b.temperature);
  r.salinity = mix(a.salinity, b.salinity);
  r.conductivity = mix(a.conductivity, b.conductivity);
  r.ph = mix(a.ph, b.ph);
  r.redox = mix(a.redox, b.redox);
  r.oxygen = mix(a.oxygen, b.oxygen);
  r.turbidity = mix(a.turbidity, b.turbidity);
  return r;
}

[[noreturn]] void fail(const std::string& key, double value, const std::string& expected) {
  throw ConfigError("'" + key + "' = " + formatNumber(value) + ": expected " + expected);
}

void checkRange(const std::string& key, double value, double lo, double hi, const std::string& unit) {
  if (!(value >= lo && value <= hi))
    fail(key, value, "[" + formatNumber(lo) + ", " + formatNumber(hi) + "]" + (unit.empty() ? "" : " " + unit));
}

}  // namespace

void checkProfile(const Profile& p, const std::string& where) {
  if (p.rows.empty())
    throw ConfigError("'" + where + "' is empty: expected a list of rows {depth, temperature, ...}");
  for (std::size_t i = 0; i < p.rows.size(); ++i) {
    const WaterRow& r = p.rows[i];
    const std::string at = where + "[" + formatNumber(static_cast<double>(i)) + "].";
    if (!(r.depth >= 0.0 && std::isfinite(r.depth)))
      fail(at + "depth", r.depth, "a depth >= 0 m below the free surface");
    if (i > 0 && r.depth < p.rows[i - 1].depth)
      fail(at + "depth", r.depth,
           "rows sorted by depth: it is above the row before it (" + formatNumber(p.rows[i - 1].depth) + " m)");
    if (i > 1 && r.depth == p.rows[i - 2].depth)
      fail(at + "depth", r.depth, "at most two rows at one depth (a step)");
    checkRange(at + "temperature", r.temperature, 0.0, 40.0, "degC (the range of EOS-80 and Chen & Millero)");
    if (p.conductivity)
      checkRange(at + "conductivity", r.conductivity, 0.0, 1.2e5, "uS/cm (not negative)");
    else
      checkRange(at + "salinity", r.salinity, 0.0, 42.0, "PSU (not negative)");
    checkRange(at + "ph", r.ph, 0.0, 14.0, "");
    checkRange(at + "redox", r.redox, -1000.0, 1000.0, "mV");
    checkRange(at + "oxygen", r.oxygen, 0.0, 100.0, "mg/L (not negative)");
    checkRange(at + "turbidity", r.turbidity, 0.0, 1e5, "NTU (not negative)");
  }
  const Boundary& b = p.boundary;
  if (!b.enabled)
    return;
  const double bottom = p.rows.back().depth;
  const std::string at = where.substr(0, where.rfind('.') + 1) + "boundary.";
  if (!(b.depth > 0.0 && b.depth < bottom))
    fail(at + "depth", b.depth, "a depth inside the profile, in (0, " + formatNumber(bottom) + ") m");
  if (!(std::abs(b.amplitude) < std::min(b.depth, bottom - b.depth)))
    fail(at + "amplitude", b.amplitude,
         "|amplitude| < " + formatNumber(std::min(b.depth, bottom - b.depth)) +
             " m (the boundary stays between the surface and the profile's last row)");
  if (!(b.period > 0.0 && std::isfinite(b.period)))
    fail(at + "period", b.period, "> 0 s");
  if (!std::isfinite(b.phase))
    fail(at + "phase", b.phase, "a finite angle [rad]");
}

WaterColumn::WaterColumn(Profile profile, std::vector<Region> regions, double surface_z, double gravity)
    : profile_(std::move(profile)), regions_(std::move(regions)), surface_z_(surface_z), gravity_(gravity) {}

const Profile& WaterColumn::profileAt(const Eigen::Vector3d& point) const {
  for (auto it = regions_.rbegin(); it != regions_.rend(); ++it)
    if (it->box.contains(point))
      return it->profile;
  return profile_;
}

double WaterColumn::restDepth(const Profile& p, double depth, double time) {
  const Boundary& b = p.boundary;
  if (!b.enabled)
    return depth;
  const double bottom = p.rows.back().depth;
  if (depth <= 0.0 || depth >= bottom)
    return depth;
  const double moved = b.depth + b.amplitude * std::sin(2.0 * M_PI * time / b.period + b.phase);
  // z = z0 + d(z0), d linear from 0 at the surface to the boundary's displacement at its rest depth, then to 0
  // at the last row: the inverse is linear on each side of the moved boundary
  if (depth <= moved)
    return depth * b.depth / moved;
  return b.depth + (depth - moved) * (bottom - b.depth) / (bottom - moved);
}

WaterSample WaterColumn::at(const Eigen::Vector3d& point, double time) const {
  const Profile& p = profileAt(point);
  WaterSample s;
  s.depth = std::max(0.0, surface_z_ - point.z());
  s.pressure = 1e-4 * 1000.0 * gravity_ * s.depth;
  const WaterRow r = interpolate(p, restDepth(p, s.depth, time));
  s.temperature = r.temperature;
  if (p.conductivity) {
    s.conductivity = r.conductivity;
    s.salinity = practicalSalinity(r.conductivity, r.temperature, s.pressure);
  } else {
    s.salinity = r.salinity;
    s.conductivity = conductivityFromSalinity(r.salinity, r.temperature, s.pressure);
  }
  s.ph = r.ph;
  s.redox = r.redox;
  s.oxygen = r.oxygen;
  s.turbidity = r.turbidity;
  s.density = density(s.salinity, s.temperature, s.pressure);
  s.sound_speed = soundSpeed(s.salinity, s.temperature, s.pressure);
  return s;
}

}  // namespace water
}  // namespace unexmin

namespace unexmin {
namespace water {

Eigen::Vector3d WaterColumn::stp(const Eigen::Vector3d& point, double time) const {
  const Profile& p = profileAt(point);
  const double depth = std::max(0.0, surface_z_ - point.z());
  const double pressure = 1e-4 * 1000.0 * gravity_ * depth;
  const WaterRow r = interpolate(p, restDepth(p, depth, time));
  const double s = p.conductivity ? practicalSalinity(r.conductivity, r.temperature, pressure) : r.salinity;
  return Eigen::Vector3d(s, r.temperature, pressure);
}

double WaterColumn::densityIn(const Profile& p, double depth, double time) const {
  const double pressure = 1e-4 * 1000.0 * gravity_ * depth;
  const WaterRow r = interpolate(p, restDepth(p, depth, time));
  const double s = p.conductivity ? practicalSalinity(r.conductivity, r.temperature, pressure) : r.salinity;
  return density(s, r.temperature, pressure);
}

double WaterColumn::hydrostaticPressure(const Eigen::Vector3d& point, double time) const {
  const double bottom = surface_z_ - point.z();  // [m] depth of the point
  if (!(bottom > 0.0))
    return 0.0;
  // Where the profile changes along the vertical: the faces of the regions whose footprint holds x, y.
  std::vector<double> cuts{0.0, bottom};
  for (const Region& region : regions_) {
    const Eigen::Vector3d& lo = region.box.min();
    const Eigen::Vector3d& hi = region.box.max();
    if (point.x() < lo.x() || point.x() > hi.x() || point.y() < lo.y() || point.y() > hi.y())
      continue;
    for (const double z : {lo.z(), hi.z()}) {
      const double d = surface_z_ - z;
      if (d > 0.0 && d < bottom)
        cuts.push_back(d);
    }
  }
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());

  // 3-point Gauss-Legendre on [-1, 1]: exact for polynomials up to degree 5.
  constexpr double kNode = 0.77459666924148337704;  // sqrt(3/5)
  constexpr double kOuter = 5.0 / 9.0, kInner = 8.0 / 9.0;
  double weight = 0.0;  // integral of the density [kg/m^2]
  std::vector<double> pieces;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double a = cuts[i], b = cuts[i + 1];
    const Eigen::Vector3d middle(point.x(), point.y(), surface_z_ - 0.5 * (a + b));
    const Profile& p = profileAt(middle);
    // where the profile's rows (and its boundary) are now: the density's kinks and steps
    pieces.assign({a, b});
    const Boundary& heave = p.boundary;
    const double last = p.rows.back().depth;
    const double moved =
        heave.enabled ? heave.depth + heave.amplitude * std::sin(2.0 * M_PI * time / heave.period + heave.phase) : 0.0;
    auto now = [&](double rest) {  // restDepth() inverted
      if (!heave.enabled || rest <= 0.0 || rest >= last)
        return rest;
      if (rest <= heave.depth)
        return rest * moved / heave.depth;
      return moved + (rest - heave.depth) * (last - moved) / (last - heave.depth);
    };
    for (const WaterRow& r : p.rows) {
      const double d = now(r.depth);
      if (d > a && d < b)
        pieces.push_back(d);
    }
    if (heave.enabled && moved > a && moved < b)
      pieces.push_back(moved);
    std::sort(pieces.begin(), pieces.end());
    for (std::size_t k = 0; k + 1 < pieces.size(); ++k) {
      const double c = 0.5 * (pieces[k] + pieces[k + 1]), h = 0.5 * (pieces[k + 1] - pieces[k]);
      if (!(h > 0.0))
        continue;
      weight += h * (kOuter * densityIn(p, c - kNode * h, time) + kInner * densityIn(p, c, time) +
                     kOuter * densityIn(p, c + kNode * h, time));
    }
  }
  return gravity_ * weight;
}

double WaterColumn::densityAt(const Eigen::Vector3d& point, double time) const {
  const Eigen::Vector3d x = stp(point, time);
  return density(x[0], x[1], x[2]);
}

double WaterColumn::soundSpeedAt(const Eigen::Vector3d& point, double time) const {
  const Eigen::Vector3d x = stp(point, time);
  return soundSpeed(x[0], x[1], x[2]);
}

}  // namespace water
}  // namespace unexmin
