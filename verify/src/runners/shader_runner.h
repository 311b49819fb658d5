// What the GLSL and HLSL runners share: each order's functions wrapped in one compute shader
// (storage buffers, a push constant; invocation i runs mode i / count on input i % count),
// compiled to SPIR-V by glslangValidator, validated by spirv-val, and run through the Vulkan
// device in float.
#pragma once

#include <cstdint>
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

// Values as the float32 bytes of a storage buffer.
std::vector<std::uint8_t> as_floats(const std::vector<double>& values);

ShaderDialect glsl_dialect();
ShaderDialect hlsl_dialect();

// `source` written to dir/<source_name>, compiled by glslangValidator and checked by spirv-val
// (logs beside it): the SPIR-V words, or RunFailure with the log's excerpt.
std::vector<std::uint32_t> compile_spirv(const ShaderDialect& dialect, const std::string& dir, const std::string& source);

std::unique_ptr<Runner> make_shader_runner(ShaderDialect dialect);

}  // namespace zhf::verify
