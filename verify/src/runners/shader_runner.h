// What the GLSL and HLSL runners share: each order's functions wrapped in one compute shader
// (storage buffers, a push constant; invocation i runs mode i / count on input i % count),
// compiled to SPIR-V by glslangValidator, validated by spirv-val, and run through the Vulkan
// device in float.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "../runner.h"

namespace zhf::verify {

struct ShaderDialect {
  bool glsl = true;                         // else HLSL
  std::string source_name;                  // "verify.comp", "verify.hlsl"
  std::vector<std::string> compile_flags;   // glslangValidator's, before -o
};

std::unique_ptr<Runner> make_shader_runner(ShaderDialect dialect);

}  // namespace zhf::verify
