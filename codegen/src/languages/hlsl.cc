// HLSL (an include file): float/float3, or double/double3 with --precision double.
#include "../shader_backend.h"

namespace zhf::codegen {

std::unique_ptr<Backend> make_hlsl_backend() {
  ShaderSpelling s;
  s.language = Language::kHlsl;
  s.extension = ".hlsli";
  s.float_vector_stem = "float";
  s.double_vector_stem = "double";
  s.double_suffix = "L";
  s.temp_qualifier = "const ";
  s.reciprocal_sqrt = "rsqrt";
  return make_shader_backend(s);
}

}  // namespace zhf::codegen
