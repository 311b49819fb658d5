// A needlet expansion evaluated through look-up tables of its kernels (frames/needlets.h): for
// coefficients beta of a NeedletFrame,
//   f(x) = sum_levels sum_k beta_k sqrt(lambda_k) K_level(x . xi_k),
// with each K tabulated at `size` equally spaced t in [-1, 1] and read back by linear or quadratic
// interpolation (frames::UniformTable is the CPU mirror, read for read). Printed as C++, GLSL,
// HLSL or WGSL: a kernel read and the sum over nodes, on one float array of nodes, scales and
// tables (embedded in C++; a storage buffer in shaders). Everything placed in the source is a number or
// the checked identifier prefix (the command line only inside an escaped comment).
#pragma once

#include <string>
#include <vector>

#include "zhf/codegen/backend.h"
#include "zhf/codegen/limits.h"
#include "zhf/frames/needlets.h"

namespace zhf::codegen {

struct NeedletLutOptions {
  int table_size = 1024;
  frames::Interpolation interpolation = frames::Interpolation::kLinear;
  std::string prefix = "zhf_needlets";  // names every function and constant; [A-Za-z_][A-Za-z0-9_]{0,47}
  // Where shaders find the data buffer: GLSL and HLSL macros' defaults, WGSL's fixed group and
  // binding; 0..codegen::kMaxStorageSet and 0..codegen::kMaxStorageBinding.
  int storage_set = 0, storage_binding = 0;
  std::string command;                   // recorded in the banner
};

// False (and the reason) for a prefix that is not a plain identifier.
bool valid_prefix(const std::string& prefix, std::string& why);

// The languages with a needlet evaluator: cpp, glsl, hlsl, wgsl.
const std::vector<Language>& needlet_lut_languages();

// The file for one language: "<prefix>.h", ".glsl", ".hlsl" or ".wgsl". Functions:
//   float <prefix>_kernel(int level, float t)     K_level(t) from its table
//   float <prefix>_eval(beta[size], x[3])         the expansion at the unit direction x
// (WGSL: beta as array<f32, size> by value, x as vec3<f32>.) Throws std::invalid_argument for a
// bad prefix, table size, set or binding.
EmittedFile emit_needlet_lut(const frames::NeedletFrame& frame, Language language, const NeedletLutOptions& options);

// The numbers every evaluator reads, in float: nodes (3 per node), sqrt(lambda) (1 per node), then
// each level's kernel table. C++ embeds them; shaders read them from a storage buffer.
std::vector<float> needlet_lut_data(const frames::NeedletFrame& frame, int table_size);

// Operations per <prefix>_eval call, as printed.
OpCount needlet_lut_ops(const frames::NeedletFrame& frame, frames::Interpolation interpolation);

}  // namespace zhf::codegen
