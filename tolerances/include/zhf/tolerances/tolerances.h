// zhf's named tolerances above the runtime, each with where it comes from: the checks of verify,
// the benchmarks' accuracy columns and the tests, and the stopping rules and zero tests of the
// numerical algorithms in sh/, candidates/, optimizer/, frames/, codegen/ and io/. With the
// runtime's own (runtime/tolerances.h, brought in below) this is zhf's one tolerance table:
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

// ---- Rotation kernels: the stage choice's margins and the tests' inputs ----------------------
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
// The worst unit input rather than random ones: kernels whose lobe stage runs (partly) in float
// reach 1.4e-6 (scalar, order 4) and 1.75e-6 (lanes, order 6) over 20000 rotations, where random
// unit vectors stay below 7.5e-7 (a random f meets the worst error row at a cosine of about 1/N).
// 1.4x the largest measured.
inline constexpr double kFloatLobeStageWorstUnitInput = 2.5e-6;
// The worst unit input against a method's random-input tolerance: the largest row norm of the
// error matrix, which a random unit f sees about N/3 times smaller; measured up to 1.75x.
inline constexpr double kWorstUnitInputFactor = 3;
// A float kernel chained 1000 times by small steps: the near-identity steps repeat one rounding
// pattern, so the drift grows faster than a random walk (measured 2e-4; a double-stepped chain
// through the float kernel drifts 2.9e-6). 2.5x the measured.
inline constexpr double kFloatChain = 5e-4;

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
// A design's equal-weight rule against the closed-form integrals of monomials of degree <= t, in
// long double: the points carry double rounding (1e-16) and the design residual (<= 1e-14).
inline constexpr double kDesignQuadrature = 1e-14;
// The needlet window: psi's integrals against a long-double tanh-sinh rule, closed forms
// (psi(0) = 1/2, psi(u) + psi(-u) = 1) and the partition of unity sum_j b^2(l / B^j) = 1, each a
// few roundings of values below 1 (measured at most 2.3e-15, B = 1.2).
inline constexpr double kNeedletWindow = 1e-14;
// A Mexican needlet window is taken as zero where b^2 is below this fraction of its peak
// (its Gaussian tail: the sum over levels changes by less than that).
inline constexpr double kWindowNegligible = 1e-20;
// The spline step against Simpson's rule on the cubic B-spline (2000 panels a piece: the
// rule's error on a quartic is below 1e-16) and the Mexican square sums against a plain sum
// over levels (a few roundings of ~20 terms, relative).
inline constexpr double kSplineStepAgainstSimpson = 1e-13;
inline constexpr double kWindowSquareSum = 1e-14;
// A kernel's energy outside a cap against the midpoint rule in the angle on 200 000 panels:
// the rule's error, h^2 / 24 times the integrand's second derivative (~band^2), relative.
inline constexpr double kCapEnergyAgainstMidpoint = 1e-6;
// The needlet frame on unit-norm signals of bands <= 16: reconstruction, Parseval, sampled analysis,
// kernels and rotation, each sums of ~10^3 terms of size <= 1 over a cubature whose nodes carry
// double rounding (the bound for exact reconstruction).
inline constexpr double kNeedletFrame = 1e-12;
// The tight-frame rotation in double against the reference band matrices, orders <= 16: sums of
// M <= 500 lobe terms of size <= 1 for unit inputs, condition exactly 1.
inline constexpr double kTightFrameRotation = 1e-13;
// An emitted needlet evaluator (C++, GLSL, HLSL in float) against its CPU mirror (the same tables
// read in double), relative to the sum of the terms' magnitudes: float rounding of the nodes, the
// tables, the interpolation weight (u ~ table size, so its ulp grows with the table) and a sum of
// a few hundred terms.
inline constexpr double kNeedletLutFloat = 1e-5;
// Projection of a function of bands <= 7 (coefficients ~1) on nodes exact for it (designs, Gauss
// rules): sums of up to ~10^3 weighted samples of size <= 10.
inline constexpr double kExactProjection = 1e-12;

