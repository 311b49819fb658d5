// The manifest of a generated tree (manifest.json, "zhf-manifest-2"): every file zhf emitted with
// what it holds, as types. It is written and read by this code only, so verify, the benchmarks
// and the tests see exactly what generate recorded.
//
//   {"format": "zhf-manifest-2", "generator": "zhf 0.1.0", "command": "zhf generate",
//    "scene": {...} (only for a scene's tree),
//    "files": [{"path": "cpp/zhf_order3.h", "kind": "kernels", "language": "cpp", "order": 3,
//               "precision": "template", "lobe_stage": "float", "zero_bands": [],
//               "functions": [{"name": "rotate_order3", "kind": "rotate", "channels": 1,
//                              "multiplies": 70, "adds": 65}, ...],
//               "fnv1a64": "..."}, ...]}
// kind: kernels, lanes-tables (the constants of runtime/lanes.h), dispatch (zhf_paths.h, zhf_kernels.h), or
// lobe-table (lobes/*.json: only path, kind, order and fnv1a64).
// precision: template (C++), float or double (shaders).
// Every file zhf wrote is listed with its hash: generate replaces a file only when it is listed
// with its current bytes (or would get the same bytes again), so a user's file is never lost.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "zhf/codegen/backend.h"
#include "zhf/io/json.h"
#include "zhf/runtime/lobe_stage.h"

namespace zhf::codegen {

inline constexpr const char* kManifestFormat = "zhf-manifest-2";

enum class FileKind { kKernels, kLanesTables, kDispatch, kLobeTable };
enum class FilePrecision { kTemplate, kFloat, kDouble };

struct ManifestFile {
  std::string path;  // relative to the tree
  FileKind kind = FileKind::kKernels;
  Language language = Language::kCpp;
  int order = 0;     // 0 for the dispatch header
  FilePrecision precision = FilePrecision::kTemplate;
  runtime::LobeStage lobe_stage = runtime::LobeStage::kFloat;
  std::vector<int> zero_bands;
  std::vector<EmittedFunction> functions;
  std::string fnv1a64;  // of the file's bytes
};

struct Manifest {
  std::string generator;
  std::string command;
  std::optional<nlohmann::ordered_json> scene;
  std::vector<ManifestFile> files;

  // The entry of a path, or nullptr.
  const ManifestFile* find(const std::string& path) const;
  // The kernel file of an order and language, or nullptr.
  const ManifestFile* kernels(int order, Language language) const;
  // The orders that have kernel files, ascending.
  std::vector<int> orders() const;
};

nlohmann::ordered_json manifest_json(const Manifest& manifest);
// Throws InputError naming the source and the field that is wrong.
Manifest parse_manifest(const io::json::Json& root, const std::string& source);
Manifest read_manifest(const std::string& path);

// What generate needs of an existing tree's manifest, in this or the previous format
// (zhf-manifest-1): the files zhf wrote there, path -> fnv1a64. InputError when it is not a zhf
// manifest.
std::map<std::string, std::string> read_manifest_hashes(const std::string& path);

// 64-bit FNV-1a of the bytes, as 16 hex digits (the manifest's content hash).
std::string content_hash(const std::string& bytes);

}  // namespace zhf::codegen
