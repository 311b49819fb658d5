#include "shader_backend.h"

#include <sstream>
#include <stdexcept>
#include <utility>

namespace zhf::codegen {
namespace {

class ShaderBackend : public Backend {
 public:
  explicit ShaderBackend(ShaderSpelling spelling) : s_(std::move(spelling)) {}
  Language language() const override { return s_.language; }

  EmittedFile emit(const Module& module, const EmitOptions& options) const override {
    if (module.kind != ModuleKind::kKernels)
      throw std::invalid_argument(std::string(language_name(s_.language)) + " has no layout for lanes tables (C++ only)");
    const bool f64 = options.precision == Precision::kDouble;
    LanguageConfig config;
    config.name = language_name(s_.language);
    config.scalar = f64 ? "double" : "float";
    config.vector_stem = f64 ? s_.double_vector_stem : s_.float_vector_stem;
    config.literal_suffix = f64 ? s_.double_suffix : "f";
    config.wide_scalar = "double";
    config.wide_vector_stem = s_.double_vector_stem;
    config.wide_literal_suffix = s_.double_suffix;
    config.temp_qualifier = s_.temp_qualifier;
    config.input_array_qualifier = s_.input_array_qualifier;
    config.output_array_qualifier = "out ";
    config.reciprocal_sqrt = s_.reciprocal_sqrt;
    EmittedFile file;
    file.file_name = "zhf_order" + std::to_string(module.order) + (f64 ? "_f64" : "") + s_.extension;
    const std::string body = print_functions(module, config, options.precision, file.functions);
    std::string guard = "ZHF_ORDER" + std::to_string(module.order) + (f64 ? "_F64" : "") + "_";
    for (char c : s_.extension.substr(1)) guard += static_cast<char>(c - 'a' + 'A');
    std::ostringstream out;
    out << banner(options.command, file.functions) << "#ifndef " << guard << "\n#define " << guard << "\n\n";
    if (!module.lobes.empty()) {
      const std::string count = std::to_string(3 * module.lobes.size());
      const std::string name = "kLobesOrder" + std::to_string(module.order);
      out << commented(lobe_derivation(module, options)) << "// Flattened: w_d = (" << name << "[3d], [3d+1], [3d+2]).\n";
      if (s_.array_constructor) {
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
  ShaderSpelling s_;
};

}  // namespace

std::unique_ptr<Backend> make_shader_backend(ShaderSpelling spelling) {
  return std::make_unique<ShaderBackend>(std::move(spelling));
}

}  // namespace zhf::codegen
