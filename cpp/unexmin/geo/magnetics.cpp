#include <unexmin/geo/magnetics.h>

#include <algorithm>
#include <cmath>

namespace unexmin {
namespace geo {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTeslaToNanotesla = 1e9;

/// ln(t + R) with R = sqrt(t^2 + rho2), computed without cancellation when t < 0; clamped away from ln(0) on
/// the prolongation of an edge (rho2 = 0, t < 0), where the field is singular.
double logPlusR(double t, double R, double rho2) {
  if (t >= 0.0)
    return std::log(t + R);
  return std::log(std::max(rho2, 1e-300) / (R - t));
}

/// atan(a b / (c R)), its limit for c -> 0+ on a face plane.
double atanTerm(double a, double b, double c, double R) {
  if (c == 0.0)
    c = 1e-300;
  return std::atan(a * b / (c * R));
}

}  // namespace

Eigen::Vector3d fieldFromAngles(double intensity, double inclination, double declination) {
  const double inc = inclination * kPi / 180.0, dec = declination * kPi / 180.0;
  const double h = intensity * std::cos(inc);
  return {h * std::sin(dec), h * std::cos(dec), -intensity * std::sin(inc)};
}

double carlsonRD(double x, double y, double z) {
  // Carlson 1995 (Numer. Algorithms 10:13-26): duplication until the arguments agree to 1.5e-3, then the
  // fifth-order series; its relative error is below ~1e-15 there.
  constexpr double kTol = 0.0015, C1 = 3.0 / 14.0, C2 = 1.0 / 6.0, C3 = 9.0 / 22.0, C4 = 3.0 / 26.0;
  constexpr double C5 = 0.25 * C3, C6 = 1.5 * C4;
  double sum = 0.0, fac = 1.0, ave = 0.0, dx = 0.0, dy = 0.0, dz = 0.0;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double sx = std::sqrt(x), sy = std::sqrt(y), sz = std::sqrt(z);
    const double lambda = sx * (sy + sz) + sy * sz;
    sum += fac / (sz * (z + lambda));
    fac *= 0.25;
    x = 0.25 * (x + lambda);
    y = 0.25 * (y + lambda);
    z = 0.25 * (z + lambda);
    ave = 0.2 * (x + y + 3.0 * z);
    dx = (ave - x) / ave;
    dy = (ave - y) / ave;
    dz = (ave - z) / ave;
    if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) < kTol)
      break;
  }
  const double ea = dx * dy, eb = dz * dz, ec = ea - eb, ed = ea - 6.0 * eb, ee = ed + ec + ec;
  return 3.0 * sum + fac *
                         (1.0 + ed * (-C1 + C5 * ed - C6 * dz * ee) + dz * (C2 * ee + dz * (-C3 * ec + dz * C4 * ea))) /
                         (ave * std::sqrt(ave));
}

Eigen::Vector3d demagnetisingFactors(const Eigen::Vector3d& semi_axes) {
  const double a = semi_axes.x(), b = semi_axes.y(), c = semi_axes.z();
  const double abc3 = a * b * c / 3.0;
  return {abc3 * carlsonRD(b * b, c * c, a * a), abc3 * carlsonRD(c * c, a * a, b * b),
          abc3 * carlsonRD(a * a, b * b, c * c)};
}

Eigen::Vector3d dipoleField(const Eigen::Vector3d& m, const Eigen::Vector3d& r) {
  const double d = r.norm();
  if (d == 0.0)
    return Eigen::Vector3d::Zero();
  const Eigen::Vector3d u = r / d;
  return kMu0 / (4.0 * kPi * d * d * d) * (3.0 * m.dot(u) * u - m) * kTeslaToNanotesla;
}

