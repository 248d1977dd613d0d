// <sensor name type link rate> of a robot description with its <param>s: numeric ones as numbers, the others as
// text (model names, ...). The sensor factory of each type checks them.
#include <unexmin/sim/description_entities.h>

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace unexmin {
namespace sim {
namespace description {
namespace {

/// One <param name value>: into sp.params when every word of the value is a number, else into sp.text.
void readParam(const DescriptionReader& r, const tinyxml2::XMLElement* q, const std::string& sw, SensorSpec& sp) {
  const char* key = q->Attribute("name");
  const char* value = q->Attribute("value");
  if (!key)
    r.fail(sw + "/param has no 'name'");
  if (!value)
    r.fail(sw + "/param[" + key + "] has no 'value'");
  std::istringstream in(value);
  std::string tok;
  bool numeric = true;
  std::vector<double> numbers;
  while (in >> tok) {
    char* end = nullptr;
    const double v = std::strtod(tok.c_str(), &end);
    if (end == tok.c_str() || *end != '\0')
      numeric = false;
    else if (!std::isfinite(v))
      r.fail(sw + "/param[" + key + "]: '" + tok + "' is not finite");
    numbers.push_back(v);
  }
  if (numeric && !numbers.empty())
    sp.params[key] = numbers;
  else
    sp.text[key] = value;
}

SensorSpec readSensor(const DescriptionReader& r, const tinyxml2::XMLElement* e, const LinkNames& links,
                      const RobotDescription& d) {
  SensorSpec sp;
  sp.name = textOf(e, "name");
  const std::string sw = "<sensor name='" + sp.name + "'>";
  if (sp.name.empty())
    r.fail("a <sensor> has no 'name'");
  for (const auto& other : d.sensors)
    if (other.name == sp.name)
      r.fail(sw + ": the name is used twice");
  sp.type = textOf(e, "type");
  if (sp.type.empty())
    r.fail(sw + " has no 'type'");
  sp.link = textOf(e, "link");
  if (!links.count(sp.link))
    r.fail(sw + "@link '" + sp.link + "' is not a link of the robot");
  sp.pose = d.linkPose(sp.link);
  sp.rate = r.attr(e, "rate", sw);
  if (!(sp.rate > 0.0))
    r.fail(sw + "@rate = " + formatNumber(sp.rate) + " must be > 0 [Hz]");
  for (const auto* q = e->FirstChildElement("param"); q; q = q->NextSiblingElement("param"))
    readParam(r, q, sw, sp);
  return sp;
}

}  // namespace

void parseSensors(const DescriptionReader& r, const tinyxml2::XMLElement* ext, const LinkNames& links,
                  RobotDescription& d) {
  for (const auto* e = ext->FirstChildElement("sensor"); e; e = e->NextSiblingElement("sensor"))
    d.sensors.push_back(readSensor(r, e, links, d));
}

}  // namespace description
}  // namespace sim
}  // namespace unexmin
