// One runner per language, behind one interface: it turns an emitted file and the modes to check
// into outputs on verify's inputs, compiling and running whatever that language needs. Runners
// start programs through io::run_process (an argv vector, never a shell).
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "inputs.h"
#include "zhf/codegen/backend.h"

namespace zhf::verify {

class VulkanDevice;

struct RunRequest {
  int order = 0;
  std::string kernel_file;      // the emitted file
  std::string runtime_include;  // runtime/include (the C++ runner's lanes modes)
  const Inputs* inputs = nullptr;
  std::vector<Mode> modes;
  std::string work_dir;         // a private directory for sources, programs and logs
  VulkanDevice* device = nullptr;
  std::vector<std::string> compiler;  // the C++ compiler's argv prefix
  std::string naga_wasm;        // the naga-wasm package directory (WGSL)
  std::string browser_scripts;  // web/browser (WGSL in a browser's WebGPU)
};

// outputs[p][m]: precision p (precisions[p]), mode m, in the layout of reference_outputs.
struct RunOutputs {
  std::vector<std::string> precisions;
  std::vector<std::vector<std::vector<double>>> outputs;
};

// The C++ compiler's argv from --compiler (split at spaces); empty: $CXX, else c++.
std::vector<std::string> compiler_argv(const std::string& option);
// What the C++ harnesses are compiled with: IEEE float results without contraction. -O0: the same
// bytes as -O1 (x86-64 and aarch64 compute float in float either way) and an order-8 harness
// compiles in 5 s instead of 25; the harnesses run for a fraction of a second.
inline const std::vector<std::string> kHarnessFlags = {"-std=c++17", "-O0", "-ffp-contract=off"};

// A compile or run failure, one line (the runner's log excerpt included).
struct RunFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Runner {
 public:
  virtual ~Runner() = default;
  virtual bool needs_vulkan() const = 0;
  // Which modes this language can run (C++: all; shaders: no batch entry points).
  virtual bool runs(const Mode& mode) const = 0;
  virtual RunOutputs run(const RunRequest& request) const = 0;
};

#define ZHF_LANGUAGE(Enum, id, name) std::unique_ptr<Runner> make_##id##_runner();
#include "zhf/codegen/languages.def"
#undef ZHF_LANGUAGE

std::unique_ptr<Runner> make_runner(codegen::Language language);

// Doubles to and from the files runners exchange with their programs.
void write_doubles(const std::string& path, const std::vector<double>& values);
std::vector<double> read_doubles(const std::string& path, size_t count);

}  // namespace zhf::verify
