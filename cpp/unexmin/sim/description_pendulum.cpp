// <pendulum joint mass arm speed min max> of a robot description: the internal pitch pendulum (optional).
#include <unexmin/sim/description_entities.h>

namespace unexmin {
namespace sim {
namespace description {

void parsePendulum(const DescriptionReader& r, const tinyxml2::XMLElement* ext, RobotDescription& d) {
  const auto* pend = ext->FirstChildElement("pendulum");
  if (!pend)
    return;
  const std::string pw = "<pendulum>";
  d.pendulum_joint = actuatorJoint(r, d, pend->Attribute("joint"), pw).name;
  d.pendulum.mass = r.attr(pend, "mass", pw);
  d.pendulum.arm = r.attr(pend, "arm", pw);
  d.pendulum.speed = r.attr(pend, "speed", pw);
  d.pendulum.min_angle = r.attr(pend, "min", pw);
  d.pendulum.max_angle = r.attr(pend, "max", pw);
  try {
    hydro::Pendulum check(d.pendulum);
  } catch (const ParameterError& e) {
    r.fail(pw + ": " + e.what());
  }
  if (d.pendulum.mass >= d.hydro.mass)
    r.fail(pw + "@mass must be less than the vehicle mass");
}

}  // namespace description
}  // namespace sim
}  // namespace unexmin
