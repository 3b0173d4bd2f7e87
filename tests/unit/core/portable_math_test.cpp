// portable:: against the C library's long double functions (a wider reference than any double
// result): within a few units in the last place over the ranges the surfacing uses, and the
// special values as C defines them. (That the results do not depend on the CPU's features is
// SurfaceCli.ASketchSurfacesToTheSameBitsWhicheverMathTheCpuGets.)

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <random>

#include "surfacing/portable_math.h"

namespace sketchsurf {
namespace {

// |value - exact| in units of the last place of the double nearest `exact`.
double ulps(double value, long double exact) {
  const double nearest = static_cast<double>(exact);
  const double ulp =
      std::nextafter(std::fabs(nearest), std::numeric_limits<double>::infinity()) - std::fabs(nearest);
  return static_cast<double>(std::fabs(static_cast<long double>(value) - exact) / ulp);
}

// Largest error of `f` against `reference` over `count` uniform arguments in [lo, hi].
double worst_ulps(const std::function<double(double)>& f,
                  const std::function<long double(long double)>& reference, double lo, double hi,
                  int count = 200000) {
  std::mt19937_64 engine(7);
  std::uniform_real_distribution<double> u(lo, hi);
  double worst = 0.0;
  for (int i = 0; i < count; ++i) {
    const double x = u(engine);
    const long double exact = reference(x);
    if (exact == 0.0L) continue;
    worst = std::max(worst, ulps(f(x), exact));
  }
  return worst;
}

constexpr double kPi = std::numbers::pi;

TEST(PortableMath, ExpAndLogAreWithinTwoUlps) {
  const auto exp = [](double x) { return portable::exp(x); };
  const auto expl_ = [](long double x) { return std::exp(x); };
  EXPECT_LE(worst_ulps(exp, expl_, -1.0, 1.0), 2.0);
  EXPECT_LE(worst_ulps(exp, expl_, -700.0, 700.0), 2.0);
  const auto log = [](double x) { return portable::log(x); };
  const auto logl_ = [](long double x) { return std::log(x); };
  EXPECT_LE(worst_ulps(log, logl_, 0.5, 2.0), 2.0);
  EXPECT_LE(worst_ulps(log, logl_, 1e-300, 1e300), 2.0);
  EXPECT_LE(worst_ulps(log, logl_, 1e-12, 1.0), 2.0);
}

TEST(PortableMath, SineAndCosineAreWithinTwoUlps) {
  const auto sin = [](double x) { return portable::sin(x); };
  const auto cos = [](double x) { return portable::cos(x); };
  const auto sinl_ = [](long double x) { return std::sin(x); };
  const auto cosl_ = [](long double x) { return std::cos(x); };
  for (const double range : {1.0, 2.0 * kPi, 100.0}) {
    EXPECT_LE(worst_ulps(sin, sinl_, -range, range), 2.0) << range;
    EXPECT_LE(worst_ulps(cos, cosl_, -range, range), 2.0) << range;
  }
}

TEST(PortableMath, ArcTangentAndArcCosineAreWithinThreeUlps) {
  const auto atan = [](double x) { return portable::atan(x); };
  const auto atanl_ = [](long double x) { return std::atan(x); };
  EXPECT_LE(worst_ulps(atan, atanl_, -1.0, 1.0), 3.0);
  EXPECT_LE(worst_ulps(atan, atanl_, -1e6, 1e6), 3.0);
  const auto acos = [](double x) { return portable::acos(x); };
  const auto acosl_ = [](long double x) { return std::acos(x); };
  EXPECT_LE(worst_ulps(acos, acosl_, -1.0, 1.0), 3.0);
  EXPECT_LE(worst_ulps(acos, acosl_, 0.999, 1.0), 3.0);
  // atan2 in every quadrant, against atan2l.
  std::mt19937_64 engine(11);
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const double y = u(engine), x = u(engine);
    worst = std::max(worst, ulps(portable::atan2(y, x),
                                 std::atan2(static_cast<long double>(y), static_cast<long double>(x))));
  }
  EXPECT_LE(worst, 3.0);
}

TEST(PortableMath, SpecialValuesFollowC) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(portable::exp(0.0), 1.0);
  EXPECT_EQ(portable::exp(-inf), 0.0);
  EXPECT_EQ(portable::exp(inf), inf);
  EXPECT_EQ(portable::exp(710.0), inf);
  EXPECT_TRUE(std::isfinite(portable::exp(709.78)));
  EXPECT_GT(portable::exp(-745.0), 0.0);  // subnormal
  EXPECT_TRUE(std::isnan(portable::exp(nan)));
  EXPECT_EQ(portable::log(1.0), 0.0);
  EXPECT_EQ(portable::log(0.0), -inf);
  EXPECT_EQ(portable::log(inf), inf);
  EXPECT_TRUE(std::isnan(portable::log(-1.0)));
  EXPECT_EQ(portable::sin(0.0), 0.0);
  EXPECT_TRUE(std::signbit(portable::sin(-0.0)));
  EXPECT_EQ(portable::cos(0.0), 1.0);
  EXPECT_TRUE(std::isnan(portable::sin(inf)));
  EXPECT_TRUE(std::isnan(portable::cos(nan)));
  EXPECT_EQ(portable::acos(1.0), 0.0);
  EXPECT_EQ(portable::acos(-1.0), kPi);
  EXPECT_EQ(portable::acos(0.0), kPi / 2);
  EXPECT_TRUE(std::isnan(portable::acos(1.0000001)));
  EXPECT_EQ(portable::atan(inf), kPi / 2);
  EXPECT_TRUE(std::signbit(portable::atan(-0.0)));
  // atan2's signed zeros and infinities, as C's.
  for (const double y : {0.0, -0.0, 1.0, -1.0, inf, -inf})
    for (const double x : {0.0, -0.0, 1.0, -1.0, inf, -inf}) {
      const double want = std::atan2(y, x), got = portable::atan2(y, x);
      EXPECT_EQ(got, want) << "atan2(" << y << ", " << x << ")";
      EXPECT_EQ(std::signbit(got), std::signbit(want)) << "atan2(" << y << ", " << x << ")";
    }
  EXPECT_TRUE(std::isnan(portable::atan2(nan, 1.0)));
}

TEST(PortableMath, IntegerPowersByRepeatedSquaring) {
  EXPECT_EQ(portable::pow(2.0, 10), 1024.0);
  EXPECT_EQ(portable::pow(2.0, -3), 0.125);
  EXPECT_EQ(portable::pow(-3.0, 3), -27.0);
  EXPECT_EQ(portable::pow(0.7, 0), 1.0);
  for (int n = -12; n <= 12; ++n)
    EXPECT_LE(ulps(portable::pow(1.37, n), std::pow(1.37L, static_cast<long double>(n))), 8.0) << n;
}

}  // namespace
}  // namespace sketchsurf
