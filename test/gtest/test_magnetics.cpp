// Magnetic anomalies of the geology (cpp/unexmin/geo/magnetics.h) against closed forms computed here: the field
// vector from intensity, inclination and declination; demagnetising factors of a sphere and of spheroids (Osborn
// 1945); a sphere against the dipole of its induced moment (and science-payload.md's worked numbers); a prism against
// a fine sum of dipoles over its volume and its far field against one dipole; a cube's centre; a rotated box; the
// contrast with the host; remanence; a vein's disc; a stratum against the field of two charged square plates.
#include <unexmin/geo/magnetics.h>

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace unexmin {
namespace geo {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMu0Test = 4e-7 * kPi;  // [T m/A], written here

Rock rockOf(double chi, double remanence = 0.0) {
  Rock r;
  r.susceptibility = chi;
  r.remanence = remanence;
  return r;
}

Body bodyOf(BodyKind kind, const Eigen::Vector3d& centre, const Eigen::Vector3d& size, const Rock& rock,
            const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity()) {
  Body b;
  b.name = "b";
  b.kind = kind;
  b.pose = Eigen::Isometry3d::Identity();
  b.pose.linear() = rotation;
  b.pose.translation() = centre;
  b.size = size;
  b.rock = rock;
  return b;
}

std::shared_ptr<const Geology> geologyOf(const Body& b, const Rock& host = rockOf(0.0)) {
  return std::make_shared<Geology>(host, std::vector<Body>{b});
}

/// mu0 / (4 pi r^3) (3 (m.r^) r^ - m) [nT] of moment m [A m^2] at offset r [m], written here.
Eigen::Vector3d dipole(const Eigen::Vector3d& m, const Eigen::Vector3d& r) {
  const double d = r.norm();
  const Eigen::Vector3d u = r / d;
  return 1e9 * kMu0Test / (4 * kPi * d * d * d) * (3 * m.dot(u) * u - m);
}

const Eigen::Vector3d kF(1500.0, 18000.0, -45000.0);  // [nT] an inclined field, ENU

TEST(Magnetics, FieldFromIntensityInclinationAndDeclination) {
  const double F = 52750.0, I = 75.0, D = 10.0;  // Kaatiala (science-payload.md)
  const Eigen::Vector3d b = fieldFromAngles(F, I, D);
  EXPECT_NEAR(b.norm(), F, 1e-9 * F);
  EXPECT_NEAR(std::atan2(-b.z(), b.head<2>().norm()) * 180 / kPi, I, 1e-9);  // down positive
  EXPECT_NEAR(std::atan2(b.x(), b.y()) * 180 / kPi, D, 1e-9);                // east of north
  // The world's default (sim/world_config.h, [mG]) is this site's field within 1 %
  EXPECT_LT((fieldFromAngles(52600.0, 75.0, 10.0) - Eigen::Vector3d(2400, 13400, -50800)).norm(), 0.01 * F);
}

TEST(Magnetics, DemagnetisingFactorsOfSphereAndSpheroids) {
  EXPECT_NEAR(carlsonRD(1.0, 1.0, 1.0), 1.0, 1e-14);
  const Eigen::Vector3d sphere = demagnetisingFactors(Eigen::Vector3d::Constant(2.5));
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(sphere[i], 1.0 / 3.0, 1e-13);
  // prolate a > b = c, m = a / b (Osborn 1945): N_a = (m / sqrt(m^2 - 1) ln(m + sqrt(m^2 - 1)) - 1) / (m^2 - 1)
  const double m = 3.0, root = std::sqrt(m * m - 1);
  const double na = (m / root * std::log(m + root) - 1) / (m * m - 1);
  const Eigen::Vector3d prolate = demagnetisingFactors(Eigen::Vector3d(3.0, 1.0, 1.0));
  EXPECT_NEAR(prolate.x(), na, 1e-12);
  EXPECT_NEAR(prolate.y(), (1 - na) / 2, 1e-12);
  // oblate a = b > c, m = a / c: N_c = m^2 / (m^2 - 1) (1 - asin(sqrt(m^2 - 1) / m) / sqrt(m^2 - 1))
  const double mo = 4.0, ro = std::sqrt(mo * mo - 1);
  const double nc = mo * mo / (mo * mo - 1) * (1 - std::asin(ro / mo) / ro);
  const Eigen::Vector3d oblate = demagnetisingFactors(Eigen::Vector3d(4.0, 4.0, 1.0));
  EXPECT_NEAR(oblate.z(), nc, 1e-12);
  EXPECT_NEAR(oblate.x(), (1 - nc) / 2, 1e-12);
  const Eigen::Vector3d triaxial = demagnetisingFactors(Eigen::Vector3d(3.0, 2.0, 0.5));
  EXPECT_NEAR(triaxial.sum(), 1.0, 1e-12);
  EXPECT_TRUE(triaxial.x() < triaxial.y() && triaxial.y() < triaxial.z());  // the shortest axis demagnetises most
}

TEST(Magnetics, SphereIsTheDipoleOfItsInducedMoment) {
  // science-payload.md: F = 49 000 nT, a = 1 m, r = 2 m on the axis: chi 0.01 -> ~41 nT, 0.1 -> ~395 nT
  const Eigen::Vector3d F(0, 0, -49000.0);
  for (const auto& [chi, expected] : {std::pair<double, double>{0.01, 41.0}, {0.1, 395.0}}) {
    const MagneticAnomalies a(
        F, geologyOf(bodyOf(BodyKind::ellipsoid, Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), rockOf(chi))));
    const Eigen::Vector3d on_axis = a.anomaly(Eigen::Vector3d(0, 0, -2.0));
    EXPECT_NEAR(on_axis.z(), -expected, 1.0) << chi;                      // along the field: it adds to it
    const Eigen::Vector3d M = 3 * chi / (3 + chi) * F * 1e-9 / kMu0Test;  // [A/m]
    const Eigen::Vector3d m = 4.0 / 3.0 * kPi * M;
    EXPECT_LT((on_axis - dipole(m, Eigen::Vector3d(0, 0, -2.0))).norm(), 1e-9 * on_axis.norm());
    const Eigen::Vector3d off(1.3, -0.7, 1.9);
    EXPECT_LT((a.anomaly(off) - dipole(m, off)).norm(), 1e-9 * dipole(m, off).norm());
    // inside, uniform: B = mu0 (1 - 1/3) M
    EXPECT_LT((a.anomaly(Eigen::Vector3d(0.2, 0.1, -0.3)) - 2.0 / 3.0 * kMu0Test * M * 1e9).norm(), 1e-9 * F.norm());
    EXPECT_LT((a.field(off) - F - dipole(m, off)).norm(), 1e-9 * F.norm());
  }
}

TEST(Magnetics, TheContrastWithTheHostIsWhatShows) {
  const Body b = bodyOf(BodyKind::ellipsoid, Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), rockOf(0.05));
  EXPECT_LT(MagneticAnomalies(kF, geologyOf(b, rockOf(0.05))).anomaly(Eigen::Vector3d(0, 0, 3)).norm(), 1e-12);
  const MagneticAnomalies contrast(kF, geologyOf(b, rockOf(0.02)));
  const double chi = 0.03;
  const Eigen::Vector3d m = 4.0 / 3.0 * kPi * 3 * chi / (3 + chi) * kF * 1e-9 / kMu0Test;
  EXPECT_LT((contrast.anomaly(Eigen::Vector3d(0, 0, 3)) - dipole(m, Eigen::Vector3d(0, 0, 3))).norm(), 1e-9);
  EXPECT_LT(MagneticAnomalies(kF, nullptr).anomaly(Eigen::Vector3d(0, 0, 3)).norm(), 1e-15);
}

