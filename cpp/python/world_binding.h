// The engine's Python binding (world_binding.cpp), for a module of any set of sensor families: unexmin._core binds
// the simulator's (core_module.cpp); a test module binds its own on top (test/pytest/clients/test_family_module.cpp).
#pragma once

#include <unexmin/sensors/sensor_factory.h>

#include <pybind11/pybind11.h>

#include <functional>

namespace unexmin {
namespace python {

/// Adds World (module-local), robot_names, families, modes, visibility_levels, setting_rules, check_settings,
/// spawned_robots and ConfigError to `m`; every World builds its sensors from `families()`.
void bindWorld(pybind11::module_& m, std::function<sensors::SensorFactory()> families);

}  // namespace python
}  // namespace unexmin
