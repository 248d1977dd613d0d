#include <unexmin/sim/description_reader.h>

#include <unexmin/core/error.h>

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace unexmin {
namespace sim {
namespace description {

void DescriptionReader::fail(const std::string& what) const {
  throw ConfigError(source_ + ": " + what);
}

std::vector<double> DescriptionReader::numbers(const char* text, const std::string& where) const {
  std::vector<double> out;
  if (!text)
    return out;
  std::istringstream in(text);
  std::string tok;
  while (in >> tok) {
    char* end = nullptr;
    const double v = std::strtod(tok.c_str(), &end);
    if (end == tok.c_str() || *end != '\0' || !std::isfinite(v))
      fail(where + ": '" + tok + "' is not a finite number");
    out.push_back(v);
  }
  return out;
}

std::vector<double> DescriptionReader::attrNumbers(const tinyxml2::XMLElement* e, const char* attr, std::size_t count,
                                                   const std::string& where) const {
  const char* text = e ? e->Attribute(attr) : nullptr;
  if (!text)
    fail("missing " + where + " attribute '" + attr + "'");
  auto v = numbers(text, where + "@" + attr);
  if (count && v.size() != count)
    fail(where + "@" + attr + " has " + formatNumber(v.size()) + " numbers, expected " + formatNumber(count));
  return v;
}

double DescriptionReader::attr(const tinyxml2::XMLElement* e, const char* name, const std::string& where) const {
  return attrNumbers(e, name, 1, where)[0];
}

double DescriptionReader::attrOr(const tinyxml2::XMLElement* e, const char* name, const std::string& where,
                                 double fallback) const {
  return (e && e->Attribute(name)) ? attr(e, name, where) : fallback;
}

Eigen::Vector3d DescriptionReader::vector3(const tinyxml2::XMLElement* e, const char* attr,
                                           const std::string& where) const {
  const auto v = attrNumbers(e, attr, 3, where);
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

const tinyxml2::XMLElement* DescriptionReader::child(const tinyxml2::XMLElement* e, const char* name,
                                                     const std::string& where) const {
  const auto* c = e->FirstChildElement(name);
  if (!c)
    fail("missing <" + std::string(name) + "> in " + where);
  return c;
}

std::vector<double> DescriptionReader::valueOf(const tinyxml2::XMLElement* e, const char* name, std::size_t count,
                                               const std::string& where) const {
  return attrNumbers(child(e, name, where), "value", count, where + "/" + name);
}

hydro::ParamMap DescriptionReader::params(const tinyxml2::XMLElement* e, const std::string& where) const {
  hydro::ParamMap out;
  for (const auto* p = e->FirstChildElement("param"); p; p = p->NextSiblingElement("param")) {
    const char* name = p->Attribute("name");
    if (!name)
      fail(where + "/param has no 'name'");
    out[name] = attrNumbers(p, "value", 0, where + "/param[" + name + "]");
  }
  return out;
}

std::string textOf(const tinyxml2::XMLElement* e, const char* name) {
  const char* text = e->Attribute(name);
  return text ? text : "";
}

}  // namespace description
}  // namespace sim
}  // namespace unexmin
