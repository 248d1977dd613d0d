#include <unexmin/geo/mineral_table.h>

#include <unexmin/core/error.h>

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace geo {
namespace {

class TableReader {
public:
  explicit TableReader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& what) const { throw ConfigError(file_ + ": " + what); }

  double number(const YAML::Node& node, const std::string& key, double lo, double hi, const std::string& unit) const {
    const YAML::Node v = node[leaf(key)];
    if (!v)
      fail("missing '" + key + "' (a number" + (unit.empty() ? "" : " [" + unit + "]") + ")");
    double x = NAN;
    try {
      x = v.as<double>();
    } catch (const YAML::Exception&) {
      fail("'" + key + "' must be a number");
    }
    if (!(x >= lo && x <= hi))
      fail("'" + key + "' = " + formatNumber(x) + ": expected [" + formatNumber(lo) + ", " + formatNumber(hi) + "]" +
           (unit.empty() ? "" : " " + unit));
    return x;
  }

  std::vector<double> numbers(const YAML::Node& node, const std::string& key, std::size_t size, double lo,
                              double hi) const {
    const YAML::Node v = node[leaf(key)];
    if (!v || !v.IsSequence() || (size > 0 && v.size() != size) || v.size() < 1)
      fail("'" + key + "' must be a list of " + (size > 0 ? formatNumber(static_cast<double>(size)) : "1 or more") +
           " numbers");
    std::vector<double> out;
    for (std::size_t i = 0; i < v.size(); ++i) {
      double x = NAN;
      try {
        x = v[i].as<double>();
      } catch (const YAML::Exception&) {
      }
      if (!(x >= lo && x <= hi))
        fail("'" + key + "[" + formatNumber(static_cast<double>(i)) + "]' must be a number in [" + formatNumber(lo) +
             ", " + formatNumber(hi) + "]");
      out.push_back(x);
    }
    return out;
  }

  void onlyKeys(const YAML::Node& node, const std::string& where, const std::vector<std::string>& accepted) const {
    if (!node.IsMap())
      fail("'" + where + "' must be a map");
    std::string list;
    for (const auto& a : accepted)
      list += (list.empty() ? "" : ", ") + a;
    for (const auto& kv : node) {
      const std::string key = kv.first.Scalar();
      if (std::find(accepted.begin(), accepted.end(), key) == accepted.end())
        fail("unknown key '" + where + "." + key + "' (accepted: " + list + ")");
    }
  }

private:
  static std::string leaf(const std::string& key) { return key.substr(key.rfind('.') + 1); }
  std::string file_;
};

Spectrum readSpectrum(const TableReader& r, const YAML::Node& node, const std::string& key) {
  r.onlyKeys(node, key, {"nm", "value"});
  const std::vector<double> nm = r.numbers(node, key + ".nm", 0, Spectrum::kFirst, Spectrum::kLast);
  const std::vector<double> value = r.numbers(node, key + ".value", nm.size(), 0.0, 1.0);
  for (std::size_t i = 1; i < nm.size(); ++i)
    if (nm[i] <= nm[i - 1])
      r.fail("'" + key + ".nm' must be strictly increasing (" + formatNumber(nm[i]) + " after " +
             formatNumber(nm[i - 1]) + ")");
  return Spectrum::fromKnots(nm, value);
}

Fluorescence readFluorescence(const TableReader& r, const YAML::Node& node, const std::string& key) {
  r.onlyKeys(node, key, {"excitation", "emission", "yield"});
  Fluorescence f;
  const std::vector<double> band = r.numbers(node, key + ".excitation", 2, 200.0, 700.0);
  if (band[1] <= band[0])
    r.fail("'" + key + ".excitation' must be [shortest, longest] nm, shortest first");
  f.excitation_min = band[0];
  f.excitation_max = band[1];
  const std::vector<double> rgb = r.numbers(node, key + ".emission", 3, 0.0, 1.0);
  f.emission = Eigen::Vector3d(rgb[0], rgb[1], rgb[2]);
  if (std::abs(f.emission.maxCoeff() - 1.0) > 1e-9)
    r.fail("'" + key + ".emission' must be an RGB colour whose largest channel is 1 (the yield sets the strength)");
  f.yield = r.number(node, key + ".yield", 0.0, 1.0, "");
  return f;
}

}  // namespace

