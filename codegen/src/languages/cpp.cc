// C++: header-only kernels in namespace zhf::gen, templated on the scalar type T, each order's
// functions also gathered in the trait gen::Kernels<N> for generic code; and the constant tables of
// the lobe-parallel kernel (runtime/lanes.h) in gen::LanesTables<N>.
#include <algorithm>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "../c_family_printer.h"
#include "zhf/runtime/table_io.h"
#include "zhf/tolerances/tolerances.h"

namespace zhf::codegen {
namespace {

// Every function callable from CUDA and HIP device code as well as from the host: nothing in
// them allocates, throws or calls the standard library but sqrt. Guarded: every order's header
// has it.
constexpr const char* kHostDevice = R"(
#ifndef ZHF_HOST_DEVICE
#if defined(__CUDACC__) || defined(__CUDA__) || defined(__HIPCC__)
#define ZHF_HOST_DEVICE __host__ __device__
#else
#define ZHF_HOST_DEVICE
#endif
#endif
)";

// What the zxzxz bands call beyond + - *, for the scalar types; a vector type brings its own
// overloads, found by argument-dependent lookup (runtime/pack.h). In device code sqrt is the
// device library's (CUDA's and HIP's math headers overload it for float and double).
constexpr const char* kKernelMath = R"(
#ifndef ZHF_GEN_KERNEL_MATH
#define ZHF_GEN_KERNEL_MATH
namespace zhf::gen {
template <class T>
ZHF_HOST_DEVICE inline T reciprocal_sqrt(const T& x) {
#if !defined(__CUDA_ARCH__) && !defined(__HIP_DEVICE_COMPILE__)
  using std::sqrt;
#endif
  return T(1) / sqrt(x);
}
template <class T>
ZHF_HOST_DEVICE inline T select_positive(const T& x, const T& if_positive, const T& otherwise) {
  return x > T(0) ? if_positive : otherwise;
}
}  // namespace zhf::gen
#endif
)";

LanguageConfig cpp_config() {
  LanguageConfig config;
  config.name = "cpp";
  config.scalar = "T";
  config.wrap_literals_in_type = true;
  config.temp_qualifier = "const ";
  config.function_prefix = "template <class T>\nZHF_HOST_DEVICE inline ";
  config.wide_scalar = "W";
  config.wide_declaration = "using W = std::common_type_t<T, double>;  // the lobe stage's type";
  config.input_array_qualifier = "const ";
  config.reciprocal_sqrt = "reciprocal_sqrt";
  config.select_positive = "select_positive";
  config.batch = true;
  config.planar_channels = true;
  return config;
}

// gen::Kernels<N>: the module's functions as static members (name without _orderN) and where its
// rotations run their lobe stage (float when every band is by zxzxz).
std::string kernels_trait(const Module& module, const LanguageConfig& config) {
  const std::string n = std::to_string(module.order);
  std::ostringstream out;
  out << "\n// The functions above for generic code (runtime/rotator.h, zhf_kernels.h).\n"
      << "template <int N>\nstruct Kernels;\ntemplate <>\nstruct Kernels<" << n << "> {\n"
      << "  static constexpr int kOrder = " << n << ";\n"
      << "  static constexpr int kLobeStage = " << static_cast<int>(module.rotation_lobe_stage())
      << ";  // runtime::LobeStage of rotate and rotate_batch: " << runtime::lobe_stage_name(module.rotation_lobe_stage()) << "\n";
  for (const Function& f : module.functions)
    out << "  template <class T>\n  ZHF_HOST_DEVICE static void " << f.member << "(" << print_parameters(f, config) << ") { " << f.name
        << "<T>(" << print_arguments(f) << "); }\n";
  out << "};\n";
  return out.str();
}

EmittedFile emit_kernels(const Module& module, const EmitOptions& options) {
  const LanguageConfig config = cpp_config();
  EmittedFile file;
  file.file_name = "zhf_order" + std::to_string(module.order) + ".h";
  const std::string body = print_functions(module, config, Precision::kDouble, file.functions);
  std::ostringstream out;
  out << banner(options.command, file.functions) << "#pragma once\n\n";
  const bool square_roots = std::any_of(file.functions.begin(), file.functions.end(),
                                        [](const EmittedFunction& f) { return f.ops.others > 0; });
  if (square_roots) out << "#include <cmath>\n";
  out << "#include <cstddef>\n" << kHostDevice;
  if (square_roots) out << kKernelMath;
  if (module.lobe_stage != runtime::LobeStage::kFloat) out << "#include <type_traits>\n";
  out << "\nnamespace zhf::gen {\n";
  if (!module.lobes.empty()) {
    LanguageConfig plain = config;
    plain.wrap_literals_in_type = false;
    out << "\n" << commented(lobe_derivation(module, options));
    out << "inline constexpr double kLobesOrder" << module.order << "[" << module.lobes.size() << "][3] = {\n"
        << lobe_values(module, plain, Precision::kDouble, "{", "}") << "};\n";
  }
  out << body << kernels_trait(module, config) << "\n}  // namespace zhf::gen\n";
  file.text = out.str();
  return file;
}

