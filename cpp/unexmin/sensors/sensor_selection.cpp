#include <unexmin/sensors/sensor_selection.h>

#include <unexmin/core/error.h>

#include <algorithm>

namespace unexmin {
namespace sensors {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos)
    return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

std::string join(const std::vector<std::string>& v) {
  std::string out;
  for (const auto& s : v)
    out += (out.empty() ? "" : ", ") + s;
  return out;
}

}  // namespace

SensorSelection SensorSelection::parse(const std::string& text, const std::vector<std::string>& known,
                                       const std::string& source) {
  SensorSelection sel;
  const std::string t = trim(text);
  if (t == "all")
    return sel;
  sel.all_ = false;
  if (t == "none")
    return sel;
  std::size_t start = 0;
  while (start <= t.size()) {
    const std::size_t comma = std::min(t.find(',', start), t.size());
    const std::string name = trim(t.substr(start, comma - start));
    if (name.empty() || std::find(known.begin(), known.end(), name) == known.end())
      throw ConfigError(source + " = '" + text +
                        "': " + (name.empty() ? "empty family name" : "unknown family '" + name + "'") +
                        "; expected all, none or a comma-separated list of: " + join(known));
    sel.families_.insert(name);
    start = comma + 1;
  }
  return sel;
}

std::string SensorSelection::text() const {
  if (all_)
    return "all";
  if (families_.empty())
    return "none";
  std::string out;
  for (const auto& f : families_)
    out += (out.empty() ? "" : ",") + f;
  return out;
}

}  // namespace sensors
}  // namespace unexmin
