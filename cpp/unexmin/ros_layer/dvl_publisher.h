// Topics of a "dvl" sensor (names from its _topic parameters, relative to /<robot>/):
//   topic        (default <name>)         unexmin/Dvl: everything of the ping (input of the DVL translator)
//   sonar_topic  (default <name>_sonar)   + beam index 0..3: sensor_msgs/Range per beam (ULTRASOUND,
//                                         field of view = beam width, +inf when the beam sees no bottom),
//                                         frame: the beam_frames link (else the DVL link)
//   twist_topic  (default <name>_twist)   geometry_msgs/TwistWithCovarianceStamped, DVL frame; only with
//                                         bottom lock; the angular part is not measured (zero, variance 1e6)
//   water_track_topic (default <name>_water_track)  dvl_nortek/DvlBottomWaterTrack, the translation of
//                                         python/unexmin/translators/dvl.py (dvl_water_track.h), built here when
//                                         the robot's parameter dvl_from_simulator is true (default)
#pragma once

#include <unexmin/ros_layer/sensor_publisher.h>
#include <unexmin/sensors/dvl_sensor.h>

#include <array>

namespace unexmin {
namespace ros_layer {

class DvlPublisher : public SensorPublisher {
public:
  DvlPublisher(const sensors::DvlSensor& sensor, const PublisherContext& ctx);
  void publish() override;

private:
  const sensors::DvlSensor& sensor_;
  Stream dvl_, twist_, track_;
  std::array<Stream, 4> sonar_;
  std::array<std::string, 4> beam_frames_;
};

}  // namespace ros_layer
}  // namespace unexmin
