// Runs the real zhf binary and captures what a user would see.
#pragma once

#include <string>

namespace zhf::test {

struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// args is appended to the binary's path and run by /bin/sh.
RunResult run_zhf(const std::string& args);

// A fresh empty directory under the system temp dir.
std::string make_temp_dir();

}  // namespace zhf::test
