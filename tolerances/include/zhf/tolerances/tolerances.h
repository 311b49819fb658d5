// zhf's named tolerances above the runtime, each with where it comes from: the checks of verify and
// the benchmarks' accuracy columns, the accuracy the libraries above the runtime state, and the
// stopping rules and zero tests of the numerical algorithms in sh/, candidates/, optimizer/,
// frames/ and codegen/. With the runtime's own (runtime/tolerances.h, brought in below) and the
// tests' (tests/support/test_tolerances.h) this is zhf's one tolerance table:
// scripts/check_one_place.py fails the tests on a tolerance literal anywhere else. A tolerance is
// never loosened to make a check pass without finding out why it failed.
//
// "Max error" is the largest absolute difference from the double reference rotation over
// unit-norm coefficient vectors, unless a line says otherwise.
#pragma once

#include "zhf/runtime/tolerances.h"

namespace zhf::tolerance {

using namespace runtime::tolerance;

// ---- Lobe tables (the search) ------------------------------------------------------------------
// An entry of A_l is a structural zero when |a| <= this times max |A_l|; it is then stored as an
// exact 0.
inline constexpr double kZeroRelative = 1e-10;

// ---- Rotation kernels: the stage choice's margins ---------------------------------------------
// Emitted shading (a rotation integrated against a unit-norm transfer vector in one kernel): the rotated
// vector's error, at most float_rotation per coefficient, dotted with t: |e . t| <= |e| <= N max|e|.
inline double float_shading(int order, double worst_condition, bool lobe_stage_in_double) {
  return order * float_rotation(order, worst_condition, lobe_stage_in_double);
}
// The lobe-parallel kernel (lanes.h) multiplies A_l as dense columns; its error model is
// eps_f (N-1) a_max with a_l = sqrt((2l+1)/4pi) ||A_l||_2. Measured max errors over 131072
// rotations as multiples of it at N = 3..8: all float 0.86 to 2.1; lobes rotated in double 0.62
// to 1.13. The stage chosen per order is the cheapest whose model times its margin meets 1e-6.
inline constexpr double kLanesFloatMargin = 2.5;
inline constexpr double kLanesLobesInDoubleMargin = 1.25;

// ---- Building blocks of the emitted kernels ---------------------------------------------------
// sh_eval in float: l-1 recurrence steps of relative error ~4 eps on |y| <= 1.07 (order 8) bound
// the error by ~1.7e-6 at l = 7.
inline constexpr double kFloatEvaluation = 2e-6;
// The sparse products A^T f and A s in float: entries of A up to ~10.
inline constexpr double kFloatSparse = 4e-6;
// Shader float results against the C++ float kernel (built with -ffp-contract=off), in ulps at
// the coefficients' scale, at least kUlpFloor. GLSL reaches the driver as the same operations in
// the same order: measured 2 ulps on lavapipe. glslang legalises HLSL with SPIRV-Tools passes that
// fold constant products and regroup sums, amplified like every rounding error (by ~(N-1) k_max):
// measured 97 ulps at order 5, 768 at order 8 (2 with -Od), hence max(256, 8 (N-1) k_max). The
// dense-matrix pair differs from C++ by 24 ulps in GLSL too (order 5), so it gets HLSL's limit.
inline constexpr double kGlslUlps = 8;
inline constexpr double kUlpFloor = 1.0 / 64;  // unit-norm vectors of up to 64 entries
inline double hlsl_ulps(int order, double worst_condition) {
  const double model = 8 * (order - 1) * worst_condition;
  return model > 256 ? model : 256;
}

// ---- Emitted SH products ----------------------------------------------------------------------
// Shader product and shading kernels against the C++ float kernel, in ulps at the outputs' scale
// (floor kUlpFloor = 1/64): their outputs are sums over intermediates of size ~|f||g| = 1 for unit
// inputs, so one rounding the driver does differently (lavapipe may fuse a multiply into an add;
// C++ is built with -ffp-contract=off) moves a small output by up to 64 such ulps. Measured at
// most 16 (GLSL square, orders 4..8), 8 (product), 26 (GLSL shade_lobes, order 8).
inline constexpr double kSumShaderUlps = 64;

// ---- Spherical designs (frames/) -------------------------------------------------------------
// A Mexican needlet window is taken as zero where b^2 is below this fraction of its peak
// (its Gaussian tail: the sum over levels changes by less than that).
inline constexpr double kWindowNegligible = 1e-20;
// An emitted needlet evaluator (C++, GLSL, HLSL in float) against its CPU mirror (the same tables
// read in double), relative to the sum of the terms' magnitudes: float rounding of the nodes, the
// tables, the interpolation weight (u ~ table size, so its ulp grows with the table) and a sum of
// a few hundred terms.
inline constexpr double kNeedletLutFloat = 1e-5;

// ---- Reference math ---------------------------------------------------------------------------
// g(w) = f(R^T w) pointwise at N = 8, unit-norm f.
inline constexpr double kPointwise = 1e-12;
// Two zonal axes are one axis when |a x b| is below this (a and -a are the same axis).
inline constexpr double kSameAxis = 1e-6;

// ---- Frames, designs, products -------------------------------------------------------------------
// A design's accepted residual: a few roundings of sums of M terms of size <= 1.
inline constexpr double kDesignResidual = 1e-14;
// Relative spread (B - A) / B at or below which a frame counts as tight.
inline constexpr double kTightFrame = 1e-12;
// A / B at or below which the lobes do not span the space (rounding leaves ~1e-16 B where A is 0;
// the lobe tables' singular bound, condition 1e6, is A / B = 1e-12).
inline constexpr double kSpanning = 1e-12;

// ---- Numerical algorithms: stopping rules and zero tests ----------------------------------------
// A rotation off orthonormal by more than a few double roundings: worth saying that the nearest
// rotation was used instead.
inline constexpr double kDoubleRoundingDefect = 1e-14;
// Two magnitudes this close (relative) are one value: grouping equal |A_l| entries and equal
// lobe-scale factors; rounding of one evaluation is ~1e-16.
inline constexpr double kSameMagnitude = 1e-12;
// A Gauss-Legendre node this close to 0 is the centre node (computed as a root).
inline constexpr double kCenterNode = 1e-12;
// Two axes whose cross product is below this are parallel (no turn carries one onto the other).
inline constexpr double kParallelAxes = 1e-12;
// Candidates: computed values within kSnapToZero of 0 are 0 (SH values at exact zeros round to
// ~1e-17); theta values closer than kThetaMergeTolerance are one value (roots of different P_l^m
// meet only at pi/2, which is set exactly; anything closer that is not the same value would be a
// bug).
inline constexpr double kSnapToZero = 1e-15;
inline constexpr double kThetaMergeTolerance = 1e-12;
// Legendre roots: bisection stops at this bracket width; the Newton polish gives up on a step
// this large (it only polishes, never leaves the bracket).
inline constexpr double kRootBracket = 1e-14;
inline constexpr long double kRootPolishStep = 1e-10L;
// Zonal analysis: the first odd band whose weight exceeds this (relative to the energy) orients
// the axis; below it the weight is rounding.
inline constexpr double kOrientingWeight = 1e-12;
// Continuous searches (subplex): relative step at which a start has converged; a lobe matrix whose
// determinant is below kSearchSingularDeterminant is penalised as singular.
inline constexpr double kContinuousSearchStep = 1e-10;
inline constexpr double kSearchSingularDeterminant = 1e-12;
// Design search: central differences along the tangent plane with step h err by h^2 |y'''|, about
// 1e-10 relative, plenty for the descent and Levenberg-Marquardt's steps (the residual itself is
// evaluated exactly); the damping starts at kDampingStart and never drops below kDampingFloor;
// L-BFGS on the design energy stops at these absolute and relative changes.
inline constexpr double kDesignDifferenceStep = 1e-5;
inline constexpr double kDampingStart = 1e-6;
inline constexpr double kDampingFloor = 1e-15;
inline constexpr double kDesignEnergyAbsolute = 1e-26;
inline constexpr double kDesignEnergyRelative = 1e-15;
// A point read from a file is refused as a direction below this length (its normalisation would
// overflow).
inline constexpr double kShortestDirection = 1e-150;
// Adaptive Gauss-Kronrod (needlet windows): each integral to this relative error of its own value,
// so a window weight of 1e-8 (b^2 ~ 1e-16) keeps its digits; a panel whose error estimate is at
// the rounding of its value (64 eps) is done.
inline constexpr double kKronrodRelative = 1e-15;
inline constexpr double kKronrodRounding = 64 * 2.220446049250313e-16;

// ---- HEALPix maps ----------------------------------------------------------------------------
// A pixel within this relative distance of UNSEEN (-1.6375e30) is UNSEEN: a float file stores the
// marker rounded (6e-8 relative); healpy's own test is as loose.
inline constexpr double kHealpixUnseenRelative = 1e-5;

}  // namespace zhf::tolerance