// The lanes tables: the lobes and dense A_l, read by runtime/lanes.h through gen::LanesTables<N>.
EmittedFile emit_lanes_tables(const Module& module, const EmitOptions& options) {
  const runtime::LobeTable& table = module.table;
  const int n = table.order, lobes = 2 * n - 1;
  auto number = [](double v) { return format_literal(v, LanguageConfig{}, Precision::kDouble); };
  std::ostringstream out;
  out << banner(options.command, {}) << "//   (none: constants only, read by runtime/lanes.h)\n";
  out << "#pragma once\n\nnamespace zhf::gen {\n\n";
  std::vector<std::string> derivation = {
      "Lobe directions w_d for the lobe-parallel rotation (runtime/lanes.h) at order " + std::to_string(n) + ", from",
      options.table_path + ";"};
  if (const std::string command = runtime::provenance_command(table); !command.empty()) derivation.push_back("made by: " + command);
  std::string amplification = "a_l = sqrt((2l+1)/4pi) ||A_l||_2 with lobe sharing (band l uses lobes 0..2l). a_l per band:";
  for (const runtime::TableBand& band : table.bands) {
    char text[16];
    std::snprintf(text, sizeof text, " %.3f", runtime::band_amplification(runtime::band_matrix(table, band.l)));
    amplification += text;
  }
  derivation.push_back("Continuous directions (not SH zeros) minimising the float error amplification");
  derivation.push_back(amplification + ".");
  char model[160];
  std::snprintf(model, sizeof model, "Float error model eps_f (N - 1) a_max = %.2g; with margins %.2g (float) and %.3g",
                lanes_float_error_model(table), zhf::tolerance::kLanesFloatMargin,
                zhf::tolerance::kLanesLobesInDoubleMargin);
  derivation.push_back(model);
  derivation.push_back(std::string("(") + runtime::lobe_stage_name(runtime::LobeStage::kDoubleRotation) + ") against the " + runtime::format_number(zhf::tolerance::kFloatRotation) + " target, the lobe stage is " +
                       runtime::lobe_stage_name(module.lobe_stage) + ".");
  out << commented(derivation);
  out << "template <int N>\nstruct LanesTables;\ntemplate <>\nstruct LanesTables<" << n << "> {\n";
  out << "  static constexpr int kLobeStage = " << static_cast<int>(module.lobe_stage) << ";  // runtime::LobeStage: "
      << runtime::lobe_stage_name(module.lobe_stage) << "\n";
  out << "  static constexpr double kLobes[" << lobes << "][3] = {\n";
  for (int d = 0; d < lobes; ++d) {
    const auto& w = table.lobes[d].xyz;
    out << "      {" << number(w[0]) << ", " << number(w[1]) << ", " << number(w[2]) << "}" << (d + 1 < lobes ? "," : "")
        << "  // w_" << d << "\n";
  }
  out << "  };\n";
  out << "  // kInverse[l - 2][m + l][d] = A_l = Y_l^-1, Y_l[d][m + l] = y_l^m(w_d), dense (no structural\n";
  out << "  // zeros); zero beyond 2l + 1 rows and columns. Double, from the table's inverse.\n";
  out << "  static constexpr double kInverse[" << n - 2 << "][" << lobes << "][" << lobes << "] = {\n";
  for (const runtime::TableBand& band : table.bands) {
    out << "      {  // l = " << band.l << "\n";
    for (int row = 0; row < lobes; ++row) {
      out << "          {";
      for (int d = 0; d < lobes; ++d) {
        const bool inside = row < band.inverse.rows && d < band.inverse.cols;
        out << (d ? ", " : "") << (inside ? number(band.inverse(row, d)) : "0.0");
      }
      out << "}" << (row + 1 < lobes ? "," : "") << "\n";
    }
    out << "      }" << (band.l + 1 < n ? "," : "") << "\n";
  }
  out << "  };\n};\n\n}  // namespace zhf::gen\n";
  return {"zhf_lanes_order" + std::to_string(n) + ".h", out.str(), {}};
}

class CppBackend : public Backend {
 public:
  Language language() const override { return Language::kCpp; }
  EmittedFile emit(const Module& module, const EmitOptions& options) const override {
    return module.kind == ModuleKind::kLanesTables ? emit_lanes_tables(module, options) : emit_kernels(module, options);
  }
};

}  // namespace

std::unique_ptr<Backend> make_cpp_backend() { return std::make_unique<CppBackend>(); }

}  // namespace zhf::codegen
