// The names of kernel kinds, band methods and lobe-stage choices: what the manifest records, what
// the CLI parses and what its help lists.
#include <string>
#include <vector>

#include "zhf/codegen/kernels.h"

namespace zhf::codegen {

const char* kernel_kind_name(KernelKind kind) {
  switch (kind) {
    case KernelKind::kShEval: return "sh_eval";
    case KernelKind::kLobeWeights: return "lobe_weights";
    case KernelKind::kFromSamples: return "coefficients_from_samples";
    case KernelKind::kRotate: return "rotate";
    case KernelKind::kSignalTailored: return "rotate_signal_tailored";
    case KernelKind::kBatch: return "rotate_batch";
    case KernelKind::kRotationMatrices: return "rotation_matrices";
    case KernelKind::kApplyMatrices: return "apply_rotation_matrices";
    case KernelKind::kZonal: return "rotate_zonal";
    case KernelKind::kProduct: return "product";
    case KernelKind::kSquare: return "square";
    case KernelKind::kShade: return "shade";
    case KernelKind::kShadeLobes: return "shade_lobes";
  }
  return "?";
}

bool parse_kernel_kind(const std::string& name, KernelKind& kind) {
  for (int k = 0; k <= static_cast<int>(KernelKind::kShadeLobes); ++k)
    if (name == kernel_kind_name(static_cast<KernelKind>(k))) {
      kind = static_cast<KernelKind>(k);
      return true;
    }
  return false;
}

bool parse_lobe_stage_choice(const std::string& name, std::optional<runtime::LobeStage>& stage) {
  runtime::LobeStage parsed = runtime::LobeStage::kFloat;
  if (name == "auto") {
    stage.reset();
  } else if (runtime::parse_lobe_stage(name, parsed)) {
    stage = parsed;
  } else {
    return false;
  }
  return true;
}

std::string lobe_stage_choice_name(const std::optional<runtime::LobeStage>& stage) {
  return stage ? runtime::lobe_stage_name(*stage) : "auto";
}

runtime::LobeStage lobe_stage_for(const runtime::LobeTable& table, const ModuleOptions& options) {
  if (table.order <= 2) return runtime::LobeStage::kFloat;  // no lobes
  return options.lobe_stage ? *options.lobe_stage : automatic_lobe_stage(table);
}


const char* band_method_name(BandMethod method) {
  switch (method) {
    case BandMethod::kLobes: return "zhf";
    case BandMethod::kZxzxz: return "zxzxz";
    case BandMethod::kQuadratic: return "quadratic";
  }
  return "?";
}

bool parse_band_method_choice(const std::string& name, std::optional<BandMethod>& method) {
  if (name == "auto") {
    method.reset();
    return true;
  }
  for (BandMethod m : {BandMethod::kLobes, BandMethod::kZxzxz, BandMethod::kQuadratic})
    if (name == band_method_name(m)) {
      method = m;
      return true;
    }
  return false;
}

std::vector<std::string> band_method_choices() {
  return {"auto", band_method_name(BandMethod::kLobes), band_method_name(BandMethod::kZxzxz),
          band_method_name(BandMethod::kQuadratic)};
}

std::string band_method_choice_name(const std::optional<BandMethod>& method) {
  return method ? band_method_name(*method) : "auto";
}
}  // namespace zhf::codegen
