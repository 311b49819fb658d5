// HLSL: the wrapper compiled by glslangValidator's HLSL front end (entry main, compute stage);
// push constants as [[vk::push_constant]] ConstantBuffer<T>.
#include "shader_runner.h"

namespace zhf::verify {

std::unique_ptr<Runner> make_hlsl_runner() {
  return make_shader_runner({false, "verify.hlsl", {"-D", "-e", "main", "-S", "comp", "-V"}});
}

}  // namespace zhf::verify
