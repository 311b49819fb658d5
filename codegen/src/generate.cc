#include "zhf/codegen/generate.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "zhf/codegen/path_headers.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/lobe_table_writer.h"
#include "zhf/io/signals.h"
#include "zhf/codegen/limits.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/table_io.h"

namespace zhf::codegen {
namespace fs = std::filesystem;

namespace {

// The staged tree: relative path -> bytes, in the order written, and the manifest entries.
struct Tree {
  std::vector<std::pair<std::string, std::string>> files;
  Manifest manifest;

  void add(const std::string& path, std::string text, ManifestFile entry) {
    entry.path = path;
    entry.fnv1a64 = content_hash(text);
    manifest.files.push_back(std::move(entry));
    files.emplace_back(path, std::move(text));
  }
};

ManifestFile code_entry(FileKind kind, Language language, int order, FilePrecision precision, const Module* module,
                        const EmittedFile& file, const ModuleOptions* options) {
  ManifestFile entry;
  entry.kind = kind;
  entry.language = language;
  entry.order = order;
  entry.precision = precision;
  if (module) entry.lobe_stage = make_backend(language)->has_double() ? module->lobe_stage : runtime::LobeStage::kFloat;
  if (options) entry.zero_bands = options->zero_bands;
  entry.functions = file.functions;
  return entry;
}

ManifestFile table_entry(int order) {
  ManifestFile entry;
  entry.kind = FileKind::kLobeTable;
  entry.order = order;
  return entry;
}

// A lock on the output directory for this process's lifetime (flock: released by the kernel if
// the process dies), so two generates never interleave their renames.
class DirectoryLock {
 public:
  explicit DirectoryLock(const fs::path& dir) {
    fd_ = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd_ < 0) throw io::OutputError(dir.string() + ": cannot open: " + std::strerror(errno));
    if (flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd_);
      throw io::OutputError(dir.string() + ": another zhf generate is writing this directory");
    }
  }
  ~DirectoryLock() { ::close(fd_); }
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;

 private:
  int fd_ = -1;
};

// Everything that could make the commit overwrite what zhf did not write is checked here,
// before anything is written.
void check_targets(const fs::path& out, const Tree& tree) {
  std::error_code ec;
  if (fs::is_empty(out, ec)) return;
  const fs::path manifest_path = out / "manifest.json";
  std::optional<std::map<std::string, std::string>> old;
  if (fs::exists(manifest_path, ec)) {
    try {
      old = read_manifest_hashes(manifest_path.string());
    } catch (const io::InputError& e) {
      throw io::OutputError(out.string() + ": has a manifest.json zhf cannot read as its own (" + e.what() +
                            "); refusing to write into it");
    }
  }
  for (const auto& [relative, text] : tree.files) {
    const fs::path target = out / relative;
    struct stat st {};
    if (lstat(target.c_str(), &st) != 0) continue;  // new
    if (!S_ISREG(st.st_mode))
      throw io::OutputError(target.string() + ": exists and is not a regular file; refusing to replace it");
    if (relative == "manifest.json") continue;  // a zhf manifest (read above) is zhf's
    if (io::read_text_file(target.string(), kMaxEmittedFileBytes) == text) continue;
    const auto recorded = old ? old->find(relative) : std::map<std::string, std::string>::const_iterator();
    if (!old || recorded == old->end() || recorded->second != content_hash(io::read_text_file(target.string(), kMaxEmittedFileBytes)))
      throw io::OutputError(target.string() + ": exists and was not written by zhf (or was changed since); refusing to replace it");
  }
  if (!old) {
    // No manifest: only a tree whose every file this run writes again unchanged (a fresh
    // generated/ holding its own lobe tables) counts as zhf's.
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(out, ec)) {
      if (!entry.is_regular_file()) continue;
      const std::string relative = entry.path().lexically_relative(out).string();
      if (relative.rfind(".zhf-staging-", 0) == 0) continue;
      const auto ours = std::find_if(tree.files.begin(), tree.files.end(), [&](const auto& f) { return f.first == relative; });
      if (ours == tree.files.end())
        throw io::OutputError(out.string() + ": not empty and has no zhf manifest.json; refusing to write into it");
    }
  }
}

