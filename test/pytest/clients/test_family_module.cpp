// A Python module of the engine's binding with one sensor family more than unexmin._core: "test_altimeter", defined
// only here. test/pytest/test_sample_description.py checks that its fields reach Python through the family's sample
// description alone (cpp/python/world_binding.cpp knows no family).
#include "../../../cpp/python/world_binding.h"

#include <unexmin/engine/sensor_families.h>
#include <unexmin/sensors/sensor.h>
#include <unexmin/sensors/sensor_params.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace {

using namespace unexmin;

/// Ranges straight down from its link to what lies below [m] (+inf: nothing within max_range), the link's depth
/// below the free surface [m], and how many of its samples saw the bottom.
class TestAltimeter : public sensors::Sensor {
public:
  TestAltimeter(const sim::SensorSpec& spec, const sensors::SensorSetup& setup) : Sensor(spec, setup) {
    sensors::SensorParams p(spec, setup.robot);
    max_range_ = p.number("max_range", 10.0, 0.01, 1000.0, "m");
    p.finish();
    rays_.resize(2);
  }

protected:
  void sample(const sensors::SensorContext& ctx) override {
    const Eigen::Isometry3d link = ctx.state.pose * spec().pose;
    for (std::size_t i = 0; i < rays_.size(); ++i) {
      rays_[i].origin = (link * Eigen::Vector3d(0.1 * static_cast<double>(i), 0.0, 0.0)).cast<float>();
      rays_[i].direction = Eigen::Vector3f(0.0f, 0.0f, -1.0f);
      rays_[i].max_range = static_cast<float>(max_range_);
    }
    castRays(ctx, rays_, hits_);
    ranges_.resize(hits_.size());
    for (std::size_t i = 0; i < hits_.size(); ++i)
      ranges_[i] = hits_[i].range;
    depth_ = ctx.world.config().surface_z - link.translation().z();
    if (std::isfinite(ranges_[0]))
      ++seen_;
  }
  void describeSample(sensors::SampleWriter& out) const override {
    out.array("ranges", "m", ranges_);
    out.scalar("depth", "m", depth_);
    out.count("bottom_seen", seen_);
  }

private:
  double max_range_ = 10.0;
  std::vector<raycast::Ray> rays_;
  std::vector<raycast::Hit> hits_;
  std::vector<float> ranges_;
  double depth_ = 0.0;
  std::uint64_t seen_ = 0;
};

sensors::SensorFactory families() {
  sensors::SensorFactory f = engine::sensorFamilies();
  f.add<TestAltimeter>("test_altimeter");
  return f;
}

}  // namespace

PYBIND11_MODULE(_test_family_core, m) {
  unexmin::python::bindWorld(m, &families);
}
