// What the GLSL, HLSL and WGSL runners share: each order's functions wrapped in one compute
// shader (storage buffers, and the count as a push constant, or in WGSL the rotations' length;
// invocation i runs mode i / count on input i % count), compiled to SPIR-V (glslangValidator;
// WGSL: naga through Node), validated by spirv-val, and run through the Vulkan device in float.
// The WebGPU runner (webgpu_runner.cc) runs the same WGSL wrapper in a browser.
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

// The WGSL wrapper of one order's functions: core WebGPU, entry point main, bind group 0 holding
// the rotations (kRotationStride floats each), the coefficients and the results.
std::string wgsl_wrapper(int order, const std::string& kernels, const std::vector<Mode>& modes);

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

// WGSL in a browser's WebGPU: the wrapper run by headless Chromium (web/browser/run_compute.mjs
// under Node, in the directory RunRequest::browser_scripts names), compiled by its Tint.
std::unique_ptr<Runner> make_webgpu_runner();
// Why WGSL cannot run in a browser here (no node, no scripts at browser_scripts), or "".
std::string webgpu_missing(const std::string& browser_scripts);

}  // namespace zhf::verify
