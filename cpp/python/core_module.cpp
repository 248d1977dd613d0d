// unexmin._core: the simulator's engine in-process from Python with the simulator's sensor families
// (docs/python_api.md, "unexmin.core"); python/unexmin/core/ wraps it. Links no ROS library.
#include "world_binding.h"

#include <unexmin/engine/sensor_families.h>

PYBIND11_MODULE(_core, m) {
  m.doc() = "The unexmin simulator's engine in-process (use unexmin.core; docs/python_api.md)";
  unexmin::python::bindWorld(m, &unexmin::engine::sensorFamilies);
}
