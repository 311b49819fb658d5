// WGSL (WebGPU): f32 and vec3<f32>/vec4<f32> only, so every node prints as f32 and the file's
// lobe stage is float whatever the module's (the graph, and so the operation count, is the C++
// one). WGSL has no #include: the file is plain declarations (the lobe constants, then one
// fn per function, inputs by value, outputs through ptr<function, ...>) to concatenate ahead of
// the shader that calls them.
#include <sstream>
#include <stdexcept>

#include "../c_family_printer.h"

namespace zhf::codegen {
namespace {

class WgslBackend : public Backend {
 public:
  Language language() const override { return Language::kWgsl; }
  bool has_double() const override { return false; }

  EmittedFile emit(const Module& module, const EmitOptions& options) const override {
    if (module.kind != ModuleKind::kKernels) throw std::invalid_argument("wgsl has no layout for lanes tables (C++ only)");
    if (options.precision == Precision::kDouble) throw std::invalid_argument("wgsl has no double precision (f64): emit float");
    LanguageConfig config;
    config.name = "wgsl";
    config.scalar = "f32";
    config.vector_stem = "vec";
    config.literal_suffix = "f";
    config.wide_scalar = "f32";
    config.wide_vector_stem = "vec";
    config.wide_literal_suffix = "f";
    config.reciprocal_sqrt = "inverseSqrt";
    config.wgsl = true;
    EmittedFile file;
    file.file_name = "zhf_order" + std::to_string(module.order) + ".wgsl";
    const std::string body = print_functions(module, config, Precision::kFloat, file.functions);
    std::ostringstream out;
    out << banner(options.command, file.functions);
    if (!module.lobes.empty()) {
      const std::string type = "array<f32, " + std::to_string(3 * module.lobes.size()) + ">";
      const std::string name = "kLobesOrder" + std::to_string(module.order);
      out << commented(lobe_derivation(module, options, runtime::LobeStage::kFloat)) << "// Flattened: w_d = (" << name << "[3d], [3d+1], [3d+2]).\n";
      out << "const " << name << ": " << type << " = " << type << "(\n" << lobe_values(module, config, Precision::kFloat, "", "") << ");\n";
    }
    out << body;
    file.text = out.str();
    return file;
  }
};

}  // namespace

std::unique_ptr<Backend> make_wgsl_backend() { return std::make_unique<WgslBackend>(); }

}  // namespace zhf::codegen
