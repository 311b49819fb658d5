#include <algorithm>
#include <string>
#include <vector>

#include "commands.h"
#include "needlets.h"
#include "options.h"
#include "zhf/codegen/limits.h"
#include "zhf/frames/cubature.h"
#include "zhf/frames/limits.h"
#include "zhf/io/errors.h"
#include "zhf/pipeline/data_root.h"
#include "zhf/runtime/enum_names.h"

namespace zhf::cli {

int top_band(const NeedletOptions& o, int lo, int hi) {
  if (!o.lmax.empty()) return static_cast<int>(integer_option("--lmax", o.lmax, lo, hi));
  if (o.order.empty()) throw UsageError("--order: required (bands 0..N-1)");
  return static_cast<int>(integer_option("--order", o.order, lo + 1, hi + 1)) - 1;
}

double dilation_option(const std::string& text) {
  return number_option("--B", text, frames::kMinDilation, frames::kMaxDilation);
}

frames::NeedletFrame needlet_frame(double dilation, int lmax, bool gauss) {
  if (gauss) return frames::NeedletFrame(dilation, lmax);
  const std::string designs = pipeline::data_root().designs();
  return frames::NeedletFrame(dilation, lmax, [&](int degree) { return frames::design_cubature(designs, degree); });
}

codegen::NeedletLutOptions lut_options(const NeedletOptions& o, const std::string& command) {
  codegen::NeedletLutOptions lut;
  lut.table_size = static_cast<int>(integer_option("--size", o.size, frames::kMinNeedletTableSize, frames::kMaxNeedletTableSize));
  if (o.interpolation == "linear") lut.interpolation = frames::Interpolation::kLinear;
  else if (o.interpolation == "quadratic") lut.interpolation = frames::Interpolation::kQuadratic;
  else throw UsageError("--interpolation: '" + io::excerpt(o.interpolation) + "' is not linear or quadratic");
  std::string why;
  if (!codegen::valid_prefix(o.prefix, why)) throw UsageError("--prefix: " + why);
  lut.prefix = o.prefix;
  lut.storage_set = static_cast<int>(integer_option("--set", o.set, 0, codegen::kMaxStorageSet));
  lut.storage_binding = static_cast<int>(integer_option("--binding", o.binding, 0, codegen::kMaxStorageBinding));
  lut.command = command;
  return lut;
}

codegen::Language language_option(const std::string& option, const std::string& name) {
  codegen::Language language;
  const auto& known = codegen::needlet_lut_languages();
  if (codegen::parse_language(name, language) && std::find(known.begin(), known.end(), language) != known.end()) return language;
  std::vector<std::string> names;
  for (codegen::Language l : known) names.push_back(codegen::language_name(l));
  throw UsageError(option + ": '" + io::excerpt(name) + "' is not " + runtime::name_list(names));
}

}  // namespace zhf::cli
