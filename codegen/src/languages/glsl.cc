// GLSL (Vulkan compute or any stage): float/vec3, or double/dvec3 with --precision double.
#include "../shader_backend.h"

namespace zhf::codegen {

std::unique_ptr<Backend> make_glsl_backend() {
  ShaderSpelling s;
  s.language = Language::kGlsl;
  s.extension = ".glsl";
  s.float_vector_stem = "vec";
  s.double_vector_stem = "dvec";
  s.double_suffix = "lf";
  s.input_array_qualifier = "in ";
  s.reciprocal_sqrt = "inversesqrt";
  s.array_constructor = true;
  return make_shader_backend(s);
}

}  // namespace zhf::codegen
