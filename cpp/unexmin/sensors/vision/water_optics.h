// Optical properties of the water, per RGB channel, from the world's visibility (level none|low|medium|high and
// the colour of the murk): absorption a, scattering b and beam attenuation c = a + b [1/m], the Henyey-Greenstein
// asymmetry g of the scattering. Light travelling a distance R keeps exp(-c R) of its power (Beer-Lambert).
// Used by the cameras (direct light and backscatter) and the SLS (how far its laser line stays visible).
//
// Green-channel values (the SLS laser's 532 nm), see docs/vision.md for sources:
//   level   a      b      c      visible range ~4/c   source
//   none    0.114  0.037  0.151  ~26 m                 Petzold, clear ocean (Bahamas), Mobley 1994 tab. 3.10
//   low     0.179  0.219  0.398  ~10 m                 Petzold, coastal ocean
//   medium  0.300  0.900  1.200  ~3 m                  assumed, between Petzold's coastal and turbid harbour
//   high    0.600  3.400  4.000  ~1 m                  assumed, ~1.8 x Petzold's turbid harbour (c = 2.19)
// Colour: scattering by suspended particles is about equal per channel; absorption of channel k is the green
// one times colour_g / colour_k (the murk transmits best the colour it shows) [assumed model].
// g = 0.924 (Petzold's average particle phase function fitted by Henyey-Greenstein; Mobley 1994).
// Level "water": the water column's turbidity T [NTU] where the sensor is, as the clear water ("none") plus particles
// scattering 0.6 T and absorbing 0.1 T [1/m] in green (c = 0.151 + 0.7 T: 1.5 NTU is about "medium", 5.5 NTU
// about "high"; the factor per NTU is assumed, of the order Davies-Colley & Smith 2001 report for mineral silt).
#pragma once

#include <unexmin/sim/world_config.h>

#include <Eigen/Core>

#include <string>

namespace unexmin {
namespace sensors {
namespace vision {

struct WaterOptics {
  Eigen::Vector3d a{0, 0, 0};  ///< absorption per channel (R, G, B) [1/m]
  Eigen::Vector3d b{0, 0, 0};  ///< scattering per channel [1/m]
  double g = 0.924;            ///< Henyey-Greenstein asymmetry of the scattering [-]

  /// Beam attenuation c = a + b [1/m].
  Eigen::Vector3d c() const { return a + b; }
  /// Fraction of light left after `range` [m] per channel: exp(-c range).
  Eigen::Vector3d transmission(double range) const;
  /// Henyey-Greenstein phase function p(psi) [1/sr] at scattering angle psi (cos given), normalised over the
  /// sphere.
  double phase(double cos_psi) const;

  /// The water of a visibility `level` (none|low|medium|high) and murk `colour` (RGB, each in (0, 1]). Throws
  /// ConfigError naming the level or colour otherwise.
  static WaterOptics fromVisibility(const std::string& level, const Eigen::Vector3d& colour);
  /// Clear water plus the particles of turbidity `ntu` [NTU] >= 0 (above), murk `colour` as fromVisibility's.
  static WaterOptics fromTurbidity(double ntu, const Eigen::Vector3d& colour);
  /// The water of `config`'s visibility: its level's, or for level "water" that of `turbidity` (opticalTurbidity()).
  static WaterOptics fromWorld(const sim::WorldConfig& config, double turbidity);
};

/// The turbidity [NTU] the optics use at world point `p` at sim time `time`: for level "water" the water column's
/// there, rounded to steps of 2 % (and to 0.01 NTU), so that a sensor rebuilds its water only where it changes; -1
/// for the other levels (the level holds everywhere).
double opticalTurbidity(const sim::WorldConfig& config, const Eigen::Vector3d& p, double time);

}  // namespace vision
}  // namespace sensors
}  // namespace unexmin