TEST(Magnetics, RemanenceAlongItsDirectionOrTheAmbientField) {
  Body b = bodyOf(BodyKind::ellipsoid, Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(0.5), rockOf(0.0, 2.0));
  const Eigen::Vector3d p(0.4, 1.5, 0.9);
  const double V = 4.0 / 3.0 * kPi * 0.125;
  EXPECT_LT((MagneticAnomalies(kF, geologyOf(b)).anomaly(p) - dipole(V * 2.0 * kF.normalized(), p)).norm(), 1e-9);
  b.remanence_direction = Eigen::Vector3d(1, 0, 0);
  EXPECT_LT((MagneticAnomalies(kF, geologyOf(b)).anomaly(p) - dipole(Eigen::Vector3d(V * 2.0, 0, 0), p)).norm(), 1e-9);
}

/// Field [nT] of `n` x `n` x `n` (per unit length of the box's longest side) point dipoles filling a box of `size`
/// magnetised with M, at q (box frame).
Eigen::Vector3d dipoleSum(const Eigen::Vector3d& size, const Eigen::Vector3d& M, const Eigen::Vector3d& q, double h) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  const Eigen::Vector3i n = (size / h).array().round().cast<int>();
  const Eigen::Vector3d cell = size.array() / n.cast<double>().array();
  const Eigen::Vector3d m = M * cell.prod();
  for (int i = 0; i < n.x(); ++i)
    for (int j = 0; j < n.y(); ++j)
      for (int k = 0; k < n.z(); ++k) {
        const Eigen::Vector3d c =
            -0.5 * size + Eigen::Vector3d((i + 0.5) * cell.x(), (j + 0.5) * cell.y(), (k + 0.5) * cell.z());
        sum += dipole(m, q - c);
      }
  return sum;
}

