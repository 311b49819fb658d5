#include "report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <tuple>

#include "zhf/io/limits.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"

namespace zhf::verify {
namespace {

using codegen::KernelKind;

// |a - b| in units in the last place of max(|a|, |b|, kUlpFloor): near zero a plain ulp count is
// meaningless (1e-12 against 0 is a billion ulps), so differences are measured at least at the
// scale of the coefficients.
double ulp_distance(float a, float b) {
  if (a == b) return 0;
  if (!std::isfinite(a) || !std::isfinite(b)) return INFINITY;
  const float scale = std::max({std::abs(a), std::abs(b), float(zhf::tolerance::kUlpFloor)});
  const double ulp = static_cast<double>(std::nextafter(scale, INFINITY)) - scale;
  return std::abs(static_cast<double>(a) - static_cast<double>(b)) / ulp;
}

double tolerance_for(const Mode& mode, const std::string& precision, int order, const Conditioning& c) {
  using namespace zhf::tolerance;
  if (precision == "double") return kDouble;
  if (mode.kind == KernelKind::kShEval || mode.kind == KernelKind::kZonal) return kFloatEvaluation;
  if (mode.kind == KernelKind::kLobeWeights || mode.kind == KernelKind::kFromSamples) return kFloatSparse;
  if (mode.kind == KernelKind::kProduct || mode.kind == KernelKind::kSquare) return kFloatProduct;
  if (mode.kind == KernelKind::kShade || mode.kind == KernelKind::kShadeLobes)
    return float_shading(order, c.worst_condition, c.lobe_stage == runtime::LobeStage::kDouble);
  if (mode.lanes) return kFloatRotation;  // its lobe stage is chosen from its own model to meet it
  return float_rotation(order, c.worst_condition, c.lobe_stage == runtime::LobeStage::kDouble);
}

// A measured figure; a NaN or infinite one (a kernel that produced garbage) as text, since JSON
// has no such numbers.
nlohmann::ordered_json number_or_text(double x) {
  if (std::isfinite(x)) return x;
  return std::isnan(x) ? "nan" : "infinite";
}

}  // namespace

FunctionResult compare(const Inputs& in, const Conditioning& conditioning, const Mode& mode, const std::vector<double>& got,
                       const std::vector<double>& expected, const std::string& language, const std::string& precision,
                       const std::vector<double>* cpp_float) {
  FunctionResult r;
  const bool sums = mode.kind == KernelKind::kProduct || mode.kind == KernelKind::kSquare || mode.kind == KernelKind::kShade ||
                    mode.kind == KernelKind::kShadeLobes;
  r.ulp_limit = sums ? zhf::tolerance::kSumShaderUlps
                : language == "hlsl" || mode.kind == KernelKind::kApplyMatrices
                    ? zhf::tolerance::hlsl_ulps(in.order, conditioning.worst_condition)
                    : zhf::tolerance::kGlslUlps;
  r.order = in.order;
  r.language = language;
  r.precision = precision;
  r.function = mode.function;
  r.tolerance = tolerance_for(mode, precision, in.order, conditioning);
  const int n = in.order * in.order;
  const int lanes = mode.channels * n;
  double sum = 0;
  size_t terms = 0;
  for (int v = 0; v < in.count; ++v)
    for (int k = 0; k < lanes; ++k) {
      const size_t at = size_t(kMaxChannels) * n * v + k;
      const double e = std::abs(got[at] - expected[at]);
      if (!(e <= r.max_error)) {
        r.max_error = std::isnan(e) ? INFINITY : e;
        r.worst_index = k % n;
        r.worst_input = v;
      }
      sum += e * e;
      ++terms;
      if (cpp_float) r.max_ulps = std::max(r.max_ulps, ulp_distance(float(got[at]), float((*cpp_float)[at])));
    }
  if (!cpp_float) r.max_ulps = -1;
  r.rms_error = std::sqrt(sum / std::max<size_t>(1, terms));
  r.pass = r.max_error <= r.tolerance && r.max_ulps <= r.ulp_limit;
  return r;
}

bool VerifyReport::pass() const {
  if (!errors.empty() || vulkan_missing) return false;
  for (const FunctionResult& r : results)
    if (!r.pass) return false;
  return !results.empty();
}

nlohmann::ordered_json VerifyReport::to_json() const {
  using namespace zhf::tolerance;
  nlohmann::ordered_json j;
  j["format"] = "zhf-verify-1";
  j["pass"] = pass();
  j["device"] = device;
  j["tolerances"] = {{"double", kDouble},
                     {"float_rotation", kFloatRotation},
                     {"float_sh_eval", kFloatEvaluation},
                     {"float_sparse_multiply", kFloatSparse},
                     {"float_product", kFloatProduct},
                     {"product_and_shading_shader_ulps_vs_cpp_float", kSumShaderUlps},
                     {"glsl_ulps_vs_cpp_float", kGlslUlps},
                     {"hlsl_ulps_vs_cpp_float", "max(256, 8 (N-1) k_max)"}};
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const FunctionResult& r : results)
    rows.push_back({{"order", r.order},
                    {"language", r.language},
                    {"precision", r.precision},
                    {"function", r.function},
                    {"max_error", number_or_text(r.max_error)},
                    {"rms_error", number_or_text(r.rms_error)},
                    {"max_ulps", number_or_text(r.max_ulps)},
                    {"tolerance", r.tolerance},
                    {"worst_index", r.worst_index},
                    {"worst_input", r.worst_input},
                    {"pass", r.pass}});
  j["results"] = rows;
  j["errors"] = errors;
  return j;
}

