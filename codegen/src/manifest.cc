#include "zhf/codegen/manifest.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <set>

#include "zhf/codegen/limits.h"
#include "zhf/io/files.h"
#include "zhf/io/limits.h"
#include "zhf/runtime/enum_names.h"
#include "zhf/runtime/limits.h"

namespace zhf::codegen {
namespace {

constexpr runtime::EnumName<FileKind> kFileKindNames[] = {{FileKind::kKernels, "kernels"},
                                                           {FileKind::kLanesTables, "lanes-tables"},
                                                           {FileKind::kDispatch, "dispatch"},
                                                           {FileKind::kLobeTable, "lobe-table"}};
constexpr runtime::EnumName<FilePrecision> kPrecisionNames[] = {
    {FilePrecision::kTemplate, "template"}, {FilePrecision::kFloat, "float"}, {FilePrecision::kDouble, "double"}};

}  // namespace

const ManifestFile* Manifest::find(const std::string& path) const {
  for (const ManifestFile& f : files)
    if (f.path == path) return &f;
  return nullptr;
}

const ManifestFile* Manifest::kernels(int order, Language language) const {
  for (const ManifestFile& f : files)
    if (f.kind == FileKind::kKernels && f.order == order && f.language == language) return &f;
  return nullptr;
}

std::vector<int> Manifest::orders() const {
  std::set<int> orders;
  for (const ManifestFile& f : files)
    if (f.kind == FileKind::kKernels) orders.insert(f.order);
  return {orders.begin(), orders.end()};
}

nlohmann::ordered_json manifest_json(const Manifest& manifest) {
  nlohmann::ordered_json j;
  j["format"] = kManifestFormat;
  j["generator"] = manifest.generator;
  j["command"] = manifest.command;
  if (manifest.scene) j["scene"] = *manifest.scene;
  nlohmann::ordered_json files = nlohmann::ordered_json::array();
  for (const ManifestFile& f : manifest.files) {
    nlohmann::ordered_json functions = nlohmann::ordered_json::array();
    for (const EmittedFunction& fn : f.functions)
      functions.push_back({{"name", fn.name},
                           {"kind", kernel_kind_name(fn.kind)},
                           {"channels", fn.channels},
                           {"multiplies", fn.ops.multiplies},
                           {"adds", fn.ops.adds},
                           {"others", fn.ops.others}});
    nlohmann::ordered_json entry = {{"path", f.path}, {"kind", runtime::enum_name(kFileKindNames, f.kind)}};
    if (f.kind != FileKind::kLobeTable) entry["language"] = language_name(f.language);
    entry["order"] = f.order;
    if (f.kind != FileKind::kLobeTable) {
      entry["precision"] = runtime::enum_name(kPrecisionNames, f.precision);
      entry["lobe_stage"] = runtime::lobe_stage_name(f.lobe_stage);
      entry["zero_bands"] = f.zero_bands;
      entry["functions"] = functions;
    }
    entry["fnv1a64"] = f.fnv1a64;
    files.push_back(entry);
  }
  j["files"] = files;
  return j;
}

Manifest parse_manifest(const io::json::Json& root, const std::string& source) {
  using io::json::Field;
  const Field top(root, source);
  top.allow_only({"format", "generator", "command", "scene", "files"});
  const Field format = top.member("format");
  if (format.string() != kManifestFormat)
    format.fail("'" + runtime::excerpt(format.string()) + "' is not " + kManifestFormat + " (regenerate the tree with this zhf)");
  Manifest manifest;
  manifest.generator = top.member("generator").string();
  manifest.command = top.member("command").string();
  if (const auto scene = top.find("scene")) manifest.scene = scene->value();
  for (const Field& f : top.member("files").items(0, codegen::kMaxManifestFiles)) {
    ManifestFile file;
    const Field path = f.member("path");
    file.path = path.string();
    // A relative path inside the tree: no way out of it.
    if (file.path.empty() || file.path[0] == '/' || file.path.find("..") != std::string::npos || !runtime::is_printable_text(file.path))
      path.fail("must be a relative path inside the tree");
    runtime::parse_enum(kFileKindNames, f.member("kind").one_of(runtime::enum_names(kFileKindNames)), file.kind);
    if (file.kind == FileKind::kLobeTable) {
      f.allow_only({"path", "kind", "order", "fnv1a64"});
      file.order = f.member("order").integer(runtime::kMinTableOrder, runtime::kMaxTableOrder);
      file.fnv1a64 = f.member("fnv1a64").string();
      manifest.files.push_back(std::move(file));
      continue;
    }
    f.allow_only({"path", "kind", "language", "order", "precision", "lobe_stage", "zero_bands", "functions", "fnv1a64"});
    const Field language = f.member("language");
    if (!parse_language(language.string(), file.language)) language.fail("'" + runtime::excerpt(language.string()) + "' is not a language zhf emits");
    file.order = f.member("order").integer(file.kind == FileKind::kDispatch ? 0 : runtime::kMinGeneratedOrder, codegen::kMaxEmitOrder);
    runtime::parse_enum(kPrecisionNames, f.member("precision").one_of(runtime::enum_names(kPrecisionNames)), file.precision);
    runtime::parse_lobe_stage(f.member("lobe_stage").one_of(runtime::enum_names(runtime::kLobeStageNames)), file.lobe_stage);
    for (const Field& band : f.member("zero_bands").items(0, codegen::kMaxEmitOrder))
      file.zero_bands.push_back(band.integer(0, std::max(0, file.order - 1)));
    for (const Field& fn : f.member("functions").items(0, codegen::kMaxManifestFunctions)) {
      fn.allow_only({"name", "kind", "channels", "multiplies", "adds", "others"});
      EmittedFunction function;
      function.name = fn.member("name").string();
      if (!runtime::is_printable_text(function.name)) fn.member("name").fail("not a function name");
      const Field kind_field = fn.member("kind");
      if (!parse_kernel_kind(kind_field.string(), function.kind))
        kind_field.fail("'" + runtime::excerpt(kind_field.string()) + "' is not a kind of function zhf emits");
      function.channels = fn.member("channels").integer(1, io::kMaxChannels);
      function.ops.multiplies = fn.member("multiplies").integer(0LL, kMaxFunctionOps);
      function.ops.adds = fn.member("adds").integer(0LL, kMaxFunctionOps);
      if (const auto others = fn.find("others")) function.ops.others = others->integer(0LL, kMaxFunctionOps);  // absent: none
      file.functions.push_back(function);
    }
    file.fnv1a64 = f.member("fnv1a64").string();
    manifest.files.push_back(std::move(file));
  }
  return manifest;
}

Manifest read_manifest(const std::string& path) {
  return parse_manifest(io::json::read_file(path, codegen::kMaxManifestBytes), path);
}

std::map<std::string, std::string> read_manifest_hashes(const std::string& path) {
  using io::json::Field;
  const io::json::Json root = io::json::read_file(path, codegen::kMaxManifestBytes);
  const Field top(root, path);
  const std::string& format = top.member("format").one_of({kManifestFormat, "zhf-manifest-1"});
  std::map<std::string, std::string> hashes;
  if (format == kManifestFormat) {
    for (const ManifestFile& f : parse_manifest(root, path).files) hashes[f.path] = f.fnv1a64;
    return hashes;
  }
  for (const Field& f : top.member("files").items(0, codegen::kMaxManifestFiles)) hashes[f.member("path").string()] = f.member("fnv1a64").string();
  return hashes;
}

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

}  // namespace zhf::codegen
