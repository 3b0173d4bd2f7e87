#pragma once
// The transcendental functions of the surfacing, computed the same way on every machine.
//
// glibc chooses its exp, log, pow, sin, cos, atan, atan2, asin and acos at load time by the CPU's
// features (FMA and AVX2 variants on most current x86-64 CPUs), and the variants differ in the
// last bit of some results. The surfacing amplifies such bits: VIPSS's optimisation over
// spherical angles, the remeshing's flips and collapses and PEARL's choices turn them into other
// meshes and other regions (an egg split into one region on one CPU and into eight on another).
// These functions use only IEEE-754 additions, multiplications, divisions and square roots, in an
// order fixed by the source, and their file is compiled without contracting them into FMAs, so
// that the C library's choice no longer shows in what a sketch surfaces to. Their accuracy: exp,
// log, sin and cos within 2 units in the last place of the exact result, atan, atan2 and acos
// within 3 (tested against the C library's long double functions).

namespace sketchsurf::portable {

/// e^x; 0 below about -745.13, +inf above about 709.78.
double exp(double x);
/// Natural logarithm; -inf at +-0, NaN below 0.
double log(double x);
/// Sine and cosine of x in radians. Exact argument reduction to |x| < 1.6e6 (three-part pi / 2);
/// beyond that still deterministic, with an absolute error that grows with |x|.
double sin(double x);
double cos(double x);
/// Arc tangent in [-pi/2, pi/2].
double atan(double x);
/// Angle of (x, y) in [-pi, pi], with C's conventions for signed zeros and infinities.
double atan2(double y, double x);
/// Arc cosine in [0, pi]; NaN outside [-1, 1].
double acos(double x);
/// x^n for an integer n by repeated squaring.
double pow(double x, int n);

}  // namespace sketchsurf::portable
