// zhf needlets verify: the emitted needlet evaluators (codegen/needlet_lut.h) compiled and run —
// C++ with the host compiler, GLSL and HLSL through glslang and WGSL through naga to SPIR-V on a
// Vulkan device — at random directions, against the CPU mirror (the same tables read in double)
// and against the exact expansion (each kernel by its Legendre series), which measures the
// tables' own error.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "zhf/codegen/backend.h"
#include "zhf/codegen/needlet_lut.h"
#include "zhf/frames/needlets.h"
#include "zhf/tolerances/tolerances.h"

namespace zhf::verify {

struct NeedletLutResult {
  std::string language;
  // max |emitted - mirror| / max_x sum_k |beta_k sqrt(lambda_k) K(x . xi_k)|: float rounding of
  // the evaluator, held to tolerance::kNeedletLutFloat.
  double vs_mirror = 0;
  // max |mirror - exact| / max |exact|: what the table size and interpolation cost.
  double table_error = 0;
  bool pass = false;
  std::string error;  // a compile or run failure, one line
};

struct NeedletLutVerify {
  std::vector<codegen::Language> languages = codegen::needlet_lut_languages();
  int directions = 512;
  std::string compiler;   // as for zhf verify
  std::string naga_wasm;  // the naga-wasm package directory (WGSL), as for zhf verify
  // Called before each language and at the end (languages done, languages; it may throw).
  std::function<void(std::size_t, std::size_t)> checkpoint;
};

// Shader languages are reported as failed with the reason when no Vulkan device can run them.
std::vector<NeedletLutResult> verify_needlet_lut(const frames::NeedletFrame& frame, const codegen::NeedletLutOptions& lut,
                                                 const NeedletLutVerify& options);

}  // namespace zhf::verify
