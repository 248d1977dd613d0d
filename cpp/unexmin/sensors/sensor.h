// Base of every simulated sensor: its specification from the robot description, its schedule
// (samples at t_k = k / rate of simulation time, k = 1, 2, ..., taken at the first physics step at or
// after t_k), its seeded random stream and its reset. Knows no ROS; time is a double in seconds.
#pragma once

#include <unexmin/raycast/ray_caster.h>
#include <unexmin/sensors/random.h>
#include <unexmin/sensors/sample_fields.h>
#include <unexmin/sensors/sensor_params.h>
#include <unexmin/sim/robot.h>
#include <unexmin/sim/robot_description.h>
#include <unexmin/sim/world.h>

#include <cstdint>
#include <string>
#include <vector>

namespace unexmin {
namespace sensors {

/// What a sensor may read at one physics step; everything is passed in, nothing is global.
struct SensorContext {
  const sim::World& world;
  const sim::Robot& robot;
  const sim::RobotState& state;    ///< robot.state() after this step
  const raycast::RayCaster* rays;  ///< the world's caster, updated after this step (null: rays hit nothing)
  int robot_index;                 ///< the robot's index in the world: its own hull is invisible to its rays
};

/// The acoustic sensors' apparent-range factor at `point` (world frame [m]): c_configured / c_water, with c_water the
/// sound speed of the world's water column there now (docs/worlds.md, "Water column"). A sonar times its echoes in
/// the water's sound but turns the time into a range with its own configured speed `configured` [m/s], so it reports
/// factor x the true range. 1 in a world without a water column (its water is at every sensor's configured speed).
double apparentRangeFactor(const sim::World& world, const Eigen::Vector3d& point, double configured);

/// A sonar's `sound_speed` setting (docs/sonars.md): the speed it turns echo times into ranges with, configured
/// (a number [m/s] in [1300, 1700], default 1500, as on the sonar's settings page), or `probe`: a sound velocity
/// probe at the head measures the water's speed there at every ping (as a multibeam's SV sensor feeds its
/// beamformer; its error is not modelled), so its ranges are the true ones.
struct SoundSpeed {
  double configured = 1500.0;  ///< [m/s] the configured speed; with the probe, the nominal one for rate limits
  bool probe = false;
  /// The apparent-range factor at `point` (world frame [m]): 1 with the probe, else apparentRangeFactor().
  double rangeFactor(const sim::World& world, const Eigen::Vector3d& point) const {
    return probe ? 1.0 : apparentRangeFactor(world, point, configured);
  }
  /// Reads parameter `sound_speed` of `p` (ConfigError naming it on another text or a number out of range).
  static SoundSpeed read(SensorParams& p);
};

/// A joint a sensor moves (the MSIS head, an SLS motor), as joint_states reports it.
struct MovedJoint {
  std::string name;       ///< URDF joint name
  double position = 0.0;  ///< [rad] (or [m] for a prismatic joint)
  double velocity = 0.0;  ///< [rad/s] (or [m/s])
};

/// What a sensor's constructor may read: the robot description (link poses) and the step.
struct SensorSetup {
  std::string robot;  ///< robot name (messages, random stream)
  const sim::RobotDescription& description;
  double physics_dt = 0.002;  ///< physics step [s] > 0
  /// Visual mode (/sim/mode): lights on, images rendered; false = operational (fastest).
  bool visual = false;
};

class Sensor {
public:
  /// Throws ConfigError naming the sensor when its rate exceeds the physics rate.
  Sensor(const sim::SensorSpec& spec, const SensorSetup& setup);
  virtual ~Sensor() = default;
  Sensor(const Sensor&) = delete;
  Sensor& operator=(const Sensor&) = delete;

  const sim::SensorSpec& spec() const { return spec_; }
  const std::string& name() const { return spec_.name; }
  const std::string& type() const { return spec_.type; }
  const std::string& robotName() const { return robot_; }
  /// frame_id of its messages: the URDF link.
  const std::string& frame() const { return spec_.link; }
  double rate() const { return spec_.rate; }  ///< [Hz of sim time]

