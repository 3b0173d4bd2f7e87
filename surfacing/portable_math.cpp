#include "surfacing/portable_math.h"

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace sketchsurf::portable {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ln 2 split so that k * kLn2Hi is exact for |k| < 2^21.
constexpr double kLn2Hi = 0.6931471803691238;
constexpr double kLn2Lo = 1.9082149292705877e-10;
constexpr double kInvLn2 = 1.4426950408889634;
constexpr double kExpMax = 709.782712893384;    // largest x with a finite e^x
constexpr double kExpMin = -745.1332191019412;  // below: e^x rounds to 0
constexpr double kSqrtHalf = 0.7071067811865476;

// pi / 2 in three parts of 33 bits (the last rounded): k * part is exact for |k| < 2^20.
constexpr double kPio2Part1 = 1.5707963267341256;
constexpr double kPio2Part2 = 6.077100506303966e-11;
constexpr double kPio2Part3 = 2.0222662487959506e-21;
constexpr double kTwoOverPi = 0.6366197723675814;

// Multiples of pi as a double and the rest.
constexpr double kPiHi = 3.141592653589793, kPiLo = 1.2246467991473532e-16;
constexpr double kPio2Hi = 1.5707963267948966, kPio2Lo = 6.123233995736766e-17;
constexpr double kPio4Hi = 0.7853981633974483;
constexpr double kPio6Hi = 0.5235987755982989, kPio6Lo = -5.360408832255455e-17;
constexpr double kSqrt3 = 1.7320508075688772;
constexpr double kTanPi12 = 0.2679491924311227;  // 2 - sqrt(3)

// c[0] + c[1] x + ... + c[N-1] x^(N-1) by Horner's rule.
template <std::size_t N>
double horner(double x, const std::array<double, N>& c) {
  double p = c[N - 1];
  for (std::size_t i = N - 1; i-- > 0;) p = p * x + c[i];
  return p;
}

// Taylor coefficients, computed by the compiler (correctly rounded divisions).
constexpr double kF3 = 6.0, kF4 = 24.0, kF5 = 120.0, kF6 = 720.0, kF7 = 5040.0, kF8 = 40320.0, kF9 = 362880.0,
                 kF10 = 3628800.0, kF11 = 39916800.0, kF12 = 479001600.0, kF13 = 6227020800.0,
                 kF14 = 87178291200.0, kF15 = 1307674368000.0, kF16 = 20922789888000.0,
                 kF17 = 355687428096000.0, kF18 = 6402373705728000.0;

// e^r - 1 for |r| <= ln(2) / 2 by its Taylor series to r^13 (remainder below 1e-17 relative).
double expm1_reduced(double r) {
  constexpr std::array<double, 12> c{0.5,     1 / kF3, 1 / kF4,  1 / kF5,  1 / kF6,  1 / kF7,
                                     1 / kF8, 1 / kF9, 1 / kF10, 1 / kF11, 1 / kF12, 1 / kF13};
  return r + r * r * horner(r, c);
}

// sin r for |r| <= pi / 4 by its Taylor series to r^17.
double sin_reduced(double r) {
  constexpr std::array<double, 8> c{-1 / kF3,  1 / kF5,  -1 / kF7,  1 / kF9,
                                    -1 / kF11, 1 / kF13, -1 / kF15, 1 / kF17};
  const double r2 = r * r;
  return r + r * r2 * horner(r2, c);
}

// cos r for |r| <= pi / 4 by its Taylor series to r^18.
double cos_reduced(double r) {
  constexpr std::array<double, 8> c{-1 / kF4,  1 / kF6,  -1 / kF8,  1 / kF10,
                                    -1 / kF12, 1 / kF14, -1 / kF16, 1 / kF18};
  const double r2 = r * r;
  return 1.0 - (0.5 * r2 + r2 * r2 * horner(r2, c));
}

// x rounded to the nearest integer (ties to even) for |x| < 2^51 without a library call: adding
// and subtracting 1.5 * 2^52 leaves no fraction bits.
double round_small(double x) {
  constexpr double kShift = 6755399441055744.0;  // 1.5 * 2^52
  return (x + kShift) - kShift;
}

// 2^k for an integer k (as a double) in the normal range [-1022, 1023], by its bits.
double two_to(double k) {
  return std::bit_cast<double>(static_cast<std::uint64_t>(static_cast<std::int64_t>(k) + 1023) << 52);
}

// x = k pi / 2 + r with |r| <= pi / 4 (about); quadrant = k mod 4.
double reduce_half_pi(double x, int& quadrant) {
  const double scaled = x * kTwoOverPi;
  const double k = std::fabs(scaled) < 1e15 ? round_small(scaled) : std::floor(scaled + 0.5);
  quadrant = static_cast<int>(k - 4.0 * std::floor(0.25 * k));
  return ((x - k * kPio2Part1) - k * kPio2Part2) - k * kPio2Part3;
}

// atan t for |t| <= 2 - sqrt(3) by its Taylor series to t^29 (remainder below 1e-18 relative).
double atan_series(double t) {
  const double t2 = t * t;
  double p = 1.0 / 29.0;
  for (int k = 27; k >= 3; k -= 2) p = p * t2 + ((k / 2) % 2 == 0 ? 1.0 : -1.0) / k;
  return t + t * t2 * p;
}

// atan a for 0 <= a <= 1: beyond tan(pi / 12) through atan a = pi / 6 + atan((a sqrt 3 - 1) /
// (a + sqrt 3)).
double atan_unit(double a) {
  if (a <= kTanPi12) return atan_series(a);
  return kPio6Hi + (atan_series((a * kSqrt3 - 1.0) / (a + kSqrt3)) + kPio6Lo);
}

}  // namespace

