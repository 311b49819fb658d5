// The names of kernel kinds, band methods and lobe-stage choices: what the manifest records, what
// the CLI parses and what its help lists.
#include <string>
#include <vector>

#include "zhf/codegen/kernels.h"
#include "zhf/runtime/enum_names.h"

namespace zhf::codegen {
namespace {

constexpr runtime::EnumName<KernelKind> kKernelKindNames[] = {
    {KernelKind::kShEval, "sh_eval"},
    {KernelKind::kLobeWeights, "lobe_weights"},
    {KernelKind::kFromSamples, "coefficients_from_samples"},
    {KernelKind::kRotate, "rotate"},
    {KernelKind::kSignalTailored, "rotate_signal_tailored"},
    {KernelKind::kBatch, "rotate_batch"},
    {KernelKind::kRotationMatrices, "rotation_matrices"},
    {KernelKind::kApplyMatrices, "apply_rotation_matrices"},
    {KernelKind::kZonal, "rotate_zonal"},
    {KernelKind::kProduct, "product"},
    {KernelKind::kSquare, "square"},
    {KernelKind::kShade, "shade"},
    {KernelKind::kShadeLobes, "shade_lobes"},
};

constexpr runtime::EnumName<BandMethod> kBandMethodNames[] = {
    {BandMethod::kLobes, "zhf"}, {BandMethod::kZxzxz, "zxzxz"}, {BandMethod::kQuadratic, "quadratic"}};

constexpr const char* kAutomatic = "auto";

}  // namespace

const char* kernel_kind_name(KernelKind kind) { return runtime::enum_name(kKernelKindNames, kind); }
bool parse_kernel_kind(const std::string& name, KernelKind& kind) { return runtime::parse_enum(kKernelKindNames, name, kind); }

bool parse_lobe_stage_choice(const std::string& name, std::optional<runtime::LobeStage>& stage) {
  runtime::LobeStage parsed = runtime::LobeStage::kFloat;
  if (name == kAutomatic) {
    stage.reset();
  } else if (runtime::parse_lobe_stage(name, parsed)) {
    stage = parsed;
  } else {
    return false;
  }
  return true;
}

std::string lobe_stage_choice_name(const std::optional<runtime::LobeStage>& stage) {
  return stage ? runtime::lobe_stage_name(*stage) : kAutomatic;
}

std::vector<std::string> lobe_stage_choices() { return runtime::enum_names(runtime::kLobeStageNames, {kAutomatic}); }

runtime::LobeStage lobe_stage_for(const runtime::LobeTable& table, const ModuleOptions& options) {
  if (table.order <= 2) return runtime::LobeStage::kFloat;  // no lobes
  return options.lobe_stage ? *options.lobe_stage : automatic_lobe_stage(table);
}

const char* band_method_name(BandMethod method) { return runtime::enum_name(kBandMethodNames, method); }

bool parse_band_method_choice(const std::string& name, std::optional<BandMethod>& method) {
  BandMethod parsed = BandMethod::kLobes;
  if (name == kAutomatic) {
    method.reset();
  } else if (runtime::parse_enum(kBandMethodNames, name, parsed)) {
    method = parsed;
  } else {
    return false;
  }
  return true;
}

std::vector<std::string> band_method_choices() { return runtime::enum_names(kBandMethodNames, {kAutomatic}); }

std::string band_method_choice_name(const std::optional<BandMethod>& method) {
  return method ? band_method_name(*method) : kAutomatic;
}

}  // namespace zhf::codegen
