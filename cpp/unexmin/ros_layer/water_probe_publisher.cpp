#include <unexmin/ros_layer/water_probe_publisher.h>

#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/Temperature.h>
#include <unexmin/WaterQuality.h>

namespace unexmin {
namespace ros_layer {

WaterProbePublisher::WaterProbePublisher(const sensors::science::WaterProbeSensor& sensor, const PublisherContext& ctx)
    : sensor_(sensor) {
  const int queue = queueSize(sensor.rate());
  temperature_ = ctx.nh.advertise<sensor_msgs::Temperature>(
      resolve(ctx.ns, topicParam(sensor, "temperature_topic", "probe/temperature")), queue);
  pressure_ = ctx.nh.advertise<sensor_msgs::FluidPressure>(
      resolve(ctx.ns, topicParam(sensor, "pressure_topic", "probe/pressure")), queue);
  quality_ = ctx.nh.advertise<unexmin::WaterQuality>(
      resolve(ctx.ns, topicParam(sensor, "water_quality_topic", "probe/water_quality")), queue);
}

void WaterProbePublisher::publish() {
  const sensors::science::WaterProbeSample& s = sensor_.last();
  std_msgs::Header header;
  header.stamp.fromSec(s.time);
  header.frame_id = sensor_.frame();
  if (wanted(temperature_)) {
    sensor_msgs::Temperature m;
    m.header = header;
    m.temperature = s.temperature;
    m.variance = s.temperature_variance;
    emit(temperature_, m);
  }
  if (wanted(pressure_)) {
    sensor_msgs::FluidPressure m;
    m.header = header;
    m.fluid_pressure = s.pressure;
    m.variance = s.pressure_variance;
    emit(pressure_, m);
  }
  if (wanted(quality_)) {
    unexmin::WaterQuality m;
    m.header = header;
    m.temperature = s.temperature;
    m.temperature_variance = s.temperature_variance;
    m.conductivity = s.conductivity;
    m.conductivity_variance = s.conductivity_variance;
    m.conductivity_25 = s.conductivity_25;
    m.conductivity_25_variance = s.conductivity_25_variance;
    m.ph = s.ph;
    m.ph_variance = s.ph_variance;
    m.redox = s.redox;
    m.redox_variance = s.redox_variance;
    m.oxygen = s.oxygen;
    m.oxygen_variance = s.oxygen_variance;
    m.pressure = s.pressure;
    m.pressure_variance = s.pressure_variance;
    emit(quality_, m);
  }
}

}  // namespace ros_layer
}  // namespace unexmin
