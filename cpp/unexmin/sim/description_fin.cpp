// <fin id joint> of a robot description: pose from its joint (origin = centre of pressure, axis = span, x = chord at
// angle 0), lift model by family name, area, angle and rate limits (docs/robot_description.md).
#include <unexmin/sim/description_entities.h>

namespace unexmin {
namespace sim {
namespace description {
namespace {

/// Area, angle limits, rate and watchdog of a <fin>.
void readLimits(const DescriptionReader& r, const tinyxml2::XMLElement* f, const std::string& fw,
                hydro::FinParams& fp) {
  const auto* area = f->FirstChildElement("area");
  if (!area)
    r.fail(fw + ": missing <area value=...> (planform area > 0 [m^2])");
  fp.area = r.attr(area, "value", fw + "/area");
  const auto* angle = f->FirstChildElement("angle");
  if (!angle || !angle->Attribute("min") || !angle->Attribute("max"))
    r.fail(fw + ": missing <angle min=... max=...> (limits [rad], -pi/2 <= min <= 0 <= max <= pi/2)");
  fp.min_angle = r.attr(angle, "min", fw + "/angle");
  fp.max_angle = r.attr(angle, "max", fw + "/angle");
  const auto* rate = f->FirstChildElement("rate");
  if (!rate)
    r.fail(fw + ": missing <rate value=...> (largest fin speed > 0 [rad/s])");
  fp.rate = r.attr(rate, "value", fw + "/rate");
  if (const auto* to = f->FirstChildElement("timeout"))
    fp.timeout = r.attr(to, "value", fw + "/timeout");
}

hydro::FinParams readFin(const DescriptionReader& r, const tinyxml2::XMLElement* f, const RobotDescription& d,
                         std::string& joint) {
  hydro::FinParams fp;
  fp.id = actuatorId(r, f, "fin");
  const std::string fw = "<fin id=" + formatNumber(fp.id) + ">";
  const JointInfo& j = actuatorJoint(r, d, f->Attribute("joint"), fw);
  joint = j.name;
  const Eigen::Isometry3d frame = d.linkPose(j.parent) * j.origin;
  fp.axis = frame.linear() * j.axis;
  fp.chord = frame.linear().col(0);
  fp.position = frame.translation();
  requireInsideHull(r, d, fp.position, fw);
  const auto* model = f->FirstChildElement("model");
  if (!model)
    r.fail(fw + ": missing <model type=...> (a fin lift family, e.g. linear_lift)");
  fp.model = textOf(model, "type");
  fp.model_params = r.params(model, fw + "/model");
  readLimits(r, f, fw, fp);
  try {
    hydro::Fin check(fp, d.fin_families);
  } catch (const ParameterError& e) {
    r.fail(fw + ": " + e.what());
  }
  return fp;
}

}  // namespace

void parseFins(const DescriptionReader& r, const tinyxml2::XMLElement* ext, RobotDescription& d) {
  readActuators(
      r, ext, "fin", [&](const tinyxml2::XMLElement* e, std::string& joint) { return readFin(r, e, d, joint); }, d.fins,
      d.fin_joints);
}

}  // namespace description
}  // namespace sim
}  // namespace unexmin
