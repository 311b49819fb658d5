// The runtime's named tolerances: the accuracy each of its paths promises and the thresholds of its
// own checks and algorithms, each with where it comes from. They are part of zhf's one tolerance
// table; the rest of it, the tolerances of the libraries above the runtime and of the tests, is
// zhf/tolerances/tolerances.h, which brings these in so that zhf::tolerance::kX names every entry.
// A tolerance is never loosened to make a check pass without finding out why it failed.
//
// "Max error" is the largest absolute difference from the double reference rotation over
// unit-norm coefficient vectors, unless a line says otherwise.
#pragma once

namespace zhf::runtime::tolerance {

// ---- Lobe tables (the reader's checks) -------------------------------------------------------
// Stored unit xyz against theta/phi, and |w|^2 - 1: both are rounded from the same double angles.
inline constexpr double kTableDirection = 1e-12;
// Y_l A_l - I, max entry: A_l is stored to 17 digits; the product rounds at ~k eps.
inline constexpr double kTableInverse = 1e-10;
// A stored condition number against the recomputed one, relative (the SVDs differ by rounding).
inline constexpr double kTableConditionRelative = 0.01;
// Beyond this condition a lobe matrix counts as singular: zero detection at 1e-10 relative is
// meaningless once rounding (condition x 1e-16) reaches it.
inline constexpr double kSingularCondition = 1e6;

// ---- Rotation matrices given to zhf ----------------------------------------------------------
// max |R R^T - I| and |det R - 1| accepted as a rotation: float matrices built from quaternions
// or Euler angles carry a few 1e-7.
inline constexpr double kRotationDefect = 1e-5;

// ---- Rotations against the reference ---------------------------------------------------------
// Double kernels and every double method: ~1e-15 per entry, measured at most 2.9e-14 at the
// worst unit input.
inline constexpr double kDouble = 1e-12;
// The float target of every rotation kernel, on random unit inputs; also of float band matrices
// built by the kernels (Rotator::dense, rotate_shared's batch path): measured at most 5.0e-7 at
// N = 2..8.
inline constexpr double kFloatRotation = 1e-6;
inline constexpr double kFloatEpsilon = 5.9604644775390625e-08;  // 2^-24

// Float rotations through lobes. Each rotated lobe is rounded to float, band-l SH turn that into
// about l eps_f, and A_l amplifies it by up to its condition number k (k_max over the bands); a
// float R's own symmetric rounding error is amplified the same way. Measured max error /
// (eps_f (N-1) k_max) over 1000 rotations for the checked-in tables, orders 3..8: 0.42 to 0.95.
inline double float_lobe_error_model(int order, double worst_condition) {
  return kFloatEpsilon * (order - 1) * worst_condition;
}
// Where the lobe stage runs in double (R projected onto the rotations first), what is left is the
// rounding of R itself, which turns band l by ~l eps_f, and of the output: 2 (N-1) eps_f, which
// is below 1e-6 up to order 9. Measured at orders 5..8: 1.2e-7 to 6.8e-7 over 1000 rotations.
inline double float_rotation(int order, double worst_condition, bool lobe_stage_in_double) {
  const double model =
      lobe_stage_in_double ? 2 * (order - 1) * kFloatEpsilon : float_lobe_error_model(order, worst_condition);
  return model > kFloatRotation ? model : kFloatRotation;
}
// zxzxz in float: five stages of O(eps) rounding per coefficient, and the Euler angles' rounding
// turns band l by ~l eps: 4 N eps_f (measured at most 0.6 of it).
inline double zxzxz_float(int order) { return 4 * order * kFloatEpsilon; }

// ---- SH products (runtime/gaunt.h, runtime/product.h) -------------------------------------------
// Gaunt coefficients (3j closed form, long double) against a long-double product quadrature in
// double nodes: both round at ~1e-16 on values below 0.6.
inline constexpr double kGauntAgainstQuadrature = 1e-14;
// Products, double- and triple-product integrals of random functions (coefficients ~N(0, 1/N^2))
// against numerical integration of the reconstructed functions: sums of up to N^4 terms in double.
inline constexpr double kProductAgainstIntegration = 1e-12;
// The same products in float: each output sums up to ~2N^2 products of float terms.
inline constexpr double kFloatProduct = 2e-6;
// 3j symbols have zeros the selection rules do not predict; Racah's sum leaves ~1e-20 there, where
// every true coefficient up to order 16 is above 2.5e-5.
inline constexpr double kGauntZero = 1e-15;

// ---- Run-time orders -------------------------------------------------------------------------
// Run-time orders (16..128) in float: the error a user of Rotator::from_table or Rotator::zxzxz may
// expect.
inline constexpr double kRuntimeOrdersFloat = 1e-5;
// Rotator<double>::zxzxz above kMaxDoubleAccurateZxzxzOrder: its quarter turns X come from the
// Ivanic-Ruedenberg recurrence, whose rounding grows with l (in double 1.5e-12 at l = 63, 5e-7 at
// 127); made in long double they are off by 2.6e-10 at most at order 128 (measured): 4x that.
inline constexpr double kHighOrderZxzxzDouble = 1e-9;

// ---- The runtime's numerical algorithms: stopping rules and zero tests -------------------------
// One-sided Jacobi SVD: a column pair counts as orthogonal below this cosine (double rounding).
inline constexpr double kJacobiOrthogonal = 1e-15;
// Nearest rotation by polar iteration: a determinant below this is a singular matrix; the
// iteration stops when no entry moves by more than kPolarStep (double rounding).
inline constexpr double kSingularDeterminant = 1e-300;
inline constexpr double kPolarStep = 1e-16;
// An entry this close to 0 or +-1 is exactly that (X = D(Rx(90)) from the recurrence, a rescaled
// lobe's equal components): a few roundings of values of size 1.
inline constexpr double kExactEntry = 1e-14;
// Emitted zxzxz kernels: below this |R's last column in xy|^2 (sin^2 b) the rotation is at gimbal
// lock and a = 0; above it the column is normalised in full precision (a float normal number,
// whose square root ~1e-15 is what sin b is rounded to at lock, below double kernels' tolerance).
inline constexpr double kGimbalLockSine2 = 1e-30;

}  // namespace zhf::runtime::tolerance
