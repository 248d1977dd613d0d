// The water's equations (water/seawater.h) against published values: the check values printed with the UNESCO
// algorithms (Fofonoff & Millard 1983, UNESCO Tech. Pap. Mar. Sci. 44), measured densities of pure water (Tanaka et
// al. 2001, Metrologia 38:301) and sound speeds in pure water (Del Grosso & Mader 1972, JASA 52:1442), and the
// fresh-water sound speeds of TEOS-10 quoted in the science-payload reference.
#include <unexmin/water/seawater.h>

#include <gtest/gtest.h>

#include <cmath>

namespace water = unexmin::water;

namespace {

/// The UNESCO check values are given at IPTS-68 temperatures; the functions take ITS-90 (T68 = 1.00024 T90).
double t90(double t68) {
  return t68 / 1.00024;
}

}  // namespace

TEST(Seawater, Eos80MatchesTheUnescoCheckValues) {
  // UNESCO 1983, p. 19: rho(S, T68, p [dbar]) to 1e-5 kg/m^3
  struct Row {
    double s, t, p, rho;
  };
  const Row rows[] = {{0, 5, 0, 999.96675},       {0, 5, 10000, 1044.12802},  {0, 25, 0, 997.04796},
                      {0, 25, 10000, 1037.90204}, {35, 5, 0, 1027.67547},     {35, 5, 10000, 1069.48914},
                      {35, 25, 0, 1023.34306},    {35, 25, 10000, 1062.53817}};
  for (const Row& r : rows)
    EXPECT_NEAR(water::density(r.s, t90(r.t), r.p), r.rho, 2e-5) << "S " << r.s << " T68 " << r.t << " p " << r.p;
}

TEST(Seawater, PureWaterDensityMatchesMeasurements) {
  // Tanaka et al. 2001 (VSMOW, ITS-90): EOS-80's pure water (SMOW, Bigg 1967) agrees within its 0.002 kg/m^3
  struct Row {
    double t, rho;
  };
  for (const Row r : {Row{4.0, 999.9750}, Row{10.0, 999.7026}, Row{20.0, 998.2067}, Row{25.0, 997.0470}})
    EXPECT_NEAR(water::density(0.0, r.t, 0.0), r.rho, 2e-3) << r.t << " degC";
  // the maximum near 4 degC: colder and warmer water is lighter
  EXPECT_GT(water::density(0.0, 4.0, 0.0), water::density(0.0, 1.0, 0.0));
  EXPECT_GT(water::density(0.0, 4.0, 0.0), water::density(0.0, 7.0, 0.0));
}

TEST(Seawater, SoundSpeedMatchesTheCheckValueAndPureWater) {
  // UNESCO 1983, p. 49: c(S = 40, T68 = 40, 10000 dbar) = 1731.995 m/s
  EXPECT_NEAR(water::soundSpeed(40.0, t90(40.0), 10000.0), 1731.995, 1e-3);
  // pure water, 1 atm (Del Grosso & Mader 1972, accuracy 0.015 m/s); Chen & Millero's fit: 0.19 m/s
  struct Row {
    double t, c;
  };
  for (const Row r :
       {Row{0.0, 1402.39}, Row{10.0, 1447.27}, Row{20.0, 1482.35}, Row{25.0, 1496.69}, Row{30.0, 1509.16}})
    EXPECT_NEAR(water::soundSpeed(0.0, r.t, 0.0), r.c, 0.1) << r.t << " degC";
}

TEST(Seawater, FreshWaterSoundSpeedIsNotMackenzies) {
  // TEOS-10 fresh water (science-payload reference): 8 degC 1439.5, 12 degC 1455.3, 23.5 degC 1492.9 m/s. Chen &
  // Millero at S = 0, 0 dbar lies 0.3-0.4 m/s below these (and within 0.02 of Del Grosso's pure water above):
  // within 0.5 m/s.
  struct Row {
    double t, c;
  };
  for (const Row r : {Row{8.0, 1439.5}, Row{12.0, 1455.3}, Row{23.5, 1492.9}}) {
    EXPECT_NEAR(water::soundSpeed(0.0, r.t, 0.0), r.c, 0.5) << r.t << " degC";
    // Mackenzie 1981, made for S 25..40, is 3-4 m/s off in fresh water: the model must not be it
    const double t = r.t;
    const double mackenzie = 1448.96 + 4.591 * t - 5.304e-2 * t * t + 2.374e-4 * t * t * t + 1.340 * (0.0 - 35.0);
    EXPECT_GT(std::abs(water::soundSpeed(0.0, t, 0.0) - mackenzie), 2.0);
  }
  // a sonar set to 1500 m/s in 8 degC fresh water reads ranges 4 % long
  EXPECT_NEAR(1500.0 / water::soundSpeed(0.0, 8.0, 0.0), 1.042, 0.001);
}

TEST(Seawater, PracticalSalinityMatchesPss78AndFallsToZero) {
  // UNESCO 1983, p. 9: R = C / C(35, 15, 0) = 1.888091 at T68 = 40, 10000 dbar is S = 40.0000
  EXPECT_NEAR(water::practicalSalinity(1.888091 * water::kReferenceConductivity, t90(40.0), 10000.0), 40.0, 1e-4);
  // the definition: the conductivity of S = 35 at 15 degC (IPTS-68), 0 dbar (to PSS-78's rt(15) = 1 within 1e-8)
  EXPECT_NEAR(water::practicalSalinity(water::kReferenceConductivity, t90(15.0), 0.0), 35.0, 1e-6);
  // Hill et al. (1986) below S = 2: zero conductivity is zero salinity (plain PSS-78 gives 0.008)
  EXPECT_NEAR(water::practicalSalinity(0.0, 10.0, 0.0), 0.0, 1e-12);
  EXPECT_NEAR(water::practicalSalinity(1.0, 10.0, 0.0), 0.0, 1e-3);
  // and it joins PSS-78 at S = 2 without a jump
  const double c2 = water::conductivityFromSalinity(2.0, 12.0, 0.0);
  EXPECT_NEAR(water::practicalSalinity(c2 * (1 - 1e-9), 12.0, 0.0),
              water::practicalSalinity(c2 * (1 + 1e-9), 12.0, 0.0), 1e-5);
  // warmer water of one salinity conducts more: EC_T = EC_25 (1 + alpha (T - 25)), alpha about 0.02 /degC for
  // natural waters (NaCl 0.021, KCl 0.0191)
  const double c25 = water::conductivityFromSalinity(0.3, 25.0, 0.0),
               c10 = water::conductivityFromSalinity(0.3, 10.0, 0.0);
  EXPECT_NEAR((1.0 - c10 / c25) / 15.0, 0.02, 0.002);
}

TEST(Seawater, ConductivityFromSalinityInvertsIt) {
  for (double s : {0.05, 0.5, 1.99, 2.01, 5.0, 20.0, 35.0, 40.0})
    for (double t : {0.5, 8.0, 23.5, 35.0})
      EXPECT_NEAR(water::practicalSalinity(water::conductivityFromSalinity(s, t, 300.0), t, 300.0), s, 1e-7)
          << "S " << s << " T " << t;
}
