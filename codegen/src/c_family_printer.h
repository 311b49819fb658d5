// The printer all three backends share: straight-line SSA code from the expression graph.
#pragma once

#include <string>
#include <vector>

#include "zhf/codegen/backend.h"

namespace zhf::codegen {

struct LanguageConfig {
  std::string name;
  std::string extension;
  std::string scalar;          // "T", "float", "double"
  std::string vector_stem;     // "float", "vec": + lane count names the vector type; empty:
                               // channels are printed as separate scalars
  std::string literal_suffix;  // "f", "lf", "L"; for C++ literals are wrapped as T(...)
  bool wrap_literals_in_type = false;
  std::string temp_qualifier;  // "const " where a local may be const at run time
  std::string function_prefix; // "template <class T>\ninline " for C++
  std::string input_array_qualifier;  // "const " in C++, "in " in GLSL, "" in HLSL
  std::string output_array_qualifier; // "" in C++, "out " in shaders
  std::string wide_scalar;     // the wide type: "W" (C++), "double"; equal to scalar: no conversions
  std::string wide_vector_stem;
  std::string wide_literal_suffix;
  std::string wide_declaration;  // C++: the line defining W, printed in functions that use it
  std::string reciprocal_sqrt; // "inversesqrt", "rsqrt", C++: "reciprocal_sqrt" (a helper the header defines)
  std::string select_positive; // C++: "select_positive" (x > 0 ? a : b per lane); empty: the ?: operator
  bool batch = false;          // structure-of-arrays batch entry points
  bool planar_channels = false;  // C++: multi-channel parameters are [channels][n]
  // WGSL's spelling: `fn f(x: array<f32, n>, out: ptr<function, array<f32, n>>)`, `let t: f32 = ..;`,
  // outputs written through the pointer, vector types vec3<f32>, select(otherwise, if_positive, c).
  bool wgsl = false;
};

std::string format_literal(double value, const LanguageConfig& config, Precision precision);
// A vector of lanes of the config's scalar: float3, vec3, vec3<f32>.
std::string vector_type_name(const LanguageConfig& config, int lanes);
// The same config printing the wide type as its scalar (for the wide nodes).
LanguageConfig widened(const LanguageConfig& config);

// The function's source text; ops receives the operation count of what was printed
// (a vector operation counts once).
std::string print_function(const Function& function, const LanguageConfig& config, Precision precision,
                           OpCount& ops);
// Its parameter list as declared, and its parameters' names as a call passes them.
std::string print_parameters(const Function& function, const LanguageConfig& config);
std::string print_arguments(const Function& function);

// Every function of a module the language has (batch entry points only where config.batch), with
// the op counts for the banner and the manifest.
std::string print_functions(const Module& module, const LanguageConfig& config, Precision precision,
                            std::vector<EmittedFunction>& functions);

// Text as it may stand in a // comment: printable ASCII as it is, anything else (control
// characters that would end the comment, backslashes that would splice lines) and '%' as %XX.
std::string comment_text(const std::string& text);
// Lines as // comments.
std::string commented(const std::vector<std::string>& lines);

// The common file banner: generator, command, do-not-edit, op counts.
std::string banner(const std::string& command, const std::vector<EmittedFunction>& functions);

// The lobe directions, one row per lobe: row_open x, y, z row_close, "  // w_d".
std::string lobe_values(const Module& module, const LanguageConfig& config, Precision precision,
                        const std::string& row_open, const std::string& row_close);

// The lobe table derivation comment lines (without comment markers), for a file whose lobe stage
// is `stage` (the module's, unless the language has no double type).
std::vector<std::string> lobe_derivation(const Module& module, const EmitOptions& options, runtime::LobeStage stage);
inline std::vector<std::string> lobe_derivation(const Module& module, const EmitOptions& options) {
  return lobe_derivation(module, options, module.lobe_stage);
}

}  // namespace zhf::codegen