std::string VerifyReport::table() const {
  // Rotations (the 1e-6 target) and the building blocks (sh_eval, the sparse products: values
  // up to ~10, their own tolerances) in separate columns.
  struct Row {
    double rotation_error = -1, other_error = -1, rms = 0, ulps = 0;
    bool pass = true;
    int functions = 0;
  };
  auto building_block = [](const std::string& f) {
    return f.rfind("sh_eval", 0) == 0 || f.rfind("lobe_weights", 0) == 0 || f.rfind("coefficients_from_samples", 0) == 0;
  };
  auto error_text = [](double e) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2e", e);
    return e < 0 ? std::string("-") : std::string(text);
  };
  std::map<std::tuple<int, std::string, std::string>, Row> rows;
  for (const FunctionResult& r : results) {
    const bool first = !rows.count({r.order, r.language, r.precision});
    Row& row = rows[{r.order, r.language, r.precision}];
    double& error = building_block(r.function) ? row.other_error : row.rotation_error;
    error = std::max(error, r.max_error);
    row.rms = std::max(row.rms, r.rms_error);
    row.ulps = first ? r.max_ulps : std::max(row.ulps, r.max_ulps);
    row.pass = row.pass && r.pass;
    ++row.functions;
  }
  std::ostringstream out;
  char line[200];
  std::snprintf(line, sizeof line, "%5s  %-6s  %-9s  %9s  %12s  %11s  %9s  %9s  %s\n", "order", "lang", "precision",
                "functions", "rotation err", "other err", "RMS", "max ulps", "result");
  out << line;
  for (const auto& [key, row] : rows) {
    const auto& [order, language, precision] = key;
    const std::string ulps = row.ulps < 0 ? "-" : std::to_string(static_cast<long long>(std::min(row.ulps, 1e15)));
    std::snprintf(line, sizeof line, "%5d  %-6s  %-9s  %9d  %12s  %11s  %9.2e  %9s  %s\n", order, language.c_str(),
                  precision.c_str(), row.functions, error_text(row.rotation_error).c_str(), error_text(row.other_error).c_str(),
                  row.rms, ulps.c_str(), row.pass ? "pass" : "FAIL");
    out << line;
  }
  for (const FunctionResult& r : results) {
    if (r.pass) continue;
    std::snprintf(line, sizeof line, "FAIL: order %d, %s %s, %s, band %d, coefficient %d (input %d): error %.3g > %.3g%s\n",
                  r.order, r.language.c_str(), r.precision.c_str(), r.function.c_str(),
                  r.worst_index < 0 ? -1 : runtime::band_of(r.worst_index), r.worst_index, r.worst_input, r.max_error, r.tolerance,
                  r.max_ulps > r.ulp_limit ? " (or too many ulps from C++ float)" : "");
    out << line;
  }
  for (const std::string& e : errors) out << "ERROR: " << e << "\n";
  return out.str();
}

}  // namespace zhf::verify
