// What the GLSL, HLSL and WGSL runners share: each order's functions wrapped in one compute
// shader (storage buffers, a push constant; invocation i runs mode i / count on input i % count),
// compiled to SPIR-V (glslangValidator; WGSL: naga through Node), validated by spirv-val, and
// run through the Vulkan device in float.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "../runner.h"

namespace zhf::verify {

enum class ShaderFront { kGlsl, kHlsl, kWgsl };

struct ShaderDialect {
  ShaderFront front = ShaderFront::kGlsl;
  std::string source_name;                  // "verify.comp", "verify.hlsl", "verify.wgsl"
  std::vector<std::string> compile_flags;   // glslangValidator's, before -o
};

// Values as the float32 bytes of a storage buffer.
std::vector<std::uint8_t> as_floats(const std::vector<double>& values);

ShaderDialect glsl_dialect();
ShaderDialect hlsl_dialect();
ShaderDialect wgsl_dialect();

// Why WGSL cannot be compiled here (no node on PATH, no naga-wasm package at naga_wasm), or "".
std::string wgsl_compiler_missing(const std::string& naga_wasm);

// `source` written to dir/<source_name>, compiled by glslangValidator (WGSL: by naga-wasm, the
// package at naga_wasm, under Node) and checked by spirv-val (logs beside it): the SPIR-V words,
// or RunFailure with the log's excerpt.
std::vector<std::uint32_t> compile_spirv(const ShaderDialect& dialect, const std::string& dir, const std::string& source,
                                         const std::string& naga_wasm = "");

std::unique_ptr<Runner> make_shader_runner(ShaderDialect dialect);

}  // namespace zhf::verify
