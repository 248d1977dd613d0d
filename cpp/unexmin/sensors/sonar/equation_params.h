// The sonar equation's parameters (echo_model.h, docs/sonars.md) as every echo sounder of the family reads them
// from its <sensor> element: the same keys, units and bounds for the MSIS and the M3.
#pragma once

#include <unexmin/raycast/ray_caster.h>
#include <unexmin/sensors/sensor_params.h>
#include <unexmin/sensors/sonar/echo_model.h>

#include <cmath>
#include <limits>

namespace unexmin {
namespace sensors {
namespace sonar {

/// Reads gain_span, source_level (default `source_level` [dB re 1 uPa at 1 m], the sonar's own),
/// backscatter_strength and _exponent, absorption, tvg_spreading, display_min and display_span into `e`.
inline void readEquationParams(sensors::SensorParams& p, EchoParams& e, double source_level) {
  e.gain_span = p.number("gain_span", 40.0, 0.0, 120.0, "dB");
  e.source_level = p.number("source_level", source_level, 100.0, 260.0, "dB re 1 uPa at 1 m");
  e.backscatter_strength = p.number("backscatter_strength", -20.0, -100.0, 0.0, "dB");
  e.backscatter_exponent = p.number("backscatter_exponent", 2.0, 0.0, 10.0, "(-)");
  e.absorption = p.number("absorption", 0.1, 0.0, 10.0, "dB/m");
  e.tvg_spreading = p.number("tvg_spreading", 20.0, 0.0, 60.0, "dB per decade");
  e.display_min = p.number("display_min", 125.0, 0.0, 300.0, "dB re 1 uPa");
  e.display_span = p.number("display_span", 80.0, 1.0, 200.0, "dB");
}

/// The free surface as a reflector (surface multipath, docs/sonars.md): the extra levels X of its echoes.
struct SurfaceParams {
  bool multipath = true;       ///< rays that reach the surface echo there and are reflected
  double ghost_extra = 0.0;    ///< 40 log10 |R|: a ghost's two reflections at the surface [dB] (-inf for R = 0)
  double surface_extra = 0.0;  ///< surface_backscatter - backscatter_strength: the surface's own echo [dB]
};

/// Reads multipath (true), surface_reflection (|R|, amplitude, 0.9) and surface_backscatter (-30 dB) against the
/// backscatter_strength already in `e`.
inline SurfaceParams readSurfaceParams(sensors::SensorParams& p, const EchoParams& e) {
  SurfaceParams s;
  s.multipath = p.flag("multipath", true);
  const double reflection = p.number("surface_reflection", 0.9, 0.0, 1.0, "(amplitude, -)");
  s.ghost_extra = reflection > 0.0 ? 40.0 * std::log10(reflection) : -std::numeric_limits<double>::infinity();
  s.surface_extra = p.number("surface_backscatter", -30.0, -100.0, 0.0, "dB") - e.backscatter_strength;
  return s;
}

/// The reflection at the free surface (z = surface_z) of `ray`, which starts at `origin` and meets the surface at
/// distance s: from the point it meets it, mirrored in the horizontal (d_z -> -d_z), for `reach` metres.
inline raycast::Ray reflectedRay(const raycast::Ray& ray, const Eigen::Vector3d& origin, double s, double surface_z,
                                 double reach) {
  raycast::Ray r = ray;
  r.origin = (origin + s * ray.direction.cast<double>()).cast<float>();
  r.origin.z() = static_cast<float>(surface_z);
  r.direction.z() = -r.direction.z();
  r.max_range = static_cast<float>(reach);
  return r;
}

}  // namespace sonar
}  // namespace sensors
}  // namespace unexmin
