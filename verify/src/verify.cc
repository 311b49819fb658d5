// The orchestrator: for each order in the manifest, one input set and its reference, then each
// language's runner on its file, then the comparison.
#include "zhf/verify/verify.h"

#include <sys/stat.h>

#include <algorithm>
#include <exception>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "inputs.h"
#include "report.h"
#include "runner.h"
#include "runners/shader_runner.h"
#include "vulkan_device.h"
#include "zhf/codegen/manifest.h"
#include "zhf/io/errors.h"
#include "zhf/io/private_dir.h"
#include "zhf/io/signals.h"
#include "zhf/runtime/enum_names.h"
#include "zhf/runtime/parallel.h"
#include "zhf/runtime/table_io.h"

namespace zhf::verify {
namespace fs = std::filesystem;

std::unique_ptr<Runner> make_runner(codegen::Language language) {
  switch (language) {
#define ZHF_LANGUAGE(Enum, id, name)  \
  case codegen::Language::Enum:       \
    return make_##id##_runner();
#include "zhf/codegen/languages.def"
#undef ZHF_LANGUAGE
  }
  return nullptr;
}

void write_doubles(const std::string& path, const std::vector<double>& values) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(double)));
  if (!out) throw RunFailure(path + ": write failed");
}

std::vector<double> read_doubles(const std::string& path, size_t count) {
  std::vector<double> values(count);
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(values.data()), std::streamsize(count * sizeof(double)));
  if (static_cast<size_t>(in.gcount()) != count * sizeof(double)) throw RunFailure(path + ": short read");
  return values;
}

std::vector<std::string> compiler_argv(const std::string& option) {
  std::string text = option;
  if (text.empty()) text = std::getenv("CXX") && *std::getenv("CXX") ? std::getenv("CXX") : "c++";
  std::istringstream words(text);
  std::vector<std::string> argv;
  for (std::string word; words >> word;) argv.push_back(word);
  return argv;
}

