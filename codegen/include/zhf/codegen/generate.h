// zhf generate / zhf emit: lobe tables in, source files and a manifest out.
#pragma once

#include <atomic>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "zhf/codegen/backend.h"
#include "zhf/codegen/manifest.h"

namespace zhf::codegen {

struct GenerateOptions {
  std::string tables_dir;           // holds order_N.json (N >= 3) and lanes_order_N.json
  std::string paths_dir;            // holds the measured path tables (path_tables.h); empty: none
  std::string out_dir;
  std::vector<int> orders = {2, 3, 4, 5, 6, 7, 8};
  std::vector<Language> languages = all_languages();
  Precision precision = Precision::kFloat;
  ModuleOptions module;
  std::map<int, ModuleOptions> module_per_order;  // overrides module where present (scene specs)
  std::optional<nlohmann::ordered_json> scene;    // recorded in the manifest; a scene's tree gets
                                                  // no lanes tables and no dispatch header
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

// Writes out_dir/{lobes,cpp,hlsl,glsl}/... and out_dir/manifest.json, all or nothing: every file
// is staged first and moved into place only when all are complete. It writes only into an empty
// or missing directory, or a zhf tree (a readable zhf manifest), and replaces an existing file only
// when the old manifest lists it with its current bytes or the new bytes are the same; anything
// else (a user's file, a directory or FIFO where a file goes) is refused before anything is
// written (OutputError). One generate at a time writes a directory: a second is refused.
GenerateResult generate(const GenerateOptions& options);

// The emitted file for one table and language, without writing anything.
EmittedFile emit_file(const runtime::LobeTable& table, Language language, const EmitOptions& options,
                      const ModuleOptions& module_options);

}  // namespace zhf::codegen