  /// Back to t = 0 with a (new) world seed: reseeds the random stream, draws turn-on biases and
  /// restarts the schedule. Call once before the first update.
  void reset(std::uint64_t world_seed);
  /// Call after every physics step. Returns true when a sample was taken at this step.
  bool update(const SensorContext& ctx);
  /// Simulation time of the latest sample [s] (negative before the first one).
  double sampleTime() const { return sample_time_; }
  std::uint64_t sampleCount() const { return samples_; }
  /// Appends the joints this sensor moves, with their state now (none by default).
  virtual void movedJoints(std::vector<MovedJoint>& /*out*/) const {}
  /// The latest sample as named fields (sample_fields.h): "time" [s] (sampleTime()) and "count" (sampleCount()),
  /// then the family's own (describeSample()). The one description of a sample that every reader but the family's
  /// publisher reads.
  void describe(SampleWriter& out) const;
  /// Visual mode: whether the sensor renders the images of its samples (on by default, kept across reset()); off, a
  /// sample only moves its schedule, as when nobody wants its images. A family that renders images (the camera)
  /// overrides it; the others throw ParameterError naming the robot, the sensor and its family.
  virtual void setRendering(bool on);
  /// The family's one action, fired by a caller between physics steps (never during one): a water sampler starts
  /// filling its next bottle. Returns what it did, in one line. A family that fires (the water sampler) overrides it
  /// and throws ParameterError naming the robot and the sensor when it cannot now; the others throw ParameterError
  /// naming the robot, the sensor and its family.
  virtual std::string fire();
  /// Mass the sensor carries besides the robot's description [kg] >= 0 (the water a sampler has taken), at its mount
  /// (spec().pose); 0 by default. The suite adds every sensor's to the robot after each step (SensorSuite::update).
  virtual double carriedMass() const { return 0.0; }

protected:
  /// Reset the model's state (turn-on biases are drawn here from random()).
  virtual void onReset() {}
  /// Every physics step, before a possible sample (e.g. finite-difference histories).
  virtual void track(const SensorContext&) {}
  /// Take one sample at ctx.world.time().
  virtual void sample(const SensorContext& ctx) = 0;
  /// The family's fields of its latest sample, each with its unit and shape, in the order its docs list them
  /// (docs/python_api.md); none by default.
  virtual void describeSample(SampleWriter& /*out*/) const {}
  Random& random() { return random_; }
  /// Casts `rays` through ctx.rays, the robot's own hull excluded; `hits` answers them one for one (all
  /// misses when the context has no caster). Incidence::skip: a model that needs the incidence of few hits
  /// asks raycast::RayCaster::incidence() for those. `seen_by`: the meshes the sensor sees (an optical sensor:
  /// raycast::SeenBy::cameras).
  static void castRays(const SensorContext& ctx, const std::vector<raycast::Ray>& rays, std::vector<raycast::Hit>& hits,
                       raycast::Incidence incidence = raycast::Incidence::compute,
                       raycast::SeenBy seen_by = raycast::SeenBy::sonars);
  double interval() const { return 1.0 / spec_.rate; }  ///< [s]

private:
  sim::SensorSpec spec_;
  std::string robot_;
  Random random_;
  std::uint64_t next_ = 1;  ///< index k of the next sample time k / rate
  std::uint64_t samples_ = 0;
  double sample_time_ = -1.0;
  double tolerance_ = 1e-9;  ///< [s] rounding slack of the schedule
};

/// The sensor's text parameter `key` (a topic or frame name), `fallback` when absent: how the simulator's
/// publishers and the in-process mapper name a sensor's topics and frames.
inline std::string textParam(const Sensor& s, const std::string& key, const std::string& fallback) {
  const auto it = s.spec().text.find(key);
  return it == s.spec().text.end() ? fallback : it->second;
}

/// `topic` relative to a robot's namespace `ns` ("/UX_1/"), unless it is absolute.
inline std::string resolveTopic(const std::string& ns, const std::string& topic) {
  return !topic.empty() && topic[0] == '/' ? topic : ns + topic;
}

}  // namespace sensors
}  // namespace unexmin