MineralTable MineralTable::load(const std::string& file) {
  TableReader r(file);
  YAML::Node root;
  try {
    root = YAML::LoadFile(file);
  } catch (const YAML::BadFile&) {
    r.fail("cannot open the mineral table");
  } catch (const YAML::Exception& e) {
    r.fail(std::string("not valid YAML: ") + e.what());
  }
  r.onlyKeys(root, "(top)", {"references", "minerals"});
  const YAML::Node refs = root["references"];
  if (!refs || !refs.IsMap())
    r.fail("missing 'references' (a map of source keys to citations)");
  const YAML::Node minerals = root["minerals"];
  if (!minerals || !minerals.IsMap() || minerals.size() == 0)
    r.fail("missing 'minerals' (a map of mineral names to their properties)");
  MineralTable t;
  t.file_ = file;
  const std::vector<std::string> required = {"density", "susceptibility", "potassium",
                                             "uranium", "thorium",        "reflectance"};
  for (const auto& kv : minerals) {
    const std::string name = kv.first.Scalar();
    const std::string at = "minerals." + name;
    const YAML::Node m = kv.second;
    r.onlyKeys(m, at,
               {"density", "susceptibility", "remanence", "potassium", "uranium", "thorium", "reflectance",
                "fluorescence", "sources"});
    Mineral x;
    x.name = name;
    x.density = r.number(m, at + ".density", 500.0, 25000.0, "kg/m^3");
    x.susceptibility = r.number(m, at + ".susceptibility", -1e-3, 100.0, "SI");
    if (m["remanence"])
      x.remanence = r.number(m, at + ".remanence", 0.0, 1e6, "A/m");
    x.potassium = r.number(m, at + ".potassium", 0.0, 100.0, "%");
    x.uranium = r.number(m, at + ".uranium", 0.0, 1e6, "ppm");
    x.thorium = r.number(m, at + ".thorium", 0.0, 1e6, "ppm");
    if (!m["reflectance"])
      r.fail("missing '" + at + ".reflectance' (a map of nm and value lists)");
    x.reflectance = readSpectrum(r, m["reflectance"], at + ".reflectance");
    if (m["fluorescence"])
      x.fluorescence = readFluorescence(r, m["fluorescence"], at + ".fluorescence");
    // every value given has a source: a key of `references` or the word "assumed"
    const YAML::Node sources = m["sources"];
    if (!sources || !sources.IsMap())
      r.fail("missing '" + at + ".sources' (the source of every value: a key of 'references' or assumed)");
    std::vector<std::string> given = required;
    for (const char* opt : {"remanence", "fluorescence"})
      if (m[opt])
        given.push_back(opt);
    r.onlyKeys(sources, at + ".sources", given);
    for (const auto& g : given) {
      const YAML::Node s = sources[g];
      if (!s || !s.IsScalar())
        r.fail("missing '" + at + ".sources." + g +
               "': every value names its source (a key of 'references' or assumed)");
      const std::string src = s.Scalar();
      if (src != "assumed" && !refs[src])
        r.fail("'" + at + ".sources." + g + "' = '" + src + "': not a key of 'references' nor 'assumed'");
    }
    t.minerals_.emplace(name, x);
  }
  return t;
}

const Mineral* MineralTable::find(const std::string& name) const {
  const auto it = minerals_.find(name);
  return it == minerals_.end() ? nullptr : &it->second;
}

std::vector<std::string> MineralTable::names() const {
  std::vector<std::string> out;
  for (const auto& kv : minerals_)
    out.push_back(kv.first);
  return out;
}

}  // namespace geo
}  // namespace unexmin
