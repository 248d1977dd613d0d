#include <unexmin/engine/engine.h>
#include <unexmin/raycast/ray_caster_factory.h>

namespace unexmin {
namespace engine {

Engine::Engine(const sim::WorldConfig& config, const std::map<std::string, sim::RobotDescription>& descriptions,
               int robots, const sensors::SensorFactory& models, const EngineOptions& options,
               const std::string& world_file)
    : selection_(options.selection) {
  world_ = std::make_unique<sim::World>(config, descriptions, robots, options.dt, options.seed);
  if (!selection_.none()) {
    try {
      raycast::RayCasterOptions caster_options;
      caster_options.threads = options.ray_caster_threads;
      caster_ = raycast::makeRayCaster(config.ray_caster, *world_, caster_options);
    } catch (const RayCasterError& e) {
      throw ConfigError(world_file + ": 'ray_caster': " + e.what());
    }
    caster_->update();
  }
  for (std::size_t i = 0; i < world_->robotCount(); ++i)
    suites_.push_back(std::make_unique<sensors::SensorSuite>(*world_, world_->robot(i), caster_.get(), models,
                                                             selection_, options.visual));
}

void Engine::step(bool hold) {
  if (hold)
    for (std::size_t r = 0; r < world_->robotCount(); ++r)
      for (std::size_t k = 0; k < world_->robot(r).thrusterCount(); ++k)
        world_->robot(r).thruster(k).holdCommand(world_->time());
  world_->step();
  if (caster_)
    caster_->update();  // the robots where the sensors of this step see them
  for (auto& s : suites_)
    s->update();
}

void Engine::reset(std::uint64_t seed) {
  world_->reset(seed);
  for (auto& s : suites_)
    s->reset(seed);
}

}  // namespace engine
}  // namespace unexmin