double exp(double x) {
  if (std::isnan(x)) return x;
  if (x > kExpMax) return kInf;
  if (x < kExpMin) return 0.0;
  const double k = round_small(x * kInvLn2);
  const double r = (x - k * kLn2Hi) - k * kLn2Lo;
  const double m = 1.0 + expm1_reduced(r);
  // 2^k m: in two steps where 2^k alone would overflow or be subnormal.
  if (k > 1023.0) return m * two_to(k - 1.0) * 2.0;
  if (k < -1022.0) return m * two_to(k + 60.0) * two_to(-60.0);
  return m * two_to(k);
}

double log(double x) {
  if (std::isnan(x)) return x;
  if (x < 0.0) return kNaN;
  if (x == 0.0) return -kInf;
  if (x == kInf) return x;
  int e = 0;
  double m = std::frexp(x, &e);  // x = m 2^e, m in [0.5, 1)
  if (m < kSqrtHalf) {
    m *= 2.0;
    --e;
  }
  // log m = 2 atanh f, f = (m - 1) / (m + 1), |f| <= 0.172: series to f^23.
  const double f = (m - 1.0) / (m + 1.0), f2 = f * f;
  double p = 1.0 / 23.0;
  for (int k = 21; k >= 3; k -= 2) p = p * f2 + 1.0 / k;
  const double log_m = 2.0 * f + 2.0 * f * (f2 * p);
  return e * kLn2Hi + (e * kLn2Lo + log_m);
}

double sin(double x) {
  if (!std::isfinite(x)) return kNaN;
  if (x == 0.0) return x;  // keeps the sign of zero
  int quadrant = 0;
  const double r = reduce_half_pi(x, quadrant);
  switch (quadrant) {
    case 0:
      return sin_reduced(r);
    case 1:
      return cos_reduced(r);
    case 2:
      return -sin_reduced(r);
    default:
      return -cos_reduced(r);
  }
}

double cos(double x) {
  if (!std::isfinite(x)) return kNaN;
  int quadrant = 0;
  const double r = reduce_half_pi(x, quadrant);
  switch (quadrant) {
    case 0:
      return cos_reduced(r);
    case 1:
      return -sin_reduced(r);
    case 2:
      return -cos_reduced(r);
    default:
      return sin_reduced(r);
  }
}

double atan(double x) {
  if (std::isnan(x)) return x;
  const double a = std::fabs(x);
  const double angle = a > 1.0 ? kPio2Hi - (atan_unit(1.0 / a) - kPio2Lo) : atan_unit(a);
  return std::copysign(angle, x);
}

double atan2(double y, double x) {
  if (std::isnan(x) || std::isnan(y)) return x + y;
  if (y == 0.0) return std::signbit(x) ? std::copysign(kPiHi, y) : y;
  if (x == 0.0) return std::copysign(kPio2Hi, y);
  if (std::isinf(x)) {
    if (std::isinf(y)) return std::copysign(x > 0.0 ? kPio4Hi : 3.0 * kPio4Hi, y);
    return std::copysign(x > 0.0 ? 0.0 : kPiHi, y);
  }
  if (std::isinf(y)) return std::copysign(kPio2Hi, y);
  const double a = atan(std::fabs(y) / std::fabs(x));
  return std::copysign(x > 0.0 ? a : kPiHi - (a - kPiLo), y);
}

double acos(double x) {
  if (!(std::fabs(x) <= 1.0)) return kNaN;
  return atan2(std::sqrt((1.0 - x) * (1.0 + x)), x);
}

double pow(double x, int n) {
  unsigned m = n < 0 ? 0u - static_cast<unsigned>(n) : static_cast<unsigned>(n);
  double result = 1.0, base = x;
  while (m > 0) {
    if (m & 1u) result *= base;
    base *= base;
    m >>= 1;
  }
  return n < 0 ? 1.0 / result : result;
}

}  // namespace sketchsurf::portable
