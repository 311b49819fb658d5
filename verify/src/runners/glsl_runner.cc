// GLSL: the wrapper compiled by glslangValidator's GLSL front end.
#include "shader_runner.h"

namespace zhf::verify {

std::unique_ptr<Runner> make_glsl_runner() { return make_shader_runner(glsl_dialect()); }

}  // namespace zhf::verify
