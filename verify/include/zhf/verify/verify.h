// zhf verify: compile and run every emitted kernel on one input set and compare it with the
// independent double-precision reference in sh/, with the tolerances of runtime/tolerances.h.
// A small orchestrator: the manifest says what each file holds, one runner per language
// (verify/src/runners) compiles and runs it (C++ with the host compiler, GLSL and HLSL through
// glslang to SPIR-V on a Vulkan device), and the comparison and report are shared.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "zhf/codegen/backend.h"


namespace zhf::verify {

// Where WGSL runs: on the Vulkan device, turned into SPIR-V by naga; or in a browser's WebGPU,
// compiled by Chromium's Tint.
enum class WgslDevice { kVulkan, kWebGpu };
// "vulkan", "webgpu"; false for another name.
bool parse_wgsl_device(const std::string& name, WgslDevice& device);
std::vector<std::string> wgsl_device_names();

struct VerifyOptions {
  std::string generated_dir = "generated";  // a tree with a manifest (zhf generate)
  std::vector<int> orders;     // empty: every order in the manifest
  std::vector<codegen::Language> languages = codegen::all_languages();
  int rotations = 1000;
  std::string compiler;        // C++ compiler and its leading arguments, split at spaces; empty: $CXX, else c++
  std::string work_dir;        // kept scratch (made if missing); empty: a private temp dir, removed afterwards
  std::string runtime_include; // runtime/include, for the lanes kernels
  std::string naga_wasm;       // the naga-wasm package (WGSL to SPIR-V under Node), for WGSL
  std::vector<WgslDevice> wgsl_on = {WgslDevice::kVulkan};
  std::string browser_scripts; // web/browser, for WGSL in a browser (results named "webgpu")
  // Threads for the C++ files (0: all cores): each order's compiler and program run beside the
  // others; the report is the same on any count.
  int threads = 1;
  // Told on the calling thread before the C++ files and before each shader file: how many of how
  // many steps, and which.
  std::function<void(int done, int total, const std::string& what)> progress;
};

struct FunctionResult {
  int order = 0;
  std::string language;        // cpp, glsl, hlsl, wgsl (on Vulkan), webgpu (WGSL in a browser)
  std::string precision;       // float, double
  std::string function;
  double max_error = 0;
  double rms_error = 0;
  double max_ulps = 0;         // vs the C++ float kernel (shaders); -1: not measured (C++ itself,
                               // or a tree without the C++ file, e.g. a GLSL-only scene)
  double tolerance = 0;
  double ulp_limit = 0;
  int worst_index = -1;        // coefficient index of the largest error
  int worst_input = -1;
  bool pass = false;
};

struct VerifyReport {
  std::string device;          // the Vulkan device used, if any
  std::vector<FunctionResult> results;
  std::vector<std::string> errors;  // compile or run failures, one line each
  bool vulkan_missing = false;
  bool pass() const;
  nlohmann::ordered_json to_json() const;
  std::string table() const;   // one row per order x language x precision
};

// Whether a Vulkan device can run the shader languages here (why not, otherwise).
bool vulkan_available(std::string& why);

// Throws InputError when the tree's manifest or tables are malformed, OutputError when the work
// directory cannot be made, io::Interrupted when a signal stops it (its children stopped first).
VerifyReport run_verify(const VerifyOptions& options);

}  // namespace zhf::verify