TEST(Magnetics, PrismAgainstASumOfDipolesOverItsVolume) {
  const Eigen::Vector3d size(2.0, 1.0, 0.6), M(3.0, -1.0, 5.0);  // [m], [A/m]
  for (const Eigen::Vector3d& q :
       {Eigen::Vector3d(1.8, 0.9, 0.8), Eigen::Vector3d(-0.3, 0.2, -1.2), Eigen::Vector3d(2.5, -1.5, 0.1)}) {
    const Eigen::Vector3d exact = prismField(size, M, q);
    const Eigen::Vector3d sum = dipoleSum(size, M, q, 0.02);
    EXPECT_LT((exact - sum).norm(), 0.01 * sum.norm())
        << q.transpose() << ": " << exact.transpose() << " vs " << sum.transpose();
  }
  // far away: the dipole of moment V M
  const Eigen::Vector3d far(60.0, -45.0, 70.0);
  const Eigen::Vector3d d = dipole(size.prod() * M, far);
  EXPECT_LT((prismField(size, M, far) - d).norm(), 1e-3 * d.norm());
  // at a cube's centre N = 1/3 on every axis: B = mu0 (M - M/3)
  EXPECT_LT((prismField(Eigen::Vector3d::Ones(), M, Eigen::Vector3d::Zero()) - 2.0 / 3.0 * kMu0Test * M * 1e9).norm(),
            1e-9 * M.norm());
}

