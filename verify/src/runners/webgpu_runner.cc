// WGSL in a browser's WebGPU: the same wrapper the Vulkan runner compiles with naga, here compiled
// by Chromium's Tint and run on its WebGPU device (SwiftShader without a GPU), through
// web/browser/run_compute.mjs under Node. The results come back as float32 bytes.
#include <cstring>
#include <filesystem>

#include "shader_runner.h"
#include "zhf/io/files.h"
#include "zhf/io/process.h"
#include "zhf/runtime/limits.h"
#include "zhf/verify/limits.h"

namespace zhf::verify {
namespace {

class WebGpuRunner : public Runner {
 public:
  bool needs_vulkan() const override { return false; }
  bool runs(const Mode& mode) const override { return mode.kind != codegen::KernelKind::kBatch && !mode.lanes; }

  RunOutputs run(const RunRequest& r) const override {
    if (const std::string why = webgpu_missing(r.browser_scripts); !why.empty()) throw RunFailure(why);
    const Inputs& in = *r.inputs;
    const std::string kernels = io::read_text_file(r.kernel_file, runtime::kMaxTableBytes);
    io::write_file_atomically(r.work_dir + "/shader.wgsl", wgsl_wrapper(r.order, kernels, r.modes));
    const std::vector<std::uint8_t> rotations = as_floats(in.rotation_stream()), coefficients = as_floats(in.coeffs);
    io::write_file_atomically(r.work_dir + "/input0.bin", std::string(rotations.begin(), rotations.end()));
    io::write_file_atomically(r.work_dir + "/input1.bin", std::string(coefficients.begin(), coefficients.end()));
    const size_t block = size_t(kMaxChannels) * r.order * r.order * in.count, values = r.modes.size() * block;
    const std::size_t invocations = r.modes.size() * in.count;
    io::ProcessOptions options;
    options.stdout_path = r.work_dir + "/browser.log";
    options.time_limit_seconds = kBrowserRunSeconds;
    const io::ProcessResult result =
        io::run_process({"node", r.browser_scripts + "/run_compute.mjs", r.work_dir, std::to_string((invocations + 63) / 64),
                         std::to_string(values * sizeof(float))},
                        options);
    if (!result.ok())
      throw RunFailure(std::string(result.timed_out ? "the browser timed out" : "the browser's WebGPU refused or failed") + ": " +
                       io::log_excerpt(r.work_dir + "/browser.log", 6));
    const std::string bytes = io::read_text_file(r.work_dir + "/result.bin", values * sizeof(float));
    if (bytes.size() != values * sizeof(float)) throw RunFailure("the browser returned " + std::to_string(bytes.size()) + " bytes");
    RunOutputs out;
    out.precisions = {"float"};
    out.outputs.resize(1);
    for (size_t m = 0; m < r.modes.size(); ++m) {
      std::vector<double> got(block);
      for (size_t k = 0; k < block; ++k) {
        float f;
        std::memcpy(&f, &bytes[(m * block + k) * sizeof(float)], sizeof f);
        got[k] = f;
      }
      out.outputs[0].push_back(std::move(got));
    }
    return out;
  }
};

}  // namespace

std::string webgpu_missing(const std::string& browser_scripts) {
  if (!io::program_available("node")) return "node not found: WGSL runs in Chromium driven from Node (scripts/setup_web.sh)";
  std::error_code ec;
  if (browser_scripts.empty() || !std::filesystem::is_regular_file(browser_scripts + "/run_compute.mjs", ec))
    return "web/browser/run_compute.mjs not found at '" + runtime::excerpt(browser_scripts, 200) + "'";
  return "";
}

std::unique_ptr<Runner> make_webgpu_runner() { return std::make_unique<WebGpuRunner>(); }

}  // namespace zhf::verify
