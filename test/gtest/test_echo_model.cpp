// EchoModel (cpp/unexmin/sensors/sonar/echo_model.h) on its own, against the documented formula evaluated here:
// the bins, the spreading and absorption loss L(r), the gain A = 10^(G gain / 10), the backscatter law
// cos(theta)^n, the line (sum per bin, gain, saturation at 1), the artifact spreading between neighbouring rays
// (strength kept), and bad parameters -> ParameterError naming the parameter and its value.
#include <unexmin/sensors/sonar/echo_model.h>
#include "expect_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <string>
#include <type_traits>
#include <vector>

namespace unexmin {
namespace test {
namespace {

using sonar::Echo;
using sonar::EchoModel;
using sonar::EchoParams;

/// No spreading and no absorption: L(r) = 1, so a strength is w cos(theta)^n alone.
EchoParams flat(double range_min, double range_max, int nbins)
{
  EchoParams p;
  p.range_min = range_min;
  p.range_max = range_max;
  p.nbins = nbins;
  p.gain = 0.0;
  p.spreading_exponent = 0.0;
  p.absorption = 0.0;
  return p;
}

double sum(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0); }

TEST(EchoModel, BinsSplitTheWindowIntoEqualHalfOpenIntervals)
{
  const EchoModel m(flat(0.5, 4.5, 8));  // w = 0.5 m: bin i = [0.5 + 0.5 i, 1 + 0.5 i)
  EXPECT_DOUBLE_EQ(m.binWidth(), 0.5);
  for (int i = 0; i < 8; ++i) {
    EXPECT_DOUBLE_EQ(m.binCenter(i), 0.75 + 0.5 * i) << i;
    EXPECT_EQ(m.bin(0.75 + 0.5 * i), i);
    EXPECT_EQ(m.bin(0.5 + 0.5 * i + 0.01), i);  // just after the lower edge
    EXPECT_EQ(m.bin(1.0 + 0.5 * i - 0.01), i);  // just before the upper edge
  }
  EXPECT_EQ(m.bin(0.5), 0);      // range_min is in the first bin
  EXPECT_EQ(m.bin(1.0), 1);      // an inner edge belongs to the upper bin
  EXPECT_EQ(m.bin(4.4999), 7);
  EXPECT_EQ(m.bin(4.5), -1);     // range_max is outside
  EXPECT_EQ(m.bin(0.4999), -1);
  EXPECT_EQ(m.bin(-1.0), -1);
  EXPECT_EQ(m.bin(std::numeric_limits<double>::quiet_NaN()), -1);
  EXPECT_EQ(m.bin(std::numeric_limits<double>::infinity()), -1);
}

TEST(EchoModel, LossIsSpreadingRelativeToTheReferenceRangeTimesTwoWayAbsorption)
{
  struct Case { double s, r_ref, alpha, r, expected; };
  // L(r) = (r_ref / r)^s 10^(-2 alpha r / 10), by hand.
  for (const Case& c : {Case{2.0, 1.0, 0.0, 2.0, 0.25}, Case{2.0, 1.0, 0.0, 0.5, 4.0},
                        Case{1.0, 2.0, 0.5, 4.0, 0.5 * std::pow(10.0, -0.4)},  // 2 x 0.5 dB/m x 4 m = 4 dB
                        Case{0.0, 1.0, 1.0, 5.0, 0.1},                         // 10 dB two way
                        Case{2.0, 1.0, 0.1, 2.0, 0.25 * std::pow(10.0, -0.04)},  // the defaults
                        Case{4.0, 3.0, 0.0, 1.5, 16.0}}) {
    EchoParams p;
    p.spreading_exponent = c.s;
    p.reference_range = c.r_ref;
    p.absorption = c.alpha;
    EXPECT_NEAR(EchoModel(p).loss(c.r), c.expected, 1e-12 * c.expected)
        << "s " << c.s << " r_ref " << c.r_ref << " alpha " << c.alpha << " r " << c.r;
  }
}

TEST(EchoModel, GainAmplifiesByItsShareOfTheSpanInDecibels)
{
  struct Case { double gain, span, expected; };
  for (const Case& c : {Case{0.0, 40.0, 1.0}, Case{0.5, 40.0, 100.0}, Case{0.25, 40.0, 10.0},
                        Case{1.0, 30.0, 1000.0}, Case{0.2, 40.0, std::pow(10.0, 0.8)}, Case{1.0, 0.0, 1.0}}) {
    EchoParams p;
    p.gain = c.gain;
    p.gain_span = c.span;
    EXPECT_NEAR(EchoModel(p).amplification(), c.expected, 1e-12 * c.expected) << "gain " << c.gain << " span " << c.span;
  }
}

TEST(EchoModel, StrengthIsTheRayShareTimesCosineToTheNTimesLoss)
{
  for (double n : {0.0, 1.0, 2.0, 3.0, 1.5}) {
    EchoParams p = flat(0.0, 10.0, 10);
    p.backscatter_exponent = n;
    const EchoModel m(p);
    for (double theta_deg : {0.0, 30.0, 60.0, 80.0}) {
      const double c = std::cos(theta_deg * M_PI / 180.0);
      // w = 1 / 4 rays, L = 1.
      EXPECT_NEAR(m.strength(Echo{2.0, c}, 4), std::pow(c, n) / 4.0, 1e-15) << "n " << n << " theta " << theta_deg;
    }
    // cos(theta) is clamped to [0, 1].
    EXPECT_NEAR(m.strength(Echo{2.0, 1.2}, 4), 0.25, 1e-15) << "n " << n;
    if (n > 0.0) {
      EXPECT_EQ(m.strength(Echo{2.0, -0.3}, 4), 0.0) << "n " << n;
    }
  }
  // Lambert (n = 2) at 60 deg with the default loss and 10 rays: 0.25 x (1 / 2.5)^2 x 10^(-0.05) / 10.
  const EchoModel d{EchoParams()};
  EXPECT_NEAR(d.strength(Echo{2.5, 0.5}, 10), 0.25 * 0.16 * std::pow(10.0, -0.05) / 10.0, 1e-15);
  // No ray in the fan counts as one (no division by zero).
  EXPECT_NEAR(d.strength(Echo{2.5, 1.0}, 0), d.strength(Echo{2.5, 1.0}, 1), 1e-15);
}

TEST(EchoModel, LineSumsTheEchoesOfABinAppliesTheGainAndSaturatesAtOne)
{
  EchoParams p = flat(0.0, 4.0, 4);  // bins of 1 m
  p.gain = 0.5;
  p.gain_span = 20.0;                // A = 10
  const EchoModel m(p);
  const std::size_t rays = 100;      // w = 0.01
  std::vector<Echo> echoes = {{1.2, 1.0}, {1.7, 1.0},  // bin 1: 2 x 0.01 -> 0.2 after the gain
                              {2.5, 0.5},              // bin 2: 0.01 x 0.25 -> 0.025
                              {4.0, 1.0}, {-0.1, 1.0}, {7.0, 1.0}};  // outside the window: lost
  for (int k = 0; k < 60; ++k) echoes.push_back({3.5, 1.0});  // bin 3: 0.6 -> 6 -> saturated
  std::vector<float> line = {9.0f};  // resized and overwritten
  m.line(echoes, rays, line);
  ASSERT_EQ(line.size(), 4u);
  EXPECT_EQ(line[0], 0.0f);  // no echo: exactly nothing
  EXPECT_NEAR(line[1], 0.2, 1e-6);
  EXPECT_NEAR(line[2], 0.025, 1e-7);
  EXPECT_EQ(line[3], 1.0f);  // saturated: exactly the ceiling

  // The same by deposit + finish.
  std::vector<double> energy(4, 0.0);
  for (const Echo& e : echoes) m.deposit(e, rays, energy);
  EXPECT_NEAR(energy[1], 0.02, 1e-15);
  EXPECT_NEAR(energy[2], 0.0025, 1e-15);
  EXPECT_NEAR(energy[3], 0.6, 1e-12);
  std::vector<float> again;
  m.finish(energy, again);
  EXPECT_EQ(again, line);  // the same arithmetic: the same floats
}

TEST(EchoModel, SpreadFillsHalfTheWayToEachNeighbourAndKeepsTheStrength)
{
  const EchoModel m(flat(0.0, 10.0, 10));  // bins of 1 m, L = 1, n = 2
  // Two neighbours 3 m apart, head-on, one ray each (strength 1): each keeps half in its own bin and spreads
  // half evenly over the half-way to the other (1.5 m): [2.5, 4] and [4, 5.5].
  std::vector<double> energy(10, 0.0);
  m.spread({{2.5, 1.0}, {5.5, 1.0}}, 1, 5.0, energy);
  const std::vector<double> paired = {0, 0, 0.5 + 0.5 / 3, 1.0 / 3, 1.0 / 3, 0.5 / 3 + 0.5, 0, 0, 0, 0};
  for (int i = 0; i < 10; ++i) EXPECT_NEAR(energy[i], paired[i], 1e-12) << "bin " << i;
  EXPECT_NEAR(sum(energy), 2.0, 1e-12);

  // Farther apart than max_gap, or a ray without echo between them: no spreading, each in its own bin.
  for (const auto& column : {std::vector<Echo>{{2.5, 1.0}, {5.5, 1.0}}, std::vector<Echo>{{2.5, 1.0}, {-1.0, 1.0}, {5.5, 1.0}}}) {
    std::vector<double> e(10, 0.0);
    m.spread(column, 1, column.size() == 2 ? 2.9 : 5.0, e);
    for (int i = 0; i < 10; ++i) EXPECT_NEAR(e[i], i == 2 || i == 5 ? 1.0 : 0.0, 1e-12) << "bin " << i;
  }

  // Three rays of a fan of 8, at incidences (strengths s_k = cos^2 / 8), all paired (gaps 1 and 1.6 m <= 2 m):
  // ray 0 keeps half in bin 1 and spreads half over [1.5, 2]; ray 1 spreads halves over [2, 2.5] and
  // [2.5, 3.3]; ray 2 spreads half over [3.3, 4.1] and keeps half in bin 4.
  const double s0 = 1.0 / 8, s1 = 0.64 / 8, s2 = 0.36 / 8;
  std::vector<double> e(10, 0.0);
  m.spread({{1.5, 1.0}, {2.5, 0.8}, {4.1, 0.6}}, 8, 2.0, e);
  const std::vector<double> three = {0,
                                     s0,
                                     0.5 * s1 + 0.5 * s1 * 0.5 / 0.8,
                                     0.5 * s1 * 0.3 / 0.8 + 0.5 * s2 * 0.7 / 0.8,
                                     0.5 * s2 * 0.1 / 0.8 + 0.5 * s2,
                                     0, 0, 0, 0, 0};
  for (int i = 0; i < 10; ++i) EXPECT_NEAR(e[i], three[i], 1e-12) << "bin " << i;
  EXPECT_NEAR(sum(e), s0 + s1 + s2, 1e-12);
}

TEST(EchoModel, ErrorsAreParameterErrorsUnderTheOneErrorRoot)
{
  static_assert(std::is_base_of<ConfigError, ParameterError>::value, "ParameterError is a ConfigError");
  static_assert(std::is_base_of<Error, ParameterError>::value, "ParameterError is an unexmin::Error");
}

TEST(EchoModel, BadParametersThrowAParameterErrorNamingTheParameterAndItsValue)
{
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  struct Case
  {
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
      {"spreading_exponent", "4.5", [](EchoParams& p) { p.spreading_exponent = 4.5; }},
      {"spreading_exponent", "-0.5", [](EchoParams& p) { p.spreading_exponent = -0.5; }},
      {"reference_range", "0", [](EchoParams& p) { p.reference_range = 0.0; }},
      {"reference_range", "inf", [&](EchoParams& p) { p.reference_range = inf; }},
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
  edge.spreading_exponent = 4.0;
  edge.absorption = 10.0;
  EXPECT_NO_THROW(EchoModel{edge});
  edge.gain = 0.0;
  edge.gain_span = 0.0;
  edge.backscatter_exponent = 0.0;
  edge.spreading_exponent = 0.0;
  edge.absorption = 0.0;
  EXPECT_NO_THROW(EchoModel{edge});
}

}  // namespace
}  // namespace test
}  // namespace unexmin
