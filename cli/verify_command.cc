#include <algorithm>
#include <cstdio>
#include <memory>
#include <sstream>

#include "commands.h"
#include "options.h"
#include "progress.h"
#include "zhf/codegen/limits.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/signals.h"
#include "zhf/pipeline/data_root.h"
#include "zhf/runtime/enum_names.h"
#include "zhf/runtime/limits.h"
#include "zhf/verify/limits.h"
#include "zhf/verify/verify.h"

namespace zhf::cli {
namespace {

struct VerifyCommandOptions {
  std::string generated;
  std::string orders;     // empty: every order in the manifest
  std::string languages;  // empty: every language
  std::string wgsl_on = "vulkan";
  std::string out;
  std::string work_dir;
  std::string compiler;
  bool quiet = false, verbose = false;
  std::string rotations = "1000", threads = "0";
};

std::string language_names() {
  std::string names;
  for (codegen::Language l : codegen::all_languages()) names += (names.empty() ? "" : ", ") + std::string(codegen::language_name(l));
  return names;
}

std::vector<codegen::Language> parse_languages(const std::string& text) {
  if (text.empty()) return codegen::all_languages();
  std::vector<codegen::Language> languages;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ',')) {
    codegen::Language language = codegen::Language::kCpp;
    if (!codegen::parse_language(item, language))
      throw UsageError("--langs: '" + io::excerpt(item) + "' is not one of " + language_names());
    languages.push_back(language);
  }
  if (languages.empty()) throw UsageError("--langs: empty");
  return languages;
}

std::vector<verify::WgslDevice> parse_wgsl_devices(const std::string& text) {
  std::vector<verify::WgslDevice> devices;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ',')) {
    verify::WgslDevice device = verify::WgslDevice::kVulkan;
    if (!verify::parse_wgsl_device(item, device))
      throw UsageError("--wgsl-on: '" + io::excerpt(item) + "' is not " + runtime::name_list(verify::wgsl_device_names()));
    if (std::find(devices.begin(), devices.end(), device) == devices.end()) devices.push_back(device);
  }
  if (devices.empty()) throw UsageError("--wgsl-on: empty");
  return devices;
}

int run_verify_command(const VerifyCommandOptions& o) {
  const pipeline::DataRoot root = pipeline::data_root();
  verify::VerifyOptions options;
  options.generated_dir = o.generated.empty() ? root.generated() : o.generated;
  if (!o.orders.empty()) options.orders = orders_option("--orders", o.orders, runtime::kMinGeneratedOrder, codegen::kMaxEmitOrder);
  options.languages = parse_languages(o.languages);
  options.rotations = static_cast<int>(integer_option("--rotations", o.rotations, 1, verify::kMaxVerifyRotations));
  options.work_dir = o.work_dir;
  options.runtime_include = root.runtime_include;
  options.naga_wasm = root.naga_wasm();
  options.browser_scripts = root.browser_scripts();
  options.wgsl_on = parse_wgsl_devices(o.wgsl_on);
  options.compiler = o.compiler;
  options.threads = threads_option(o.threads);
  Progress progress("verify", o.quiet, o.verbose);
  options.progress = [&](int done, int total, const std::string& what) { progress.update(done, total, what); };
  // Refuse an unwritable report before the work, not after it.
  if (!o.out.empty()) io::PendingFile check(o.out);
  const verify::VerifyReport report = verify::run_verify(options);
  progress.done();
  if (!report.device.empty()) std::printf("Vulkan device: %s\n", report.device.c_str());
  std::printf("%s", report.table().c_str());
  if (!o.out.empty()) {
    io::throw_if_interrupted();
    io::write_file_atomically(o.out, io::json_text(report.to_json()));
    std::printf("wrote %s\n", o.out.c_str());
  }
  if (report.vulkan_missing) {
    std::fprintf(stderr, "zhf: no Vulkan device; GLSL/HLSL kernels were not verified (install mesa-vulkan-drivers for lavapipe, or pass --langs cpp)\n");
    return kExitNoDevice;
  }
  std::printf("%s\n", report.pass() ? "verify: pass" : "verify: FAIL");
  return report.pass() ? kExitOk : kExitFailure;
}

}  // namespace

void add_verify_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<VerifyCommandOptions>();
  CLI::App* c = app.add_subcommand("verify", "Compile and run every emitted kernel against the double reference");
  c->add_option("--generated", o->generated, "The generated tree to check (default generated, else the source tree's)");
  c->add_option("--orders", o->orders, "Orders, e.g. 2..8 or 3,5 (default: every order in the manifest)");
  c->add_option("--langs", o->languages, "Languages, comma separated (default: every language, " + language_names() + ")");
  keep_old_spelling(c, c->add_option("--out", o->out, "Write the report as JSON here"), "--json", o->out);
  c->add_option("--wgsl-on", o->wgsl_on,
                "Where WGSL runs, comma separated: " + runtime::name_list(verify::wgsl_device_names()) +
                    " (default vulkan, through naga; webgpu: headless Chromium's WebGPU, scripts/setup_web.sh)");
  c->add_option("--compiler", o->compiler, "C++ compiler and leading arguments (default $CXX, else c++)");
  add_threads_option(c, o->threads);
  add_progress_flags(c, o->quiet, o->verbose);
  c->add_option("--work-dir", o->work_dir, "Keep the harnesses, shaders and logs here (default: a private temp dir, removed)");
  c->add_option("--rotations", o->rotations, "Random rotations besides the fixed extreme set, 1.." + std::to_string(verify::kMaxVerifyRotations) + " (default 1000)");
  c->callback([o, &action] { action = [o] { return run_verify_command(*o); }; });
}

}  // namespace zhf::cli
