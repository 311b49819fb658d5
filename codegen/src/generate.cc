#include "zhf/codegen/generate.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "zhf/codegen/lanes_tables.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"

namespace zhf::codegen {
namespace fs = std::filesystem;

namespace {

std::string precision_name(Precision p) { return p == Precision::kDouble ? "double" : "float"; }

void check_output_dir(const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw io::OutputError(dir.string() + ": exists and is not a directory");
  if (!fs::exists(dir, ec) || fs::exists(dir / "manifest.json", ec)) return;
  // A directory with nothing but zhf's own lobes/ is a generated/ tree before its first run.
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec))
    if (entry.path().filename() != "lobes")
      throw io::OutputError(dir.string() + ": not empty and has no zhf manifest.json; refusing to write into it");
}

}  // namespace

std::string content_hash(const std::string& bytes) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(h));
  return buffer;
}

EmittedFile emit_file(const optimizer::LobeTable& table, const std::string& language, const EmitOptions& options,
                      const ModuleOptions& module_options) {
  const auto backend = make_backend(language);
  if (!backend) throw std::invalid_argument("unknown language " + language);
  return backend->emit(build_module(table, module_options), options);
}

GenerateResult generate(const GenerateOptions& options) {
  const fs::path out(options.out_dir);
  check_output_dir(out);
  std::error_code ec;
  const bool created = !fs::exists(out, ec);
  fs::create_directories(out, ec);
  if (ec) throw io::OutputError(out.string() + ": cannot create: " + ec.message());
  // A run that fails or is interrupted before the commit leaves no trace: not even the output
  // directory, when this run made it.
  struct RemoveIfUnused {
    fs::path path;
    bool created;
    bool committed = false;
    ~RemoveIfUnused() {
      std::error_code ignored;
      if (created && !committed && fs::is_empty(path, ignored)) fs::remove(path, ignored);
    }
  } out_guard{out, created};
  // Staging inside out_dir keeps the final renames on one file system.
  std::string pattern = (out / ".zhf-staging-XXXXXX").string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  if (!mkdtemp(name.data())) throw io::OutputError(out.string() + ": cannot create a staging directory");
  const fs::path staging(name.data());
  struct Cleanup {
    fs::path path;
    ~Cleanup() {
      std::error_code ignored;
      fs::remove_all(path, ignored);
    }
  } cleanup{staging};

  GenerateResult result;
  nlohmann::ordered_json manifest;
  manifest["format"] = "zhf-manifest-1";
  manifest["generator"] = std::string("zhf ") + ZHF_VERSION;
  manifest["command"] = options.command;
  if (!options.scene.is_null()) manifest["scene"] = options.scene;
  nlohmann::ordered_json files = nlohmann::ordered_json::array();
  auto stage = [&](const std::string& relative, const std::string& text) {
    fs::create_directories((staging / relative).parent_path());
    io::write_file_atomically((staging / relative).string(), text);
    result.files.push_back(relative);
  };

  for (int order : options.orders) {
    if (options.stop && options.stop->load()) {
      result.interrupted = true;
      return result;
    }
    const optimizer::LobeTable table =
        order == 2 ? order2_table()
                   : optimizer::read_table((fs::path(options.tables_dir) / ("order_" + std::to_string(order) + ".json")).string());
    if (table.order != order)
      throw io::InputError(options.tables_dir + "/order_" + std::to_string(order) + ".json: order: says " +
                           std::to_string(table.order));
    const std::string table_name = "lobes/order_" + std::to_string(order) + ".json";
    stage(table_name, io::json_text(optimizer::to_json(table)));
    OrderSummary summary;
    summary.order = order;
    summary.lobes = static_cast<int>(table.lobes.size());
    summary.zeros = table.zeros;
    summary.entries = table.entries;
    summary.worst_condition = table.worst_condition();
    summary.files = 1;
    const auto custom = options.module_per_order.find(order);
    const ModuleOptions& module_options = custom != options.module_per_order.end() ? custom->second : options.module;
    const Module module = build_module(table, module_options);
    EmitOptions emit;
    emit.precision = options.precision;
    emit.command = options.command;
    emit.table_path = "generated/" + table_name;
    for (const std::string& language : options.languages) {
      const auto backend = make_backend(language);
      const EmittedFile file = backend->emit(module, emit);
      const std::string relative = language + "/" + file.file_name;
      stage(relative, file.text);
      ++summary.files;
      nlohmann::ordered_json functions = nlohmann::ordered_json::array();
      for (const FunctionCount& c : file.counts) {
        functions.push_back({{"name", c.name}, {"multiplies", c.ops.multiplies}, {"adds", c.ops.adds}});
        if (language == "cpp" && c.name == "rotate_order" + std::to_string(order)) summary.rotate_ops = c.ops;
      }
      nlohmann::ordered_json entry = {{"path", relative},
                                      {"order", order},
                                      {"language", language},
                                      {"precision", language == "cpp" ? "template" : precision_name(options.precision)},
                                      {"functions", functions}};
      if (!module_options.zero_bands.empty()) entry["zero_bands"] = module_options.zero_bands;
      entry["lobe_stage"] = wide_lobes(table, module_options.lobe_precision) ? "double" : "native";
      entry["fnv1a64"] = content_hash(file.text);
      files.push_back(entry);
    }
    // The lanes tables go with the full tree only (a scene lists exactly what it wants).
    const fs::path lanes_table = fs::path(options.tables_dir) / ("lanes_order_" + std::to_string(order) + ".json");
    const bool wants_cpp = std::find(options.languages.begin(), options.languages.end(), "cpp") != options.languages.end();
    if (options.scene.is_null() && wants_cpp && fs::exists(lanes_table, ec)) {
      const optimizer::LobeTable lanes = optimizer::read_table(lanes_table.string());
      if (lanes.order != order)
        throw io::InputError(lanes_table.string() + ": order: says " + std::to_string(lanes.order));
      const std::string lanes_name = "lobes/" + lanes_table.filename().string();
      stage(lanes_name, io::json_text(optimizer::to_json(lanes)));
      const EmittedFile file = emit_lanes_tables(lanes, options.command, "generated/" + lanes_name);
      stage("cpp/" + file.file_name, file.text);
      summary.files += 2;
      files.push_back({{"path", "cpp/" + file.file_name},
                       {"order", order},
                       {"language", "cpp"},
                       {"kind", "lanes-tables"},
                       {"functions", nlohmann::ordered_json::array()},
                       {"lanes_stage", static_cast<int>(lanes_stage(lanes))},
                       {"fnv1a64", content_hash(file.text)}});
    }
    result.orders.push_back(summary);
  }
  manifest["files"] = files;
  stage("manifest.json", io::json_text(manifest));

  if (options.stop && options.stop->load()) {
    result.interrupted = true;
    return result;
  }
  out_guard.committed = true;
  // Commit: every file is complete in staging; each rename replaces one old file whole.
  for (const std::string& relative : result.files) {
    fs::create_directories((out / relative).parent_path(), ec);
    fs::rename(staging / relative, out / relative, ec);
    if (ec) throw io::OutputError((out / relative).string() + ": cannot move into place: " + ec.message());
  }
  return result;
}

}  // namespace zhf::codegen
