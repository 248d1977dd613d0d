#include <unexmin/water/seawater.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace water {
namespace {

double t68(double t90) {
  return 1.00024 * t90;
}

/// Horner evaluation of c[0] + c[1] x + ... + c[n-1] x^(n-1).
template <int N>
double poly(const double (&c)[N], double x) {
  double y = c[N - 1];
  for (int i = N - 2; i >= 0; --i)
    y = y * x + c[i];
  return y;
}

// PSS-78 (UNESCO 1983, pp. 6-9)
constexpr double kA[] = {0.0080, -0.1692, 25.3851, 14.0941, -7.0261, 2.7081};
constexpr double kB[] = {0.0005, -0.0056, -0.0066, -0.0375, 0.0636, -0.0144};
constexpr double kK = 0.0162;
constexpr double kC[] = {0.6766097, 2.00564e-2, 1.104259e-4, -6.9698e-7, 1.0031e-9};

/// Practical salinity from Rt, the conductivity ratio at 0 dbar relative to S = 35 at the same temperature T68.
double salinityFromRt(double rt, double t) {
  if (rt <= 0.0)
    return 0.0;
  const double x = std::sqrt(rt);
  const double f = (t - 15.0) / (1.0 + kK * (t - 15.0));
  double s = poly(kA, x) + f * poly(kB, x);
  if (s < 2.0) {  // Hill, Dauphinee & Woods (1986)
    const double x400 = 400.0 * rt, y100 = 100.0 * rt;
    const double sy = std::sqrt(y100);
    s -= kA[0] / (1.0 + 1.5 * x400 + x400 * x400) + kB[0] * f / (1.0 + sy + y100 + y100 * sy);
  }
  return s;
}

/// Rp: the pressure correction of the conductivity ratio R (UNESCO 1983).
double pressureRatio(double r, double t, double p) {
  const double e = p * (2.070e-5 + p * (-6.370e-10 + p * 3.989e-15));
  const double d = 1.0 + t * (3.426e-2 + t * 4.464e-4) + (4.215e-1 - 3.107e-3 * t) * r;
  return 1.0 + e / d;
}

}  // namespace

double practicalSalinity(double conductivity, double temperature, double pressure) {
  const double t = t68(temperature);
  const double r = conductivity / kReferenceConductivity;
  const double rt = r / (pressureRatio(r, t, pressure) * poly(kC, t));
  return std::max(0.0, salinityFromRt(rt, t));
}

double conductivityFromSalinity(double salinity, double temperature, double pressure) {
  if (salinity <= 0.0)
    return 0.0;
  // practicalSalinity rises monotonically with conductivity: bisection on [0, 3 C(35, 15, 0)] (S up to ~120)
  double lo = 0.0, hi = 3.0 * kReferenceConductivity;
  for (int i = 0; i < 200 && hi - lo > 1e-9 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (practicalSalinity(mid, temperature, pressure) < salinity ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double density(double salinity, double temperature, double pressure) {
  const double t = t68(temperature);
  const double s = std::max(0.0, salinity);
  const double s15 = s * std::sqrt(s);
  const double p = pressure / 10.0;  // [bar]
  // EOS-80 (UNESCO 1981; Millero & Poisson 1981): one-atmosphere density, then the secant bulk modulus
  constexpr double kW[] = {999.842594, 6.793952e-2, -9.095290e-3, 1.001685e-4, -1.120083e-6, 6.536332e-9};
  constexpr double kSb[] = {8.24493e-1, -4.0899e-3, 7.6438e-5, -8.2467e-7, 5.3875e-9};
  constexpr double kSc[] = {-5.72466e-3, 1.0227e-4, -1.6546e-6};
  const double rho0 = poly(kW, t) + s * poly(kSb, t) + s15 * poly(kSc, t) + 4.8314e-4 * s * s;
  if (p == 0.0)
    return rho0;
  constexpr double kKw[] = {19652.21, 148.4206, -2.327105, 1.360477e-2, -5.155288e-5};
  constexpr double kKs[] = {54.6746, -0.603459, 1.09987e-2, -6.1670e-5};
  constexpr double kKs15[] = {7.944e-2, 1.6483e-2, -5.3009e-4};
  constexpr double kAw[] = {3.239908, 1.43713e-3, 1.16092e-4, -5.77905e-7};
  constexpr double kAs[] = {2.2838e-3, -1.0981e-5, -1.6078e-6};
  constexpr double kBw[] = {8.50935e-5, -6.12293e-6, 5.2787e-8};
  constexpr double kBs[] = {-9.9348e-7, 2.0816e-8, 9.1697e-10};
  const double k0 = poly(kKw, t) + s * poly(kKs, t) + s15 * poly(kKs15, t);
  const double a = poly(kAw, t) + s * poly(kAs, t) + 1.91075e-4 * s15;
  const double b = poly(kBw, t) + s * poly(kBs, t);
  const double k = k0 + p * (a + p * b);
  return rho0 / (1.0 - p / k);
}

double soundSpeed(double salinity, double temperature, double pressure) {
  const double t = t68(temperature);
  const double s = std::max(0.0, salinity);
  const double p = pressure / 10.0;  // [bar]
  // Chen & Millero (1977), UNESCO 1983 pp. 46-49
  constexpr double kC0[] = {1402.388, 5.03711, -5.80852e-2, 3.3420e-4, -1.47800e-6, 3.1464e-9};
  constexpr double kC1[] = {0.153563, 6.8982e-4, -8.1788e-6, 1.3621e-7, -6.1185e-10};
  constexpr double kC2[] = {3.1260e-5, -1.7107e-6, 2.5974e-8, -2.5335e-10, 1.0405e-12};
  constexpr double kC3[] = {-9.7729e-9, 3.8504e-10, -2.3643e-12};
  constexpr double kA0[] = {1.389, -1.262e-2, 7.164e-5, 2.006e-6, -3.21e-8};
  constexpr double kA1[] = {9.4742e-5, -1.2580e-5, -6.4885e-8, 1.0507e-8, -2.0122e-10};
  constexpr double kA2[] = {-3.9064e-7, 9.1041e-9, -1.6002e-10, 7.988e-12};
  constexpr double kA3[] = {1.100e-10, 6.649e-12, -3.389e-13};
  const double cw = poly(kC0, t) + p * (poly(kC1, t) + p * (poly(kC2, t) + p * poly(kC3, t)));
  const double a = poly(kA0, t) + p * (poly(kA1, t) + p * (poly(kA2, t) + p * poly(kA3, t)));
  const double b = -1.922e-2 - 4.42e-5 * t + p * (7.3637e-5 + 1.7945e-7 * t);
  const double d = 1.727e-3 - 7.9836e-6 * p;
  return cw + a * s + b * s * std::sqrt(s) + d * s * s;
}

}  // namespace water
}  // namespace unexmin
