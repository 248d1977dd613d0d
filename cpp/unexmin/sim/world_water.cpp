#include <unexmin/sim/world_water.h>

namespace unexmin {
namespace sim {
namespace {

/// The map `node` (a world profile or a region: keys profile, interpolation, boundary) read into a checked profile.
water::Profile readProfile(const WorldReader& r, const YAML::Node& node, const std::string& where) {
  const std::string key = where + "profile";
  const YAML::Node rows = node["profile"];
  if (!rows.IsSequence())
    r.fail("'" + key + "' must be a list of rows {depth, temperature, conductivity or salinity, ph, ...}");
  water::Profile p;
  const std::string interp = r.text(node, "interpolation", where, "linear");
  if (interp != "linear" && interp != "layers")
    r.fail("'" + where + "interpolation' is '" + interp + "', expected linear|layers");
  p.layers = interp == "layers";
  const bool conductivity = rows.size() > 0 && rows[0].IsMap() && rows[0]["conductivity"];
  p.conductivity = conductivity;
  // a field given in one row is given in every row (else the default of WaterRow holds at every depth)
  const char* fields[] = {"temperature", "conductivity", "salinity", "ph", "redox", "oxygen", "turbidity"};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const YAML::Node row = rows[i];
    const std::string at = key + "[" + formatNumber(static_cast<double>(i)) + "].";
    if (!row.IsMap())
      r.fail("'" + at.substr(0, at.size() - 1) + "' must be a map {depth, temperature, ...}");
    for (const char* f : fields)
      if (static_cast<bool>(row[f]) != static_cast<bool>(rows[0][f]))
        r.fail("'" + at + f + "' " + (row[f] ? "given" : "missing") + ": a field is given in every row of '" + key +
               "' or in none (row 0 " + (rows[0][f] ? "gives" : "does not give") + " it)");
    if (row["conductivity"] && row["salinity"])
      r.fail("'" + at + "salinity' and '" + at + "conductivity' both given: give one of them (the other is derived)");
    water::WaterRow w;
    w.depth = r.number(row, "depth", at, 0.0, true);
    w.temperature = r.number(row, "temperature", at, w.temperature);
    w.conductivity = r.number(row, "conductivity", at, w.conductivity);
    w.salinity = r.number(row, "salinity", at, w.salinity);
    w.ph = r.number(row, "ph", at, w.ph);
    w.redox = r.number(row, "redox", at, w.redox);
    w.oxygen = r.number(row, "oxygen", at, w.oxygen);
    w.turbidity = r.number(row, "turbidity", at, w.turbidity);
    p.rows.push_back(w);
  }
  if (const YAML::Node b = node["boundary"]) {
    const std::string at = where + "boundary.";
    if (!b.IsMap())
      r.fail("'" + where + "boundary' must be a map of depth/amplitude/period/phase");
    p.boundary.enabled = true;
    p.boundary.depth = r.number(b, "depth", at, 0.0, true);
    p.boundary.amplitude = r.number(b, "amplitude", at, 0.0, true);
    p.boundary.period = r.number(b, "period", at, 0.0, true);
    p.boundary.phase = r.number(b, "phase", at, 0.0);
  }
  try {
    water::checkProfile(p, key);
  } catch (const ConfigError& e) {
    r.fail(e.what());
  }
  return p;
}

}  // namespace

std::shared_ptr<const water::WaterColumn> readWaterColumn(const WorldReader& r, const YAML::Node& water,
                                                          double surface_z, double gravity) {
  if (!water["profile"]) {
    for (const char* key : {"interpolation", "boundary", "regions"})
      if (water[key])
        r.fail(std::string("'water.") + key + "' given without 'water.profile': the profile it refines is missing");
    return nullptr;
  }
  if (water["density"])
    r.fail("'water.density' and 'water.profile' both given: the profile's water has its own density (EOS-80)");
  water::Profile profile = readProfile(r, water, "water.");
  std::vector<water::Region> regions;
  if (const YAML::Node list = water["regions"]) {
    if (!list.IsSequence())
      r.fail("'water.regions' must be a list of {min, max, profile}");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string where = "water.regions[" + formatNumber(static_cast<double>(i)) + "].";
      const YAML::Node reg = list[i];
      if (!reg.IsMap() || !reg["min"] || !reg["max"] || !reg["profile"])
        r.fail("'" + where.substr(0, where.size() - 1) + "' must be a map with min, max and profile");
      water::Region g;
      const Eigen::Vector3d lo = r.vec3(reg, "min", where, Eigen::Vector3d::Zero());
      const Eigen::Vector3d hi = r.vec3(reg, "max", where, Eigen::Vector3d::Zero());
      if ((hi.array() <= lo.array()).any())
        r.fail("'" + where + "max' must exceed '" + where + "min' on every axis");
      g.box = Eigen::AlignedBox3d(lo, hi);
      g.profile = readProfile(r, reg, where);
      regions.push_back(std::move(g));
    }
  }
  return std::make_shared<const water::WaterColumn>(std::move(profile), std::move(regions), surface_z, gravity);
}

}  // namespace sim
}  // namespace unexmin
