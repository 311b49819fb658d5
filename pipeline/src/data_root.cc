#include "zhf/pipeline/data_root.h"
#include "zhf/runtime/table_io.h"

#include <filesystem>
#include <system_error>

namespace zhf::pipeline {

namespace fs = std::filesystem;

runtime::LobeTable DataRoot::table(int order) const {
  if (order == 2) return runtime::lobe_free_table();
  return runtime::read_lobe_table(runtime::table_path(lobes(), order), order);
}

namespace {

// relative under root when it is there, else under the source tree zhf was built from.
std::string checkout_path(const std::string& root, const std::string& relative) {
  std::error_code ec;
  return fs::is_directory(root + relative, ec) ? root + relative : std::string(ZHF_SOURCE_DIR) + relative;
}

}  // namespace

std::string DataRoot::naga_wasm() const { return checkout_path(root, "/tools/node/node_modules/naga-wasm"); }
std::string DataRoot::browser_scripts() const { return checkout_path(root, "/web/browser"); }

namespace {

bool holds_tables(const fs::path& root) {
  std::error_code ec;
  return fs::is_directory(root / "generated/lobes", ec) && !fs::is_empty(root / "generated/lobes", ec);
}

}  // namespace

DataRoot data_root() {
  if (holds_tables(".")) return DataRoot{".", "./runtime/include"};
  // ZHF_INSTALLED_DATA and ZHF_INSTALLED_INCLUDE are relative to the installed binary's folder.
  std::error_code ec;
  const fs::path binary = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path bin_dir = binary.parent_path();
    const fs::path data = (bin_dir / ZHF_INSTALLED_DATA).lexically_normal();
    if (holds_tables(data)) return DataRoot{data.string(), (bin_dir / ZHF_INSTALLED_INCLUDE).lexically_normal().string()};
  }
  return DataRoot{ZHF_SOURCE_DIR, ZHF_SOURCE_DIR "/runtime/include"};
}

}  // namespace zhf::pipeline
