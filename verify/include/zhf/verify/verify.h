// zhf verify: compile and run every emitted kernel (C++ with the host compiler, GLSL and HLSL
// through glslang to SPIR-V on a Vulkan device) on one input set, and compare with the
// independent double-precision reference in sh/.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "zhf/codegen/float_model.h"

namespace zhf::verify {

// Tolerances, by method and precision (max abs error vs the double reference, unit-norm inputs).
inline constexpr double kDoubleTolerance = 1e-12;
inline constexpr double kFloatRotationTolerance = codegen::kFloatRotationTarget;  // rotations, at least
using codegen::kFloatEpsilon;
// Float rotations, by where the lobe stage runs (codegen/kernels.h, LobePrecision):
// - in double (R projected onto the rotations first): what is left is the rounding of R
//   itself, which turns band l by ~l eps_f, and of the output: max(1e-6, 2 (N-1) eps_f), which
//   is 1e-6 up to order 9. Measured at orders 5..8: 1.2e-7 to 6.8e-7 over 1000 rotations.
// - in float: each rotated lobe direction carries ~eps_f rounding, which band l's SH turn into
//   ~l eps_f and the lobe weights amplify by up to the band's condition, and R's own symmetric
//   rounding error is amplified the same way. Measured max error / (eps_f (N-1) k_max) over
//   1000 rotations for the checked-in tables, orders 3..8: 0.42 to 0.95. So the tolerance is
//   max(1e-6, eps_f (N-1) k_max); `auto` (the default) picks double exactly where this
//   exceeds 1e-6.
inline double float_rotation_tolerance(int order, double worst_condition, bool wide_lobes) {
  const double model = wide_lobes ? 2 * (order - 1) * kFloatEpsilon : codegen::float_lobe_error_model(order, worst_condition);
  return model > kFloatRotationTolerance ? model : kFloatRotationTolerance;
}
// zxzxz (sh/zxzxz.h) in float: five stages of O(eps) rounding per coefficient, and the Euler
// angles' rounding turns band l by ~l eps: 4 N eps_f (measured at most 0.6 of it).
inline double zxzxz_float_tolerance(int order) { return 4 * order * kFloatEpsilon; }
// sh_eval: l-1 recurrence steps of relative error ~4 eps on |y| <= 1.07 (order 8) bound the
// float error by ~1.7e-6 at l = 7; sh/'s own float evaluation is held to 2e-6 likewise.
inline constexpr double kFloatEvaluationTolerance = 2e-6;
inline constexpr double kFloatSparseTolerance = 4e-6;       // Ahat multiplies: entries up to ~10
// Shader float results vs the C++ float kernel (built with -ffp-contract=off), in ulps at the
// coefficients' scale (see verify.cc). GLSL reaches the driver as the same operations in the
// same order: measured 2 ulps on lavapipe. glslang legalises HLSL with SPIRV-Tools passes that
// fold constant products and regroup sums, and those differences are amplified like every
// rounding error (by ~(N-1) k_max, see above): measured 97 ulps at order 5, 768 at order 8
// (2 with -Od). HLSL's limit is max(256, 8 (N-1) k_max). The dense-matrix pair (build M in
// float, then apply) differs from C++ by 24 ulps in GLSL too (order 5; the differing operation
// is not yet pinned down, the error vs the reference is the same), so it gets HLSL's limit.
inline constexpr double kGlslUlpLimit = 8;
inline constexpr double kHlslUlpFloor = 256;
inline constexpr double kHlslUlpsPerAmplification = 8;
inline double hlsl_ulp_limit(int order, double worst_condition) {
  const double model = kHlslUlpsPerAmplification * (order - 1) * worst_condition;
  return model > kHlslUlpFloor ? model : kHlslUlpFloor;
}

struct VerifyOptions {
  std::string generated_dir = "generated";
  std::vector<int> orders;     // empty: every order in the manifest (2..8 without one)
  std::vector<std::string> languages = {"cpp", "glsl", "hlsl"};
  int rotations = 1000;
  std::string compiler;        // C++ compiler; empty: $CXX, else c++
  std::string work_dir;        // scratch; empty: a fresh temp dir, removed afterwards
  bool keep_work_dir = false;
};

struct FunctionResult {
  int order = 0;
  std::string language;        // cpp, glsl, hlsl
  std::string precision;       // float, double
  std::string function;
  double max_error = 0;
  double rms_error = 0;
  double max_ulps = 0;         // vs the C++ float kernel (shaders); -1: not measured (C++ itself,
                               // or a tree without the C++ file, e.g. a GLSL-only scene)
  double tolerance = 0;
  double ulp_limit = 0;
  int worst_index = -1;        // coefficient index of the largest error
  int worst_input = -1;
  bool pass = false;
};

struct VerifyReport {
  std::string device;          // the Vulkan device used, if any
  std::vector<FunctionResult> results;
  std::vector<std::string> errors;  // compile or run failures, one line each
  bool vulkan_missing = false;
  bool pass() const;
  nlohmann::ordered_json to_json() const;
  std::string table() const;   // one row per order x language x precision
};

VerifyReport run_verify(const VerifyOptions& options);

}  // namespace zhf::verify
