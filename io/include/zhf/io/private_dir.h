// Private temporary directories: made with mkdtemp (mode 0700, an unpredictable name) under
// $TMPDIR, or /tmp when TMPDIR is unset. Nothing zhf writes to a temporary place uses a
// predictable path.
#pragma once

#include <string>

namespace zhf::io {

// A new private directory named <prefix>-XXXXXX; OutputError naming TMPDIR when it cannot be
// made there.
std::string make_private_dir(const std::string& prefix);

// A private directory removed with everything in it when this goes out of scope (unless kept).
class PrivateDir {
 public:
  explicit PrivateDir(const std::string& prefix);
  ~PrivateDir();
  PrivateDir(const PrivateDir&) = delete;
  PrivateDir& operator=(const PrivateDir&) = delete;
  const std::string& path() const { return path_; }
  void keep() { keep_ = true; }

 private:
  std::string path_;
  bool keep_ = false;
};

}  // namespace zhf::io
