#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "commands.h"
#include "zhf/io/files.h"
#include "zhf/verify/verify.h"

namespace zhf::cli {
namespace {

struct VerifyCommandOptions {
  std::string generated = project_path("generated");
  std::string orders;  // empty: every order in the manifest
  std::string languages = "cpp,glsl,hlsl";
  std::string json;
  std::string work_dir;
  int rotations = 1000;
};

// "2..8", "3,5,7" or "4".
std::vector<int> parse_orders(const std::string& text) {
  std::vector<int> orders;
  const auto dots = text.find("..");
  try {
    if (dots != std::string::npos) {
      const int lo = std::stoi(text.substr(0, dots)), hi = std::stoi(text.substr(dots + 2));
      for (int n = lo; n <= hi; ++n) orders.push_back(n);
    } else {
      std::stringstream s(text);
      std::string item;
      while (std::getline(s, item, ',')) orders.push_back(std::stoi(item));
    }
  } catch (const std::exception&) {
    throw UsageError("--orders: expected a range like 2..8 or a list like 3,5, found \"" + text + "\"");
  }
  if (orders.empty()) throw UsageError("--orders: no orders in \"" + text + "\"");
  for (int n : orders)
    if (n < 2 || n > 12) throw UsageError("--orders: " + std::to_string(n) + " is outside [2, 12] (the orders zhf emits)");
  return orders;
}

std::vector<std::string> parse_languages(const std::string& text) {
  std::vector<std::string> languages;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ',')) {
    if (item != "cpp" && item != "glsl" && item != "hlsl")
      throw UsageError("--langs: \"" + item + "\" is not one of cpp, glsl, hlsl");
    languages.push_back(item);
  }
  if (languages.empty()) throw UsageError("--langs: empty");
  return languages;
}

int run_verify_command(const VerifyCommandOptions& o) {
  verify::VerifyOptions options;
  options.generated_dir = o.generated;
  if (!o.orders.empty()) options.orders = parse_orders(o.orders);
  options.languages = parse_languages(o.languages);
  options.rotations = o.rotations;
  options.work_dir = o.work_dir;
  const verify::VerifyReport report = verify::run_verify(options);
  if (!report.device.empty()) std::printf("Vulkan device: %s\n", report.device.c_str());
  std::printf("%s", report.table().c_str());
  if (!o.json.empty()) {
    io::write_file_atomically(o.json, io::json_text(report.to_json()));
    std::printf("wrote %s\n", o.json.c_str());
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
  c->add_option("--generated", o->generated, "The generated/ tree to check (default generated)");
  c->add_option("--orders", o->orders, "Orders, e.g. 2..8 or 3,5 (default: every order in the manifest)");
  c->add_option("--langs", o->languages, "Languages, comma separated (default cpp,glsl,hlsl)");
  c->add_option("--json", o->json, "Write the report as JSON here");
  c->add_option("--work-dir", o->work_dir, "Keep the harnesses, shaders and logs here (default: a temp dir, removed)");
  c->add_option("--rotations", o->rotations, "Random rotations besides the fixed extreme set (default 1000)")
      ->check(CLI::Range(1, 1000000));
  c->callback([o, &action] { action = [o] { return run_verify_command(*o); }; });
}

}  // namespace zhf::cli