Eigen::Vector3d prismField(const Eigen::Vector3d& size, const Eigen::Vector3d& M, const Eigen::Vector3d& q) {
  // U(r) = int_V dV' / |r' - r|; with (xi, eta, zeta) = r' - r at a corner and [[[f]]] the sum over the eight
  // corners of f signed + at an upper limit and - at a lower one (per axis):
  //   U_xx = -[[[atan(eta zeta / (xi R))]]],   U_xy = [[[ln(zeta + R)]]]   (and cyclically)
  const Eigen::Vector3d half = 0.5 * size;
  Eigen::Matrix3d U = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k) {
        const double x = (i ? half.x() : -half.x()) - q.x();
        const double y = (j ? half.y() : -half.y()) - q.y();
        const double z = (k ? half.z() : -half.z()) - q.z();
        const double s = (i ? 1.0 : -1.0) * (j ? 1.0 : -1.0) * (k ? 1.0 : -1.0);
        const double R = std::sqrt(x * x + y * y + z * z);
        U(0, 0) -= s * atanTerm(y, z, x, R);
        U(1, 1) -= s * atanTerm(z, x, y, R);
        U(2, 2) -= s * atanTerm(x, y, z, R);
        U(0, 1) += s * logPlusR(z, R, x * x + y * y);
        U(0, 2) += s * logPlusR(y, R, x * x + z * z);
        U(1, 2) += s * logPlusR(x, R, y * y + z * z);
      }
  U(1, 0) = U(0, 1);
  U(2, 0) = U(0, 2);
  U(2, 1) = U(1, 2);
  Eigen::Vector3d H = U * M / (4.0 * kPi);
  if ((q.array().abs() < half.array()).all())
    H += M;  // B = mu0 (H + M) inside
  return kMu0 * H * kTeslaToNanotesla;
}

MagneticAnomalies::MagneticAnomalies(const Eigen::Vector3d& ambient, std::shared_ptr<const Geology> geology)
    : ambient_(ambient), geology_(std::move(geology)) {
  if (!geology_)
    return;
  const double f = ambient_.norm();
  const Eigen::Vector3d along = f > 0.0 ? Eigen::Vector3d(ambient_ / f) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d H0 = ambient_ / kTeslaToNanotesla / kMu0;  // [A/m]
  const Rock& host = geology_->host();
  for (const Body& b : geology_->bodies()) {
    BodyMagnet m;
    m.kind = b.kind;
    const double dchi = b.rock.susceptibility - host.susceptibility;
    const Eigen::Vector3d dir = b.remanence_direction.norm() > 0.0 ? b.remanence_direction.normalized() : along;
    const Eigen::Vector3d dMr = b.rock.remanence * dir - host.remanence * along;  // [A/m]
    const Eigen::Vector3d source = dchi * H0 + dMr;
    m.pose = b.pose;
    double volume = 0.0;
    switch (b.kind) {
      case BodyKind::ellipsoid: {
        m.size = b.size;
        const Eigen::Matrix3d R = b.pose.linear();
        const Eigen::Vector3d N = demagnetisingFactors(b.size);
        const Eigen::Vector3d local = R.transpose() * source;
        m.magnetisation = R * Eigen::Vector3d(local.array() / (1.0 + dchi * N.array()));
        volume = 4.0 / 3.0 * kPi * b.size.prod();
        break;
      }
      case BodyKind::box:
        m.size = b.size;
        m.magnetisation = source;
        break;
      case BodyKind::vein: {
        const double side = std::isfinite(b.size.x()) ? b.size.x() * std::sqrt(kPi) : 2.0 * kTruncation;
        m.size = Eigen::Vector3d(side, side, b.size.z());
        m.magnetisation = source;
        break;
      }
      case BodyKind::stratum:
        m.size = Eigen::Vector3d(2.0 * kTruncation, 2.0 * kTruncation, b.size.z());
        m.pose.translation() = b.pose * Eigen::Vector3d(0, 0, 0.5 * b.size.z());
        m.magnetisation = source;
        break;
    }
    if (b.kind != BodyKind::ellipsoid)
      volume = m.size.prod();
    m.moment = volume * m.magnetisation;
    magnets_.push_back(m);
  }
}

Eigen::Vector3d MagneticAnomalies::anomaly(const Eigen::Vector3d& p) const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const BodyMagnet& m : magnets_) {
    if (m.magnetisation.squaredNorm() == 0.0)
      continue;
    const Eigen::Matrix3d& R = m.pose.linear();
    const Eigen::Vector3d q = R.transpose() * (p - m.pose.translation());
    if (m.kind == BodyKind::ellipsoid) {
      if ((q.array() / m.size.array()).matrix().squaredNorm() <= 1.0) {
        const Eigen::Vector3d local = R.transpose() * m.magnetisation;
        const Eigen::Vector3d N = demagnetisingFactors(m.size);
        sum += R * Eigen::Vector3d(kMu0 * kTeslaToNanotesla * (local.array() * (1.0 - N.array())));
      } else {
        sum += dipoleField(m.moment, p - m.pose.translation());
      }
    } else {
      sum += R * prismField(m.size, R.transpose() * m.magnetisation, q);
    }
  }
  return sum;
}

}  // namespace geo
}  // namespace unexmin
