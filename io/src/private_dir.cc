#include "zhf/io/private_dir.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "zhf/io/errors.h"
#include "zhf/io/signals.h"

namespace zhf::io {

std::string make_private_dir(const std::string& prefix) {
  const char* tmpdir = std::getenv("TMPDIR");
  const std::string base = tmpdir && *tmpdir ? tmpdir : "/tmp";
  std::string pattern = base + "/" + prefix + "-XXXXXX";
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  if (!mkdtemp(name.data()))
    throw OutputError((tmpdir && *tmpdir ? "TMPDIR (" + excerpt(base, 200) + ")" : base) +
                      ": cannot create a private temporary directory there: " + std::strerror(errno));
  return name.data();
}

PrivateDir::PrivateDir(const std::string& prefix) : path_(make_private_dir(prefix)) { register_temporary(path_); }

PrivateDir::~PrivateDir() {
  unregister_temporary(path_);
  if (keep_) return;
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

}  // namespace zhf::io
