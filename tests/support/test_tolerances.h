// The tests' own tolerances: how closely a test holds one computation to another where no library
// states that accuracy (the runtime's promises are runtime/tolerances.h, the libraries' and verify's
// tolerances/tolerances.h). The three files are zhf's one tolerance table, all in zhf::tolerance;
// each entry says where it comes from. A tolerance is never loosened to make a check pass without
// finding out why it failed.
#pragma once

#include "zhf/tolerances/tolerances.h"

namespace zhf::tolerance {

// ---- Rotation kernels: the tests' inputs ------------------------------------------------------
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

// ---- Spherical designs (frames/) -------------------------------------------------------------
// A design's equal-weight rule against the closed-form integrals of monomials of degree <= t, in
// long double: the points carry double rounding (1e-16) and the design residual (<= 1e-14).
inline constexpr double kDesignQuadrature = 1e-14;
// The needlet window: psi's integrals against a long-double tanh-sinh rule, closed forms
// (psi(0) = 1/2, psi(u) + psi(-u) = 1) and the partition of unity sum_j b^2(l / B^j) = 1, each a
// few roundings of values below 1 (measured at most 2.3e-15, B = 1.2).
inline constexpr double kNeedletWindow = 1e-14;
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
// Projection of a function of bands <= 7 (coefficients ~1) on nodes exact for it (designs, Gauss
// rules): sums of up to ~10^3 weighted samples of size <= 10.
inline constexpr double kExactProjection = 1e-12;

// ---- Reference math (the tests of sh/ and candidates/) ---------------------------------------
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
// A polished Legendre root, or a candidate theta from one, leaves |normalised P_l^m| at the
// rounding floor of one evaluation.
inline constexpr double kRootResidual = 1e-13;
// Zeros of A_l counted by the search, recomputed in long double, sit at rounding level.
inline constexpr double kZeroInLongDouble = 1e-13;
// The axis and weights zhf analyze finds for a zonal function (and the function rebuilt from
// them): measured to about 1e-15.
inline constexpr double kZonalFit = 1e-9;

// ---- Other checks ------------------------------------------------------------------------------
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

// ---- Needlet windows ---------------------------------------------------------------------------
// Needlet window weights against an independent long-double tanh-sinh quadrature, relative: at
// most 4.5e-13 measured for weights from 1e-4 down to 6e-62 (B = 1.2..2.4).
inline constexpr double kNeedletWindowRelative = 1e-12;

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
// zhf's reading of a .spz against the reference library's, both from the same bytes: the library
// decodes and turns in float, zhf in double, each output rounded to float: over the checked-in
// files at most 1.79e-7 apart (3 kFloatEpsilon; relative above 1), a float step and a half of a
// value near 1.
inline constexpr double kSpzReferenceLibraryReading = 4 * kFloatEpsilon;

// ---- HEALPix maps ----------------------------------------------------------------------------
// A band-limited map (bands <= Nside / 2) synthesised on HEALPix pixels and projected back with 3
// Jacobi steps: max coefficient error, measured 2.3e-10 at Nside 32, bands 0..16 (the pixel
// quadrature alone 5.5e-4, one step 4.2e-6).
inline constexpr double kHealpixProjection = 1e-9;

}  // namespace zhf::tolerance
