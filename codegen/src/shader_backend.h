// What HLSL and GLSL share: the file layout (include guard, flattened lobe constants, the
// functions), printed under each language's spellings.
#pragma once

#include <memory>
#include <string>

#include "c_family_printer.h"

namespace zhf::codegen {

struct ShaderSpelling {
  Language language = Language::kGlsl;
  std::string extension;            // ".glsl", ".hlsli"
  std::string float_vector_stem;    // "vec", "float"
  std::string double_vector_stem;   // "dvec", "double"
  std::string double_suffix;        // literal suffix of double constants: "lf", "L"
  std::string temp_qualifier;       // "" for GLSL (a GLSL const must be a compile-time constant)
  std::string input_array_qualifier;
  std::string reciprocal_sqrt;      // "inversesqrt", "rsqrt"
  bool array_constructor = false;   // GLSL: T[n](...); HLSL: static const T x[n] = {...}
};

std::unique_ptr<Backend> make_shader_backend(ShaderSpelling spelling);

}  // namespace zhf::codegen
