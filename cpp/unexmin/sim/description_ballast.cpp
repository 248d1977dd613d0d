// <vbs min max xyz> of a robot description: the variable ballast system (optional; none: a range of 0 kg).
#include <unexmin/sim/description_entities.h>

namespace unexmin {
namespace sim {
namespace description {

void parseBallast(const DescriptionReader& r, const tinyxml2::XMLElement* ext, RobotDescription& d) {
  const auto* vbs = ext->FirstChildElement("vbs");
  if (!vbs) {
    d.vbs.min_mass = d.vbs.max_mass = 0.0;
    return;
  }
  const std::string vw = "<vbs>";
  d.vbs.min_mass = r.attr(vbs, "min", vw);
  d.vbs.max_mass = r.attr(vbs, "max", vw);
  if (vbs->Attribute("xyz"))
    d.vbs.position = r.vector3(vbs, "xyz", vw);
  try {
    hydro::Vbs check(d.vbs);
  } catch (const ParameterError& e) {
    r.fail(vw + ": " + e.what());
  }
}

}  // namespace description
}  // namespace sim
}  // namespace unexmin
