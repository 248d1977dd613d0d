// Properties of fresh, brackish and sea water from temperature, salinity and pressure: the UNESCO equations
// (Fofonoff & Millard 1983, UNESCO Technical Papers in Marine Science 44): practical salinity from conductivity
// (PSS-78, with the extension of Hill et al. 1986 below practical salinity 2), density (the international
// equation of state EOS-80) and sound speed (Chen & Millero 1977). Valid for temperature 0..40 degC, practical
// salinity 0..42 and pressure 0..10000 dbar; temperatures are ITS-90 (converted to the equations' IPTS-68 as
// T68 = 1.00024 T90). Pressure is sea pressure: absolute pressure minus one standard atmosphere. Knows no ROS.
#pragma once

namespace unexmin {
namespace water {

/// Conductivity of standard sea water at practical salinity 35, 15 degC (IPTS-68) and 0 dbar [uS/cm]: the
/// reference of PSS-78's conductivity ratio.
constexpr double kReferenceConductivity = 42914.0;

/// Practical salinity [PSU, dimensionless] of water of in-situ electrical conductivity `conductivity` [uS/cm] at
/// temperature [degC] and sea pressure [dbar]: PSS-78 for S >= 2, Hill et al. (1986) below (0 at 0 uS/cm).
double practicalSalinity(double conductivity, double temperature, double pressure);

/// In-situ conductivity [uS/cm] of water of practical salinity `salinity` at temperature [degC] and sea pressure
/// [dbar]: practicalSalinity() inverted (to 1e-9 in salinity).
double conductivityFromSalinity(double salinity, double temperature, double pressure);

/// Density [kg/m^3] by EOS-80 at practical salinity, temperature [degC] and sea pressure [dbar]; published
/// accuracy about 0.01 kg/m^3 (3.5e-6 relative at the surface).
double density(double salinity, double temperature, double pressure);

/// Sound speed [m/s] by Chen & Millero (1977) in the UNESCO 1983 form at practical salinity, temperature [degC]
/// and sea pressure [dbar]; the fit's published standard deviation is 0.19 m/s. Valid for fresh water (unlike
/// Mackenzie's 1981 formula, made for salinity 25..40).
double soundSpeed(double salinity, double temperature, double pressure);

}  // namespace water
}  // namespace unexmin
