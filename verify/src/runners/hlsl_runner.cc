// HLSL: the wrapper compiled by glslangValidator's HLSL front end (shader_runner.cc).
#include "shader_runner.h"

namespace zhf::verify {

std::unique_ptr<Runner> make_hlsl_runner() { return make_shader_runner(hlsl_dialect()); }

}  // namespace zhf::verify
