#include <unexmin/ros_layer/water_sampler_publisher.h>

#include <unexmin/WaterSample.h>
#include <unexmin/core/error.h>

namespace unexmin {
namespace ros_layer {

WaterSamplerPublisher::WaterSamplerPublisher(sensors::science::WaterSamplerSensor& sensor, const PublisherContext& ctx)
    : sensor_(sensor) {
  const std::string base = resolve(ctx.ns, topicParam(sensor, "topic", "sampler"));
  // One message per bottle: room for every bottle of the rack.
  pub_ = ctx.nh.advertise<unexmin::WaterSample>(base + "/result", static_cast<std::uint32_t>(sensor.bottles()) + 1);
  fire_srv_ = ctx.nh.advertiseService(base + "/fire", &WaterSamplerPublisher::onFire, this);
}

bool WaterSamplerPublisher::onFire(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  try {
    res.message = sensor_.fire();
    res.success = true;
  } catch (const ParameterError& e) {
    res.success = false;
    res.message = e.what();
  }
  return true;
}

void WaterSamplerPublisher::publish() {
  const auto& results = sensor_.results();
  if (results.size() < sent_ || (sent_ > 0 && results[sent_ - 1].end_time != last_end_))
    sent_ = 0;  // the world was reset
  for (; sent_ < results.size(); ++sent_) {
    const sensors::science::BottleResult& r = results[sent_];
    unexmin::WaterSample m;
    m.header.stamp.fromSec(r.end_time);
    m.header.frame_id = "world";
    m.sensor = sensor_.name();
    m.bottle = r.bottle;
    m.trigger = sensors::science::triggerName(r.trigger);
    m.start_time = r.start_time;
    m.end_time = r.end_time;
    m.position.x = r.position.x();
    m.position.y = r.position.y();
    m.position.z = r.position.z();
    m.depth = r.depth;
    m.temperature = r.temperature;
    m.conductivity = r.conductivity;
    m.salinity = r.salinity;
    m.ph = r.ph;
    m.redox = r.redox;
    m.oxygen = r.oxygen;
    m.turbidity = r.turbidity;
    m.density = r.density;
    m.volume = r.volume;
    m.mass = r.mass;
    m.bottles_left = static_cast<std::uint32_t>(sensor_.bottlesLeft());
    emit(pub_, m);
    last_end_ = r.end_time;
  }
}

}  // namespace ros_layer
}  // namespace unexmin