// ---- Reference math (tests of sh/ and candidates/) ----------------------------------------------
// What is exact in exact arithmetic and rounds once or twice in double (the identity rotation's
// band matrices, a recurrence at a pole).
inline constexpr double kExactToRounding = 1e-15;
// Fast double SH against the long-double closed form: both exact to rounding for l <= 12.
inline constexpr double kDoubleVsClosedForm = 1e-13;
// The two long-double slow paths (closed form, unnormalised recurrence), normalised, for l <= 12.
inline constexpr double kSlowPathsAgreement = 1e-14;
// The emitted sh_eval (the recurrence's coefficients folded into polynomials) against eval_sh.
inline constexpr double kGeneratedVsRecurrence = 1e-14;
// Float SH against double SH at the same (float) direction: coefficients rounded to float and
// ~3l recurrence steps.
inline constexpr double kFloatVsClosedForm = 2e-6;
// Orthonormality by an exact product quadrature at N = 16.
inline constexpr double kOrthonormality = 1e-13;
// N = 64 against the long-double unnormalised recurrence, relative to the band's largest value
// at that point (absolute error near a root of P_l^m is what a recurrence offers); measured
// 1.6e-13.
inline constexpr double kOrder64Relative = 1e-12;
// The two double reference rotations (recurrence and quadrature projection): ~1e-15 per entry at
// N = 8; at N = 32 the recurrence accumulates rounding over 31 steps (measured 1.9e-14).
inline constexpr double kReferenceAgreement = 1e-13;
// g(w) = f(R^T w) pointwise at N = 8, unit-norm f.
inline constexpr double kPointwise = 1e-12;
// A polished Legendre root, or a candidate theta from one, leaves |normalised P_l^m| at the
// rounding floor of one evaluation.
inline constexpr double kRootResidual = 1e-13;
// Zeros of A_l counted by the search, recomputed in long double, sit at rounding level.
inline constexpr double kZeroInLongDouble = 1e-13;
// The axis and weights zhf analyze finds for a zonal function (and the function rebuilt from
// them): measured to about 1e-15.
inline constexpr double kZonalFit = 1e-9;
// Two zonal axes are one axis when |a x b| is below this (a and -a are the same axis).
inline constexpr double kSameAxis = 1e-6;

// ---- Goals and defaults that reports and options state ---------------------------------------
// zhf analyze / zhf.analyze: the relative L2 error within which a band limit or a zonal fit counts
// as found, by default.
inline constexpr double kDefaultZonalFit = 1e-3;
// zhf bench: the pruning thresholds of its "pruned" rows (entries of A_l below this times the
// band's largest dropped), and the error at which an exact result is drawn on a log axis (below
// every measured error).
inline constexpr double kBenchPruneSmall = 1e-3, kBenchPruneLarge = 1e-2;
inline constexpr double kPlotErrorFloor = 1e-17;

// ---- Checks the tests make that no section above covers -----------------------------------------
// A quadratic look-up table reproduces a quadratic exactly, up to rounding of a few operations.
inline constexpr double kQuadraticTableExact = 1e-14;
// Cap energies of needlet kernels against a midpoint rule in theta (its own error, ~1e-5).
inline constexpr double kCapEnergyMidpoint = 1e-4;
// A cap's zonal coefficients against a 100000-step midpoint rule in cos theta (error ~h^2).
inline constexpr double kCapCoefficientMidpoint = 1e-9;
// A constant sky projected from float pixels: the pixel sum's float rounding.
inline constexpr double kFloatProjection = 1e-6;
// Float kernels on inputs scaled by 1e30 and 1e-30, relative to the scale: the float target with
// the scaling's own rounding on top (no overflow, no subnormals).
inline constexpr double kFloatExtremeScale = 2e-5;
// Gaunt coefficients' symmetry in their three indices, and y_0^0 coupling as a delta: one rounding
// of values below 0.6.
inline constexpr double kGauntSymmetry = 1e-16;

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
// Needlet window weights against an independent long-double tanh-sinh quadrature, relative: at
// most 4.5e-13 measured for weights from 1e-4 down to 6e-62 (B = 1.2..2.4).
inline constexpr double kNeedletWindowRelative = 1e-12;
// Radiance RGBE: a pixel whose largest channel is below this is stored black (the format's rule).
inline constexpr float kRgbeBlack = 1e-32f;

// ---- Precomputed radiance transfer ------------------------------------------------------------
// Needlet shading with every coefficient kept against the SH sum it equals (the frame is tight):
// difference over the exact shading's RMS, measured at most 1.6e-14 (bands 0..31, 4667 needlets).
inline constexpr double kParsevalShading = 1e-12;
// The exact shading (frames/prt.h: caps integrated in closed-form theta intervals) against closed
// forms (open ground, the sphere straight overhead, the corner's Lambert polygon) and against
// itself at half the step: absolute, on shadings of order 1 (relative to max(1, |shading|)).
inline constexpr double kPrtExactReference = 1e-10;

// ---- Splat scenes ----------------------------------------------------------------------------
// zhf splat's .ply values are float32: each is rounded to float once on the way in and once on
// the way out, so a transformed value is within a few float steps of its double reference.
inline constexpr double kSplatFloatStorage = 4 * kFloatEpsilon;

// ---- HEALPix maps ----------------------------------------------------------------------------
// A band-limited map (bands <= Nside / 2) synthesised on HEALPix pixels and projected back with 3
// Jacobi steps: max coefficient error, measured 2.3e-10 at Nside 32, bands 0..16 (the pixel
// quadrature alone 5.5e-4, one step 4.2e-6).
inline constexpr double kHealpixProjection = 1e-9;
// A pixel within this relative distance of UNSEEN (-1.6375e30) is UNSEEN: a float file stores the
// marker rounded (6e-8 relative); healpy's own test is as loose.
inline constexpr double kHealpixUnseenRelative = 1e-5;

}  // namespace zhf::tolerance