TEST(Magnetics, ARotatedBoxGivesTheRotatedField) {
  const Eigen::Matrix3d Q = (Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(-0.4, Eigen::Vector3d(1, 1, 0).normalized()))
                                .toRotationMatrix();
  const Eigen::Vector3d c(5.0, -3.0, -20.0), size(4.0, 1.5, 2.5), p(7.5, -1.0, -17.0);
  const Rock ore = rockOf(0.08);
  const MagneticAnomalies rotated(kF, geologyOf(bodyOf(BodyKind::box, c, size, ore, Q)));
  // the same body unrotated, seen in its own axes: field Q^T F, point Q^T (p - c)
  const MagneticAnomalies upright(Q.transpose() * kF,
                                  geologyOf(bodyOf(BodyKind::box, Eigen::Vector3d::Zero(), size, ore)));
  const Eigen::Vector3d expected = Q * upright.anomaly(Q.transpose() * (p - c));
  EXPECT_LT((rotated.anomaly(p) - expected).norm(), 1e-9 * expected.norm());
  EXPECT_GT(expected.norm(), 10.0);  // a real anomaly [nT]
  // and not the unrotated box's field
  const MagneticAnomalies unrotated(kF, geologyOf(bodyOf(BodyKind::box, c, size, ore)));
  EXPECT_GT((unrotated.anomaly(p) - expected).norm(), 0.05 * expected.norm());
}

TEST(Magnetics, AVeinIsASquarePrismOfItsDiscsArea) {
  Body vein = bodyOf(BodyKind::vein, Eigen::Vector3d::Zero(), Eigen::Vector3d(3.0, 3.0, 0.4), rockOf(0.05));
  const Eigen::Vector3d p(1.0, 0.5, 2.0);
  const double side = 3.0 * std::sqrt(kPi);
  const MagneticAnomalies a(kF, geologyOf(vein));
  const Eigen::Vector3d M = 0.05 * kF * 1e-9 / kMu0Test;
  EXPECT_LT((a.anomaly(p) - prismField(Eigen::Vector3d(side, side, 0.4), M, p)).norm(), 1e-9 * a.anomaly(p).norm());
  const Eigen::Vector3d far(300.0, 200.0, 250.0);
  const Eigen::Vector3d d = dipole(kPi * 9.0 * 0.4 * M, far);
  EXPECT_LT((a.anomaly(far) - d).norm(), 1e-3 * d.norm());
}

TEST(Magnetics, AStratumIsASlabTruncatedAtItsDocumentedExtent) {
  // Horizontal stratum, base at z = 0, thickness t, magnetised vertically (a vertical ambient field). Only its faces
  // carry charge: +M on top (z = t), -M below. On the axis at height z above the top, a square plate of side 2L
  // subtends the solid angle 4 atan(L^2 / (d sqrt(2 L^2 + d^2))) at distance d: B_z = mu0 M / (4 pi) (Om(z - t) -
  // Om(z)) -- a few nT of an unbounded slab's zero, from the 1 km edges.
  const double t = 5.0, chi = 0.1, L = kTruncation;
  const Eigen::Vector3d F(0, 0, -50000.0);
  const MagneticAnomalies a(F, geologyOf(bodyOf(BodyKind::stratum, Eigen::Vector3d::Zero(),
                                                Eigen::Vector3d(INFINITY, INFINITY, t), rockOf(chi))));
  const double M = chi * F.z() * 1e-9 / kMu0Test;
  auto omega = [&](double d) { return 4 * std::atan(L * L / (d * std::sqrt(2 * L * L + d * d))); };
  for (double z : {t + 3.0, t + 40.0}) {
    const double expected = 1e9 * kMu0Test * M / (4 * kPi) * (omega(z - t) - omega(z));
    const Eigen::Vector3d b = a.anomaly(Eigen::Vector3d(0, 0, z));
    EXPECT_NEAR(b.z(), expected, 1e-6 * std::abs(expected) + 1e-9) << z;
    EXPECT_LT(b.head<2>().norm(), 1e-6);
  }
  // inside the slab, far from its edges: H = -M, so B = mu0 (H + M) = 0; the anomaly there is -mu0 M + mu0 M = 0 as
  // well within a few nT (the edges), unlike a wrong sign which gives 2 mu0 M
  EXPECT_LT(std::abs(a.anomaly(Eigen::Vector3d(0, 0, 0.5 * t)).z()), 0.01 * std::abs(1e9 * kMu0Test * M));
}

}  // namespace
}  // namespace geo
}  // namespace unexmin
