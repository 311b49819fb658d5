// The constants runtime/lanes.h rotates with: a lobe set chosen for the least float error
// amplification (zhf optimize --objective amplification) and its dense A_l, emitted as a C++
// header of tables (no functions). lanes.h multiplies A_l s as dense SIMD columns, so these
// tables trade the sparse tables' zeros for a smaller amplification of float rounding.
#pragma once

#include <string>

#include "zhf/codegen/emitter.h"
#include "zhf/optimizer/lobe_table.h"

namespace zhf::codegen {

// Where runtime/lanes.h runs each step, cheapest first:
//   kFloat: everything in float;
//   kLobesInDouble: the lobes rotated in double, the SH evaluation and sums in float;
//   kDouble: R projected onto the rotations and the whole lobe stage in double.
enum class LanesStage { kFloat = 0, kLobesInDouble = 1, kDouble = 2 };

// eps_f (N - 1) a_max: each rotated lobe's band-l SH and sums carry about l eps_f, and A_l
// amplifies that by up to a_l (conditioned.h). Max errors over 131072 random rotations (AVX-512,
// FMA), as multiples of it at N = 3..8: all float 0.86 to 2.1; lobes in double 0.62 to 1.13.
double lanes_float_error_model(const optimizer::LobeTable& table);
inline constexpr double kLanesFloatMargin = 2.5;
inline constexpr double kLanesLobesInDoubleMargin = 1.25;

// The cheapest stage whose model times its margin is within the float target.
LanesStage lanes_stage(const optimizer::LobeTable& table);

// zhf_lanes_orderN.h. table_path is where the table came from, for the derivation comment.
EmittedFile emit_lanes_tables(const optimizer::LobeTable& table, const std::string& command,
                              const std::string& table_path);

}  // namespace zhf::codegen
