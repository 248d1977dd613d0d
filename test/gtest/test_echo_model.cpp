// EchoModel (cpp/unexmin/sensors/sonar/echo_model.h) on its own, against the documented sonar equation evaluated
// here: the bins, TL(r) and TVG(r), the gain G = gain x span [dB], the echo level of a ray (source level, spreading,
// absorption, backscatter cos(theta)^n, footprint), output level and 8-bit quantisation, the line (power summed
// per bin), the artifact spreading between neighbouring rays (power kept), and bad parameters -> ParameterError
// naming the parameter and its value.
#include <unexmin/sensors/sonar/echo_model.h>
#include "expect_error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

namespace unexmin {
namespace test {
namespace {

using sensors::sonar::Echo;
using sensors::sonar::EchoModel;
using sensors::sonar::EchoParams;

/// No absorption and no gain.
EchoParams flat(double range_min, double range_max, int nbins) {
  EchoParams p;
  p.range_min = range_min;
  p.range_max = range_max;
  p.nbins = nbins;
  p.gain = 0.0;
  p.absorption = 0.0;
  return p;
}

double sum(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0);
}

TEST(EchoModel, BinsSplitTheWindowIntoEqualHalfOpenIntervals) {
  const EchoModel m(flat(0.5, 4.5, 8));  // w = 0.5 m: bin i = [0.5 + 0.5 i, 1 + 0.5 i)
  EXPECT_DOUBLE_EQ(m.binWidth(), 0.5);
  for (int i = 0; i < 8; ++i) {
    EXPECT_DOUBLE_EQ(m.binCenter(i), 0.75 + 0.5 * i) << i;
    EXPECT_EQ(m.bin(0.75 + 0.5 * i), i);
    EXPECT_EQ(m.bin(0.5 + 0.5 * i + 0.01), i);  // just after the lower edge
    EXPECT_EQ(m.bin(1.0 + 0.5 * i - 0.01), i);  // just before the upper edge
  }
  EXPECT_EQ(m.bin(0.5), 0);  // range_min is in the first bin
  EXPECT_EQ(m.bin(1.0), 1);  // an inner edge belongs to the upper bin
  EXPECT_EQ(m.bin(4.4999), 7);
  EXPECT_EQ(m.bin(4.5), -1);  // range_max is outside
  EXPECT_EQ(m.bin(0.4999), -1);
  EXPECT_EQ(m.bin(-1.0), -1);
  EXPECT_EQ(m.bin(std::numeric_limits<double>::quiet_NaN()), -1);
  EXPECT_EQ(m.bin(std::numeric_limits<double>::infinity()), -1);
}

TEST(EchoModel, TransmissionLossIsSphericalSpreadingPlusAbsorptionAndTheTvgUndoesItsConfiguredShare) {
  struct Case {
    double alpha, k, r, tl, tvg;
  };
  // TL = 20 log10 r + alpha r, TVG = k log10 r + 2 alpha r, by hand.
  for (const Case& c :
       {Case{0.0, 20.0, 10.0, 20.0, 20.0}, Case{0.0, 40.0, 100.0, 40.0, 80.0}, Case{0.5, 30.0, 1.0, 0.5, 1.0},
        Case{0.1, 20.0, 0.1, -20.0 + 0.01, -20.0 + 0.02}, Case{1.0, 0.0, 1000.0, 60.0 + 1000.0, 2000.0}}) {
    EchoParams p;
    p.absorption = c.alpha;
    p.tvg_spreading = c.k;
    const EchoModel m(p);
    EXPECT_NEAR(m.transmissionLoss(c.r), c.tl, 1e-9) << "alpha " << c.alpha << " r " << c.r;
    EXPECT_NEAR(m.tvg(c.r), c.tvg, 1e-9) << "alpha " << c.alpha << " k " << c.k << " r " << c.r;
  }
}

TEST(EchoModel, GainIsItsShareOfTheSpanInDecibels) {
  struct Case {
    double gain, span, expected;
  };
  for (const Case& c : {Case{0.0, 40.0, 0.0}, Case{0.5, 40.0, 20.0}, Case{0.2, 40.0, 8.0}, Case{1.0, 30.0, 30.0},
                        Case{1.0, 0.0, 0.0}}) {
    EchoParams p;
    p.gain = c.gain;
    p.gain_span = c.span;
    EXPECT_NEAR(EchoModel(p).gainDb(), c.expected, 1e-12) << "gain " << c.gain << " span " << c.span;
  }
}

TEST(EchoModel, EchoLevelIsTheSonarEquationWithTheRaysFootprint) {
  // By hand: SL 200 dB, r = 2 m, no absorption, BS0 -20 dB, n = 2, cos 0.5, Omega 0.04 sr over 4 rays, extra 0:
  // 2 TL = 40 log10 2 = 12.041 dB; BS = -20 + 20 log10 0.5 = -26.021 dB; A = 4 x 0.01 / 0.5 = 0.08 m^2 -> -10.969 dB.
  EchoParams p = flat(0.0, 10.0, 10);
  p.beam_solid_angle = 0.04;
  const EchoModel m(p);
  EXPECT_NEAR(m.echoLevel(Echo{2.0, 0.5}, 4), 200.0 - 12.0412 - 26.0206 - 10.9691, 1e-3);
  // The power is the same as a product of the linear factors: SL r^-4 BS0 cos^n (r^2 Omega / N / cos).
  for (double n : {0.0, 1.0, 2.0, 3.5}) {
    EchoParams q = p;
    q.backscatter_exponent = n;
    q.absorption = 0.2;
    const EchoModel mq(q);
    for (double r : {0.5, 1.0, 3.0, 17.0}) {
      for (double c : {1.0, 0.8, 0.3}) {
        const double expected = 1e20 * std::pow(r, -4) * std::pow(10.0, -2 * 0.2 * r / 10) * 0.01 * std::pow(c, n) *
                                (r * r * 0.04 / 4 / c) * std::pow(10.0, -0.3);  // extra -3 dB
        EXPECT_NEAR(mq.strength(Echo{r, c, -3.0}, 4), expected, 1e-9 * expected)
            << "n " << n << " r " << r << " c " << c;
      }
    }
  }
  // Grazing or behind: no echo.
  EXPECT_EQ(m.strength(Echo{2.0, 0.0}, 4), 0.0);
  EXPECT_EQ(m.strength(Echo{2.0, -0.3}, 4), 0.0);
  // cos above 1 counts as 1; no ray in the fan counts as one (no division by zero).
  EXPECT_NEAR(m.strength(Echo{2.0, 1.2}, 4), m.strength(Echo{2.0, 1.0}, 4), 1e-9 * m.strength(Echo{2.0, 1.0}, 4));
  EXPECT_NEAR(m.strength(Echo{2.5, 1.0}, 0), m.strength(Echo{2.5, 1.0}, 1), 1e-9 * m.strength(Echo{2.5, 1.0}, 1));
}

TEST(EchoModel, ReachesIsTheStrengthAgainstAPowerOnEitherSideOfIt) {
  // reaches(e, rays, P) == (strength >= P) for powers just below and above the expected strength computed here
  // (the linear factors as above, absorption 0.2 dB/m, window 0..20 m): the quick answers without the absorption
  // must agree with the exact one at every range, including echoes beyond the window.
  EchoParams p = flat(0.0, 20.0, 10);
  p.beam_solid_angle = 0.04;
  p.absorption = 0.2;
  const EchoModel m(p);
  for (double r : {0.5, 3.0, 17.0, 19.99, 25.0}) {
    for (double c : {1.0, 0.3, 0.0}) {
      for (double extra : {0.0, -1.83}) {
        const double expected = c > 0.0 ? 1e20 * std::pow(r, -4) * std::pow(10.0, -2 * 0.2 * r / 10) * 0.01 * c * c *
                                              (r * r * 0.04 / c) * std::pow(10.0, extra / 10)
                                        : 0.0;
        const Echo e{r, c, extra};
        EXPECT_EQ(m.reaches(e, 1, expected * (1 - 1e-6)), c > 0.0) << "r " << r << " c " << c;
        EXPECT_FALSE(m.reaches(e, 1, expected * (1 + 1e-6) + 1e-300)) << "r " << r << " c " << c;
        EXPECT_EQ(m.reaches(e, 1, expected * 1e-3), c > 0.0) << "r " << r << " c " << c;    // far below: quick yes
        EXPECT_FALSE(m.reaches(e, 1, expected * 1e3 + 1e-300)) << "r " << r << " c " << c;  // far above: quick no
      }
    }
  }
}

TEST(EchoModel, OutputLevelAddsGainAndTvgAndQuantisesToTheCodes) {
  EchoParams p = flat(0.0, 10.0, 10);
  p.gain = 0.25;  // G = 10 dB
  p.absorption = 0.5;
  p.tvg_spreading = 30.0;  // TVG(10 m) = 30 + 10 = 40 dB
  p.display_min = 100.0;
  p.display_span = 51.0;  // 0.2 dB per code
  p.levels = 255;
  const EchoModel m(p);
  EXPECT_DOUBLE_EQ(m.step(), 0.2);
  EXPECT_NEAR(m.outputLevel(1e8, 10.0), 80.0 + 10.0 + 40.0, 1e-9);
  EXPECT_EQ(m.outputLevel(0.0, 10.0), -std::numeric_limits<double>::infinity());
  EXPECT_NEAR(m.inputPower(130.0, 10.0), 1e8, 1e-3);
  // code = round((L - 100) / 0.2): 130 dB -> 150; 130.09 -> 150; 130.11 -> 151; below 100 -> 0; above 151 -> 255.
  EXPECT_FLOAT_EQ(m.quantise(130.0), 150.0f / 255.0f);
  EXPECT_FLOAT_EQ(m.quantise(130.09), 150.0f / 255.0f);
  EXPECT_FLOAT_EQ(m.quantise(130.11), 151.0f / 255.0f);
  EXPECT_EQ(m.quantise(99.0), 0.0f);
  EXPECT_EQ(m.quantise(-std::numeric_limits<double>::infinity()), 0.0f);
  EXPECT_EQ(m.quantise(170.0), 1.0f);

  // One echo alone at its own range (the M3's return): the same code as its level through gain and TVG at r,
  // for the default TVG (k = 20: the spreading cancels) and another (k = 30), away from the code edges.
  for (double k : {20.0, 30.0}) {
    EchoParams q = flat(0.0, 100.0, 1);
    q.tvg_spreading = k;
    q.absorption = 0.3;
    q.gain = 0.5;
    const EchoModel mq(q);
    for (double r : {0.7, 3.0, 12.0, 40.0}) {
      for (double c : {1.0, 0.6, 0.2}) {
        const Echo e{r, c, -2.0};
        const double level = mq.outputLevel(mq.strength(e, 3), r);
        const double x = (level - q.display_min) / mq.step();
        if (std::abs(x - std::floor(x) - 0.5) < 1e-6)
          continue;  // on an edge: either code
        EXPECT_EQ(mq.echoCode(e, 3), static_cast<int>(std::lround(mq.quantise(level) * 255.0)))
            << "k " << k << " r " << r << " c " << c;
      }
    }
  }
}

TEST(EchoModel, LineSumsThePowerOfABinThenGainTvgAndQuantisation) {
  EchoParams p = flat(0.0, 4.0, 4);  // bins of 1 m, centres 0.5, 1.5, 2.5, 3.5
  p.gain = 0.5;
  p.gain_span = 20.0;  // G = 10 dB
  const EchoModel m(p);
  const std::size_t rays = 100;
  std::vector<Echo> echoes = {{1.2, 1.0}, {1.7, 1.0},                // bin 1
                              {2.5, 0.5},                            // bin 2
                              {4.0, 1.0}, {-0.1, 1.0}, {7.0, 1.0}};  // outside the window: lost
  for (int k = 0; k < 60; ++k)
    echoes.push_back({3.5, 1.0});    // bin 3
  std::vector<float> line = {9.0f};  // resized and overwritten
  m.line(echoes, rays, line);
  ASSERT_EQ(line.size(), 4u);
  const auto expected = [&](double power, double centre) {
    const double level = 10 * std::log10(power) + 10.0 + 20 * std::log10(centre);  // + G + TVG (alpha 0)
    return std::clamp(std::round((level - 125.0) / 80.0 * 255.0), 0.0, 255.0) / 255.0;
  };
  EXPECT_EQ(line[0], 0.0f);  // no echo: exactly nothing
  const double b1 = m.strength({1.2, 1.0}, rays) + m.strength({1.7, 1.0}, rays);
  EXPECT_NEAR(line[1], expected(b1, 1.5), 1e-6);
  EXPECT_NEAR(line[2], expected(m.strength({2.5, 0.5}, rays), 2.5), 1e-6);
  EXPECT_NEAR(line[3], expected(60 * m.strength({3.5, 1.0}, rays), 3.5), 1e-6);
  EXPECT_GT(line[1], 0.0f);
  EXPECT_LT(line[3], 1.0f);

  // The same by deposit + finish.
  std::vector<double> energy(4, 0.0);
  for (const Echo& e : echoes)
    m.deposit(e, rays, energy);
  EXPECT_NEAR(energy[1], b1, 1e-12 * b1);
  std::vector<float> again;
  m.finish(energy, again);
  EXPECT_EQ(again, line);  // the same arithmetic: the same floats
}

TEST(EchoModel, SpreadFillsHalfTheWayToEachNeighbourAndKeepsTheStrength) {
  const EchoModel m(flat(0.0, 10.0, 10));  // bins of 1 m
  // Two neighbours 3 m apart, head-on, one ray each (powers a, b): each keeps half in its own bin and spreads
  // half evenly over the half-way to the other (1.5 m): [2.5, 4] and [4, 5.5].
  std::vector<double> energy(10, 0.0);
  m.spread({{2.5, 1.0}, {5.5, 1.0}}, 1, 5.0, energy);
  const double a = m.strength({2.5, 1.0}, 1), b = m.strength({5.5, 1.0}, 1);
  const std::vector<double> paired = {0, 0, 0.5 * a + 0.5 * a / 3, a / 3, b / 3, 0.5 * b / 3 + 0.5 * b, 0, 0, 0, 0};
  for (int i = 0; i < 10; ++i)
    EXPECT_NEAR(energy[i], paired[i], 1e-12 * a) << "bin " << i;
  EXPECT_NEAR(sum(energy), a + b, 1e-12 * a);

  // Farther apart than max_gap, or a ray without echo between them: no spreading, each in its own bin.
  for (const auto& column :
       {std::vector<Echo>{{2.5, 1.0}, {5.5, 1.0}}, std::vector<Echo>{{2.5, 1.0}, {-1.0, 1.0}, {5.5, 1.0}}}) {
    std::vector<double> e(10, 0.0);
    m.spread(column, 1, column.size() == 2 ? 2.9 : 5.0, e);
    for (int i = 0; i < 10; ++i)
      EXPECT_NEAR(e[i], i == 2 ? a : i == 5 ? b : 0.0, 1e-12 * a) << "bin " << i;
  }

  // Three rays of a fan of 8, at incidences (powers s_k from the model), all paired (gaps 1 and 1.6 m <= 2 m):
  // ray 0 keeps half in bin 1 and spreads half over [1.5, 2]; ray 1 spreads halves over [2, 2.5] and
  // [2.5, 3.3]; ray 2 spreads half over [3.3, 4.1] and keeps half in bin 4.
  const double s0 = m.strength({1.5, 1.0}, 8), s1 = m.strength({2.5, 0.8}, 8), s2 = m.strength({4.1, 0.6}, 8);
  std::vector<double> e(10, 0.0);
  m.spread({{1.5, 1.0}, {2.5, 0.8}, {4.1, 0.6}}, 8, 2.0, e);
  const std::vector<double> three = {0,
                                     s0,
                                     0.5 * s1 + 0.5 * s1 * 0.5 / 0.8,
                                     0.5 * s1 * 0.3 / 0.8 + 0.5 * s2 * 0.7 / 0.8,
                                     0.5 * s2 * 0.1 / 0.8 + 0.5 * s2,
                                     0,
                                     0,
                                     0,
                                     0,
                                     0};
  for (int i = 0; i < 10; ++i)
    EXPECT_NEAR(e[i], three[i], 1e-12 * s0) << "bin " << i;
  EXPECT_NEAR(sum(e), s0 + s1 + s2, 1e-12 * s0);
}

TEST(EchoModel, BadParametersThrowAParameterErrorNamingTheParameterAndItsValue) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  struct Case {
    std::string name, value;
    std::function<void(EchoParams&)> set;
  };
  const std::vector<Case> cases = {
      {"range_min", "-0.1", [](EchoParams& p) { p.range_min = -0.1; }},
      {"range_min", "nan", [&](EchoParams& p) { p.range_min = nan; }},
      {"range_max", "0.3", [](EchoParams& p) { p.range_max = 0.3; }},  // = range_min
      {"range_max", "0.2", [](EchoParams& p) { p.range_max = 0.2; }},
      {"range_max", "inf", [&](EchoParams& p) { p.range_max = inf; }},
      {"nbins", "0", [](EchoParams& p) { p.nbins = 0; }},
      {"nbins", "-5", [](EchoParams& p) { p.nbins = -5; }},
      {"gain", "-0.01", [](EchoParams& p) { p.gain = -0.01; }},
      {"gain", "1.5", [](EchoParams& p) { p.gain = 1.5; }},
      {"gain", "nan", [&](EchoParams& p) { p.gain = nan; }},
      {"gain_span", "-1", [](EchoParams& p) { p.gain_span = -1.0; }},
      {"gain_span", "130", [](EchoParams& p) { p.gain_span = 130.0; }},
      {"backscatter_exponent", "-1", [](EchoParams& p) { p.backscatter_exponent = -1.0; }},
      {"backscatter_exponent", "11", [](EchoParams& p) { p.backscatter_exponent = 11.0; }},
      {"backscatter_exponent", "nan", [&](EchoParams& p) { p.backscatter_exponent = nan; }},
      {"source_level", "90", [](EchoParams& p) { p.source_level = 90.0; }},
      {"source_level", "nan", [&](EchoParams& p) { p.source_level = nan; }},
      {"backscatter_strength", "5", [](EchoParams& p) { p.backscatter_strength = 5.0; }},
      {"beam_solid_angle", "0", [](EchoParams& p) { p.beam_solid_angle = 0.0; }},
      {"tvg_spreading", "70", [](EchoParams& p) { p.tvg_spreading = 70.0; }},
      {"display_min", "inf", [&](EchoParams& p) { p.display_min = inf; }},
      {"display_span", "0", [](EchoParams& p) { p.display_span = 0.0; }},
      {"levels", "0", [](EchoParams& p) { p.levels = 0; }},
      {"absorption", "-0.1", [](EchoParams& p) { p.absorption = -0.1; }},
      {"absorption", "12", [](EchoParams& p) { p.absorption = 12.0; }},
      {"absorption", "nan", [&](EchoParams& p) { p.absorption = nan; }},
  };
  for (const Case& c : cases) {
    EchoParams p;
    c.set(p);
    const std::string m = thrownMessage([&] { EchoModel model(p); });
    EXPECT_TRUE(contains(m, c.name + " = " + c.value)) << c.name << " = " << c.value << ": " << m;
    EXPECT_TRUE(contains(m, "expected")) << m;
  }
  // The edges of the accepted ranges are accepted.
  EchoParams edge;
  edge.range_min = 0.0;
  edge.nbins = 1;
  edge.gain = 1.0;
  edge.gain_span = 120.0;
  edge.backscatter_exponent = 10.0;
  edge.tvg_spreading = 60.0;
  edge.absorption = 10.0;
  EXPECT_NO_THROW(EchoModel{edge});
  edge.gain = 0.0;
  edge.gain_span = 0.0;
  edge.backscatter_exponent = 0.0;
  edge.tvg_spreading = 0.0;
  edge.absorption = 0.0;
  EXPECT_NO_THROW(EchoModel{edge});
}

}  // namespace
}  // namespace test
}  // namespace unexmin
