// The three backends: a LanguageConfig and a file layout each.
#include <sstream>

#include "c_family_printer.h"

namespace zhf::codegen {
namespace {

std::string commented(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& line : lines) out += "// " + line + "\n";
  return out;
}

// Prints every function, collecting the op counts for the banner.
std::string print_functions(const Module& module, const LanguageConfig& config, Precision precision,
                            std::vector<FunctionCount>& counts) {
  std::string body;
  for (const Function& f : module.functions) {
    if (f.batch && !config.batch) continue;
    OpCount ops;
    body += "\n" + print_function(f, config, precision, ops);
    counts.push_back({f.name, ops});
  }
  return body;
}

std::string lobe_values(const Module& module, const LanguageConfig& config, Precision precision,
                        const std::string& row_open, const std::string& row_close) {
  std::string out;
  for (size_t d = 0; d < module.lobes.size(); ++d) {
    out += "    " + row_open;
    for (int k = 0; k < 3; ++k) out += (k ? ", " : "") + format_literal(module.lobes[d].unit[k], config, precision);
    out += row_close + (d + 1 < module.lobes.size() ? "," : "") + "  // w_" + std::to_string(d) + "\n";
  }
  return out;
}

class CppBackend : public Backend {
 public:
  std::string language() const override { return "cpp"; }
  EmittedFile emit(const Module& module, const EmitOptions& options) const override {
    LanguageConfig config;
    config.name = "cpp";
    config.scalar = "T";
    config.wrap_literals_in_type = true;
    config.temp_qualifier = "const ";
    config.function_prefix = "template <class T>\ninline ";
    config.wide_scalar = "W";
    config.wide_declaration = "using W = std::common_type_t<T, double>;  // the lobe stage's type";
    config.input_array_qualifier = "const ";
    config.batch = true;
    config.planar_channels = true;
    EmittedFile file;
    file.file_name = "zhf_order" + std::to_string(module.order) + ".h";
    const std::string body = print_functions(module, config, Precision::kDouble, file.counts);
    std::ostringstream out;
    out << banner("//", options.command, file.counts) << "#pragma once\n\n#include <cstddef>\n";
    if (module.wide_lobes) out << "#include <type_traits>\n";
    out << "\nnamespace zhf::gen {\n\n";
    out << "inline constexpr int kOrder" << module.order << " = " << module.order << ";\n";
    if (!module.lobes.empty())
      out << "// Whether the rotations below run their lobe stage in double (see the derivation below).\n"
          << "inline constexpr bool kLobeStageInDoubleOrder" << module.order << " = " << (module.wide_lobes ? "true" : "false")
          << ";\n";
    if (!module.lobes.empty()) {
      LanguageConfig plain = config;
      plain.wrap_literals_in_type = false;
      out << "\n" << commented(lobe_derivation(module, options));
      out << "inline constexpr double kLobesOrder" << module.order << "[" << module.lobes.size() << "][3] = {\n"
          << lobe_values(module, plain, Precision::kDouble, "{", "}") << "};\n";
    }
    out << body << "\n}  // namespace zhf::gen\n";
    file.text = out.str();
    return file;
  }
};

// HLSL and GLSL share everything but a few spellings.
class ShaderBackend : public Backend {
 public:
  explicit ShaderBackend(bool glsl) : glsl_(glsl) {}
  std::string language() const override { return glsl_ ? "glsl" : "hlsl"; }
  EmittedFile emit(const Module& module, const EmitOptions& options) const override {
    const bool f64 = options.precision == Precision::kDouble;
    LanguageConfig config;
    config.name = language();
    config.scalar = f64 ? "double" : "float";
    config.vector_stem = glsl_ ? (f64 ? "dvec" : "vec") : (f64 ? "double" : "float");
    config.literal_suffix = f64 ? (glsl_ ? "lf" : "L") : "f";
    config.wide_scalar = "double";
    config.wide_vector_stem = glsl_ ? "dvec" : "double";
    config.wide_literal_suffix = glsl_ ? "lf" : "L";
    config.temp_qualifier = glsl_ ? "" : "const ";  // a GLSL const must be a compile-time constant
    config.input_array_qualifier = glsl_ ? "in " : "";
    config.output_array_qualifier = "out ";
    EmittedFile file;
    const std::string suffix = f64 ? "_f64" : "";
    file.file_name = "zhf_order" + std::to_string(module.order) + suffix + (glsl_ ? ".glsl" : ".hlsli");
    const std::string body = print_functions(module, config, options.precision, file.counts);
    std::string guard = "ZHF_ORDER" + std::to_string(module.order) + (f64 ? "_F64" : "") + (glsl_ ? "_GLSL" : "_HLSLI");
    std::ostringstream out;
    out << banner("//", options.command, file.counts) << "#ifndef " << guard << "\n#define " << guard << "\n\n";
    if (!module.lobes.empty()) {
      const std::string count = std::to_string(3 * module.lobes.size());
      const std::string name = "kLobesOrder" + std::to_string(module.order);
      out << commented(lobe_derivation(module, options)) << "// Flattened: w_d = (" << name << "[3d], [3d+1], [3d+2]).\n";
      if (glsl_) {
        out << "const " << config.scalar << " " << name << "[" << count << "] = " << config.scalar << "[" << count << "](\n";
        out << lobe_values(module, config, options.precision, "", "") << ");\n";
      } else {
        out << "static const " << config.scalar << " " << name << "[" << count << "] = {\n";
        out << lobe_values(module, config, options.precision, "", "") << "};\n";
      }
    }
    out << body << "\n#endif  // " << guard << "\n";
    file.text = out.str();
    return file;
  }

 private:
  bool glsl_;
};

}  // namespace

std::unique_ptr<Backend> make_backend(const std::string& language) {
  if (language == "cpp") return std::make_unique<CppBackend>();
  if (language == "hlsl") return std::make_unique<ShaderBackend>(false);
  if (language == "glsl") return std::make_unique<ShaderBackend>(true);
  return nullptr;
}

std::vector<std::string> backend_languages() { return {"cpp", "hlsl", "glsl"}; }

}  // namespace zhf::codegen