// Creates out (when missing), stages the tree in a private directory inside it and renames every
// file into place. Leaves no trace when interrupted or refused: not even out, when it made it.
void commit(const fs::path& out, const Tree& tree, const std::atomic<bool>* stop, bool& interrupted) {
  std::error_code ec;
  bool created = false;
  if (!fs::exists(out, ec)) {
    fs::create_directories(out.parent_path().empty() ? "." : out.parent_path(), ec);
    if (::mkdir(out.c_str(), 0777) == 0) {
      created = true;
    } else if (errno != EEXIST) {
      throw io::OutputError(out.string() + ": cannot create: " + std::strerror(errno));
    }
  }
  struct RemoveIfUnused {
    fs::path path;
    bool created;
    ~RemoveIfUnused() {
      std::error_code ignored;
      if (created && fs::is_empty(path, ignored)) fs::remove(path, ignored);
    }
  } out_guard{out, created};
  if (!fs::is_directory(out, ec)) throw io::OutputError(out.string() + ": exists and is not a directory");
  const DirectoryLock lock(out);
  check_targets(out, tree);
  // Staging inside out keeps the final renames on one file system.
  std::string pattern = (out / ".zhf-staging-XXXXXX").string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  if (!mkdtemp(name.data())) throw io::OutputError(out.string() + ": cannot create a staging directory: " + std::strerror(errno));
  const fs::path staging(name.data());
  // Known to the watchdog, which removes it if it has to end the run.
  io::register_temporary(staging.string());
  struct Cleanup {
    fs::path path;
    ~Cleanup() {
      std::error_code ignored;
      fs::remove_all(path, ignored);
      io::unregister_temporary(path.string());
    }
  } cleanup{staging};
  for (const auto& [relative, text] : tree.files) {
    if (stop && stop->load()) {
      interrupted = true;
      return;
    }
    fs::create_directories((staging / relative).parent_path(), ec);
    io::write_file_atomically((staging / relative).string(), text);
  }
  if (stop && stop->load()) {
    interrupted = true;
    return;
  }
  out_guard.created = false;
  // Commit: every file is complete in staging; each rename replaces one old file whole, and an
  // interrupt waits for the last (the tree is all old or all new).
  const io::CommitSection section;
  for (const auto& [relative, text] : tree.files) {
    fs::create_directories((out / relative).parent_path(), ec);
    fs::rename(staging / relative, out / relative, ec);
    if (ec) throw io::OutputError((out / relative).string() + ": cannot move into place: " + ec.message());
  }
}

}  // namespace

EmittedFile emit_file(const runtime::LobeTable& table, Language language, const EmitOptions& options,
                      const ModuleOptions& module_options) {
  return make_backend(language)->emit(build_module(table, module_options), options);
}

GenerateResult generate(const GenerateOptions& options) {
  GenerateResult result;
  Tree tree;
  tree.manifest.generator = std::string("zhf ") + ZHF_VERSION;
  tree.manifest.command = options.command;
  tree.manifest.scene = options.scene;
  const bool wants_cpp = std::find(options.languages.begin(), options.languages.end(), Language::kCpp) != options.languages.end();
  const bool full_tree = !options.scene;
  std::vector<int> lanes_orders;
  for (int order : options.orders) {
    if (options.stop && options.stop->load()) {
      result.interrupted = true;
      return result;
    }
    const runtime::LobeTable table =
        order == 2 ? runtime::lobe_free_table()
                   : runtime::read_lobe_table(runtime::table_path(options.tables_dir, order), order);
    const std::string table_name = runtime::table_path("lobes", order);
    tree.add(table_name, io::lobe_table_text(table, table_name), table_entry(order));
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
    for (Language language : options.languages) {
      const EmittedFile file = make_backend(language)->emit(module, emit);
      const FilePrecision precision = language == Language::kCpp              ? FilePrecision::kTemplate
                                      : options.precision == Precision::kDouble ? FilePrecision::kDouble
                                                                                : FilePrecision::kFloat;
      const std::string relative = std::string(language_name(language)) + "/" + file.file_name;
      tree.add(relative, file.text, code_entry(FileKind::kKernels, language, order, precision, &module, file, &module_options));
      ++summary.files;
      for (const EmittedFunction& f : file.functions)
        if (language == Language::kCpp && f.kind == KernelKind::kRotate && f.channels == 1) summary.rotate_ops = f.ops;
    }
    // The lanes tables go with the full tree only (a scene lists exactly what it wants).
    const fs::path lanes_path = runtime::table_path(options.tables_dir, order, runtime::TableKind::kLanes);
    std::error_code ec;
    if (full_tree && wants_cpp && fs::exists(lanes_path, ec)) {
      const runtime::LobeTable lanes = runtime::read_lobe_table(lanes_path.string(), order);
      const std::string lanes_name = "lobes/" + lanes_path.filename().string();
      tree.add(lanes_name, io::lobe_table_text(lanes, lanes_name), table_entry(order));
      EmitOptions lanes_emit = emit;
      lanes_emit.table_path = "generated/" + lanes_name;
      const Module lanes_module = build_lanes_module(lanes);
      const EmittedFile file = make_backend(Language::kCpp)->emit(lanes_module, lanes_emit);
      tree.add("cpp/" + file.file_name, file.text,
               code_entry(FileKind::kLanesTables, Language::kCpp, order, FilePrecision::kTemplate, &lanes_module, file, nullptr));
      summary.files += 2;
      lanes_orders.push_back(order);
    }
    result.orders.push_back(summary);
  }
  if (full_tree && wants_cpp) {
    const std::vector<PathTable> tables = read_path_tables(options.paths_dir);
    for (const EmittedFile& header : {emit_paths_header(options.orders, lanes_orders, tables, options.command),
                                      emit_dispatch_header(options.orders, options.command)})
      tree.add("cpp/" + header.file_name, header.text,
               code_entry(FileKind::kDispatch, Language::kCpp, 0, FilePrecision::kTemplate, nullptr, header, nullptr));
  }
  tree.files.emplace_back("manifest.json", io::json_text(manifest_json(tree.manifest)));
  commit(options.out_dir, tree, options.stop, result.interrupted);
  if (result.interrupted) return result;
  for (const auto& [relative, text] : tree.files) result.files.push_back(relative);
  return result;
}

}  // namespace zhf::codegen