namespace {

using codegen::KernelKind;
using codegen::ManifestFile;

// The functions of a file to check; an apply-matrices function needs its build function.
std::vector<Mode> modes_of(const ManifestFile& file) {
  const bool has_matrices = std::any_of(file.functions.begin(), file.functions.end(),
                                        [](const codegen::EmittedFunction& f) { return f.kind == KernelKind::kRotationMatrices; });
  std::vector<Mode> modes;
  for (const codegen::EmittedFunction& f : file.functions) {
    if (f.kind == KernelKind::kRotationMatrices) continue;
    if (f.kind == KernelKind::kApplyMatrices && !has_matrices) continue;
    modes.push_back({f.kind, f.channels, f.name, false});
  }
  return modes;
}

// The scratch directory: the caller's (made if missing, kept) or a private one (removed).
class WorkDir {
 public:
  explicit WorkDir(const std::string& given) {
    if (given.empty()) {
      private_ = std::make_unique<io::PrivateDir>("zhf-verify");
      path_ = private_->path();
      return;
    }
    std::error_code ec;
    fs::create_directories(given, ec);
    struct stat st {};
    if (stat(given.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
      throw io::OutputError(given + ": --work-dir must be a directory zhf can create or write into");
    path_ = given;
  }
  // A fresh subdirectory for one run.
  std::string sub(const std::string& name) const {
    const fs::path dir = fs::path(path_) / name;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw io::OutputError(dir.string() + ": cannot create: " + ec.message());
    return dir.string();
  }

 private:
  std::unique_ptr<io::PrivateDir> private_;
  std::string path_;
};

// One run of each order: a language's runner, named as the report names it ("wgsl" on Vulkan,
// "webgpu" in a browser).
struct Target {
  codegen::Language language;
  std::string name;
  std::unique_ptr<Runner> runner;
};

}  // namespace

constexpr runtime::EnumName<WgslDevice> kWgslDeviceNames[] = {{WgslDevice::kVulkan, "vulkan"}, {WgslDevice::kWebGpu, "webgpu"}};

bool parse_wgsl_device(const std::string& name, WgslDevice& device) { return runtime::parse_enum(kWgslDeviceNames, name, device); }
std::vector<std::string> wgsl_device_names() { return runtime::enum_names(kWgslDeviceNames); }

bool vulkan_available(std::string& why) { return VulkanDevice::open(why) != nullptr; }

VerifyReport run_verify(const VerifyOptions& options) {
  VerifyReport report;
  const fs::path generated(options.generated_dir);
  const codegen::Manifest manifest = codegen::read_manifest((generated / "manifest.json").string());
  const std::vector<int> orders = options.orders.empty() ? manifest.orders() : options.orders;
  // The runs of each order: a runner per language, and WGSL on each device asked for.
  std::vector<Target> targets;
  for (codegen::Language language : options.languages) {
    if (language != codegen::Language::kWgsl) {
      targets.push_back({language, codegen::language_name(language), make_runner(language)});
      continue;
    }
    for (WgslDevice on : options.wgsl_on) {
      if (on == WgslDevice::kVulkan) {
        if (const std::string why = wgsl_compiler_missing(options.naga_wasm); !why.empty())
          report.errors.push_back("WGSL kernels were not run on Vulkan: " + why);
        else
          targets.push_back({language, "wgsl", make_runner(language)});
      } else if (const std::string why = webgpu_missing(options.browser_scripts); !why.empty()) {
        report.errors.push_back("WGSL kernels were not run in a browser: " + why);
      } else {
        targets.push_back({language, "webgpu", make_webgpu_runner()});
      }
    }
  }
  const bool want_vulkan = std::any_of(targets.begin(), targets.end(), [](const Target& t) { return t.runner->needs_vulkan(); });
  std::unique_ptr<VulkanDevice> device;
  if (want_vulkan) {
    std::string why;
    device = VulkanDevice::open(why);
    if (!device) {
      report.vulkan_missing = true;
      report.errors.push_back("no Vulkan device: " + why + "; GLSL and HLSL kernels were not run");
    } else {
      report.device = device->description();
    }
  }
  const WorkDir work(options.work_dir);
  // C++ first: the shaders' float results are compared with its float results too.
  std::stable_partition(targets.begin(), targets.end(), [](const Target& t) { return t.language == codegen::Language::kCpp; });
  const int steps = static_cast<int>(orders.size() * targets.size());

  // Each order's inputs, reference table and files, read in order; an order the manifest lacks is
  // reported where its turn comes.
  struct OrderWork {
    int order = 0;
    std::string missing;  // the error line of an order the manifest lacks
    std::optional<runtime::LobeTable> table;
    std::optional<Inputs> in;
    bool has_lanes = false;
    const ManifestFile* cpp_file = nullptr;
  };
  std::vector<OrderWork> work_of(orders.size());
  for (std::size_t k = 0; k < orders.size(); ++k) {
    OrderWork& w = work_of[k];
    w.order = orders[k];
    const ManifestFile* any = nullptr;
    for (codegen::Language language : codegen::all_languages())
      if (!any) any = manifest.kernels(w.order, language);
    if (!any) {
      w.missing = "order " + std::to_string(w.order) + ": not in " + (generated / "manifest.json").string();
      continue;
    }
    w.table = w.order == 2 ? runtime::lobe_free_table()
                           : runtime::read_lobe_table(runtime::table_path((generated / "lobes").string(), w.order), w.order);
    w.in = make_inputs(w.order, options.rotations, *w.table, any->zero_bands);
    w.has_lanes = std::any_of(manifest.files.begin(), manifest.files.end(), [&](const ManifestFile& f) {
      return f.kind == codegen::FileKind::kLanesTables && f.order == w.order;
    });
    w.cpp_file = manifest.kernels(w.order, codegen::Language::kCpp);
  }

  // One language's run of one order: its request, and its outputs or why it did not run.
  struct LanguageRun {
    bool skipped = true;  // nothing of this language to run at this order
    RunRequest request;
    RunOutputs outputs;
    std::string error;
  };
  const auto run_target = [&](const OrderWork& w, const Target& target) {
    LanguageRun run;
    const ManifestFile* file = manifest.kernels(w.order, target.language);
    if (!file || file->precision == codegen::FilePrecision::kDouble) return run;  // shaders are run in float
    const Runner* runner = target.runner.get();
    if (runner->needs_vulkan() && !device) return run;
    run.skipped = false;
    if (runner->needs_vulkan() && file->lobe_stage != runtime::LobeStage::kFloat && !device->float64()) {
      run.error = file->path + " runs its lobe stage in double and " + device->description() +
                  " lacks shaderFloat64; emit it with --lobe-stage float for such devices";
      return run;
    }
    RunRequest& request = run.request;
    request.order = w.order;
    request.kernel_file = (generated / file->path).string();
    request.runtime_include = options.runtime_include;
    request.naga_wasm = options.naga_wasm;
    request.browser_scripts = options.browser_scripts;
    request.inputs = &*w.in;
    for (const Mode& mode : modes_of(*file))
      if (runner->runs(mode)) request.modes.push_back(mode);
    if (w.has_lanes && target.language == codegen::Language::kCpp && w.order >= 3)
      request.modes.push_back({KernelKind::kRotate, 1, "rotate_lanes_order" + std::to_string(w.order), true});
    if (request.modes.empty()) {
      run.skipped = true;
      return run;
    }
    request.work_dir = work.sub("order_" + std::to_string(w.order) + "/" + target.name);
    request.device = device.get();
    request.compiler = compiler_argv(options.compiler);
    try {
      run.outputs = runner->run(request);
    } catch (const RunFailure& e) {
      run.error = e.what();
    }
    return run;
  };

  // The C++ files of every order first, on options.threads (a compiler and a program each; the
  // shaders share one Vulkan device and run after, one at a time). What each run gives is kept by
  // order, so the report is the same on any thread count.
  std::vector<LanguageRun> cpp_runs(orders.size());
  const bool wants_cpp = !targets.empty() && targets.front().language == codegen::Language::kCpp;
  if (wants_cpp) {
    if (options.progress) options.progress(0, steps, "C++ kernel files (" + std::to_string(orders.size()) + " orders)");
    std::vector<std::exception_ptr> failures(orders.size());
    runtime::parallel_for(static_cast<int>(orders.size()), runtime::worker_count(options.threads), [&](int k) {
      try {
        if (work_of[k].missing.empty()) cpp_runs[k] = run_target(work_of[k], targets.front());
      } catch (...) {
        failures[k] = std::current_exception();
      }
    });
    for (const std::exception_ptr& failure : failures)
      if (failure) std::rethrow_exception(failure);
  }

  int step = 0;
  for (std::size_t k = 0; k < orders.size(); ++k) {
    const OrderWork& w = work_of[k];
    if (!w.missing.empty()) {
      report.errors.push_back(w.missing);
      continue;
    }
    const std::string o = "order " + std::to_string(w.order);
    std::map<std::string, std::vector<double>> cpp_float;  // by function name
    // Shaders are held to the C++ float kernel in ulps only where both run the lobe stage alike
    // (a WGSL file runs it in float where the C++ one may use double).
    for (const Target& target : targets) {
      const bool cpp = target.language == codegen::Language::kCpp;
      if (options.progress && !cpp) options.progress(step, steps, "kernel files (order " + std::to_string(w.order) + ")");
      ++step;
      const LanguageRun run = cpp ? std::move(cpp_runs[k]) : run_target(w, target);
      if (run.skipped) continue;
      const std::string& name = target.name;
      const std::string tag = o + ", " + name;
      if (!run.error.empty()) {
        report.errors.push_back(tag + ": " + run.error);
        continue;
      }
      const ManifestFile* file = manifest.kernels(w.order, target.language);
      const std::vector<std::vector<double>> expected = reference_outputs(*w.in, *w.table, run.request.modes);
      const Conditioning conditioning{w.table->order > 2 ? w.table->worst_condition() : 1.0, file->lobe_stage};
      for (size_t p = 0; p < run.outputs.precisions.size(); ++p)
        for (size_t m = 0; m < run.request.modes.size(); ++m) {
          const std::vector<double>& got = run.outputs.outputs[p][m];
          if (cpp && run.outputs.precisions[p] == "float") cpp_float[run.request.modes[m].function] = got;
          const auto reference = cpp_float.find(run.request.modes[m].function);
          const bool comparable = !cpp && reference != cpp_float.end() && w.cpp_file && w.cpp_file->lobe_stage == file->lobe_stage;
          report.results.push_back(compare(*w.in, conditioning, run.request.modes[m], got, expected[m], name, run.outputs.precisions[p],
                                           comparable ? &reference->second : nullptr));
        }
    }
  }
  io::throw_if_interrupted();
  return report;
}

}  // namespace zhf::verify
