// The printer all three backends share: straight-line SSA code from the expression graph.
#pragma once

#include <string>
#include <vector>

#include "zhf/codegen/emitter.h"

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
  bool batch = false;          // structure-of-arrays batch entry points
  bool planar_channels = false;  // C++: multi-channel parameters are [channels][n]
};

std::string format_literal(double value, const LanguageConfig& config, Precision precision);
// The same config printing the wide type as its scalar (for the wide nodes).
LanguageConfig widened(const LanguageConfig& config);

// The function's source text; ops receives the operation count of what was printed
// (a vector operation counts once).
std::string print_function(const Function& function, const LanguageConfig& config, Precision precision,
                           OpCount& ops);

// The common file banner: generator, command, do-not-edit, op counts.
std::string banner(const std::string& comment, const std::string& command, const std::vector<FunctionCount>& counts);

// The lobe table derivation comment lines (without comment markers).
std::vector<std::string> lobe_derivation(const Module& module, const EmitOptions& options);

}  // namespace zhf::codegen
