// zhf generate / zhf emit: lobe tables in, source files and a manifest out.
#pragma once

#include <atomic>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "zhf/codegen/emitter.h"

namespace zhf::codegen {

struct GenerateOptions {
  std::string tables_dir;           // holds order_N.json for N >= 3
  std::string out_dir;
  std::vector<int> orders = {2, 3, 4, 5, 6, 7, 8};
  std::vector<std::string> languages = {"cpp", "hlsl", "glsl"};
  Precision precision = Precision::kFloat;
  ModuleOptions module;
  std::map<int, ModuleOptions> module_per_order;  // overrides module where present (scene specs)
  nlohmann::ordered_json scene;                   // recorded in the manifest when not null
  std::string command = "zhf generate";  // recorded in banners and the manifest
  const std::atomic<bool>* stop = nullptr;
};

struct OrderSummary {
  int order = 0;
  int lobes = 0;
  int zeros = 0;
  int entries = 0;
  double worst_condition = 0;
  OpCount rotate_ops;  // single-channel standard rotation, as printed in C++
  int files = 0;
};

struct GenerateResult {
  std::vector<OrderSummary> orders;
  std::vector<std::string> files;  // relative to out_dir
  bool interrupted = false;
};

// Writes out_dir/{lobes,cpp,hlsl,glsl}/... and out_dir/manifest.json. Everything is emitted
// into a staging directory first and moved into place only when complete. Refuses (OutputError)
// a non-empty out_dir that has no zhf manifest.json, and never deletes a file it did not write.
GenerateResult generate(const GenerateOptions& options);

// The emitted module for one table and language, without writing anything.
EmittedFile emit_file(const optimizer::LobeTable& table, const std::string& language, const EmitOptions& options,
                      const ModuleOptions& module_options);

// 64-bit FNV-1a of the bytes, as 16 hex digits (the manifest's content hash).
std::string content_hash(const std::string& bytes);

}  // namespace zhf::codegen
