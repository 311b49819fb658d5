// Reading a whole input file with a size bound: the one file reader of the runtime and the tools.
// Works on regular files, pipes and devices alike: it stops one byte past the bound, so
// /dev/zero or an endless pipe is refused, not read into memory.
#pragma once

#include <cerrno>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <string>

#include "zhf/runtime/errors.h"

namespace zhf::runtime {

// Throws InputError "<path>: <problem>" when the file cannot be read or holds more than max_bytes.
inline std::string read_file(const std::string& path, std::size_t max_bytes) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) throw InputError(path + ": cannot open: " + std::strerror(errno));
  std::string text;
  char buffer[1 << 16];
  while (text.size() <= max_bytes) {
    const std::size_t got = std::fread(buffer, 1, sizeof buffer, file);
    text.append(buffer, got);
    if (got < sizeof buffer) break;
  }
  const int error = std::ferror(file) ? errno : 0;
  std::fclose(file);
  if (error) throw InputError(path + ": cannot read: " + std::strerror(error));
  if (text.size() > max_bytes)
    throw InputError(path + ": larger than the limit of " + std::to_string(max_bytes) + " bytes for this kind of file");
  return text;
}

}  // namespace zhf::runtime
