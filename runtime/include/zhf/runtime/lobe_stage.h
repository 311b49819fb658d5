// Where a float rotation kernel runs its lobe stage: rotating the lobe directions, evaluating the
// SH there and summing over lobes. Rounding in that stage, amplified by the lobe fit, is what
// sets a float kernel's error (docs/verification.md), so it is the one precision knob zhf has.
// Generated headers state it as an integer kLobeStage (0, 1, 2), manifests by name.
#pragma once

#include <string_view>

#include "zhf/runtime/enum_names.h"

namespace zhf::runtime {

enum class LobeStage : int {
  kFloat = 0,           // everything in the kernel's own type: fastest, error up to the model
  kDoubleRotation = 1,  // the lobes rotated in double; their SH and the sums in float
  kDouble = 2,          // R projected onto the rotations, and the whole lobe stage in double
};

inline constexpr EnumName<LobeStage> kLobeStageNames[] = {
    {LobeStage::kFloat, "float"}, {LobeStage::kDoubleRotation, "double-rotation"}, {LobeStage::kDouble, "double"}};

inline const char* lobe_stage_name(LobeStage stage) { return enum_name(kLobeStageNames, stage); }
inline bool parse_lobe_stage(std::string_view name, LobeStage& stage) { return parse_enum(kLobeStageNames, name, stage); }

}  // namespace zhf::runtime
