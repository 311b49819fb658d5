// A ZIP archive, as PlayCanvas's bundled SOG (.sog) uses one: entries stored or deflated, read by
// name through the central directory; written stored, in the order given, with fixed times so the
// same entries give the same bytes. ZIP64, encryption and other methods are refused.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "zhf/io/files.h"

namespace zhf::splat {

class ZipReader {
 public:
  // Reads the central directory of the regular file at path (io::InputError if it is not a ZIP
  // archive zhf can read, or holds more than kMaxZipEntries entries).
  explicit ZipReader(const std::string& path);
  bool has(const std::string& name) const { return entries_.count(name) > 0; }
  // The entry's bytes, at most max_bytes once decompressed, its CRC checked.
  std::string read(const std::string& name, std::uint64_t max_bytes) const;

 private:
  struct Entry {
    std::uint16_t method = 0;
    std::uint32_t crc = 0;
    std::uint64_t compressed = 0, size = 0, local_header = 0;
  };
  std::string path_;
  std::uint64_t file_size_ = 0;
  std::map<std::string, Entry> entries_;
};

// (name, bytes) entries into out, stored.
void write_zip(io::PendingFile& out, const std::vector<std::pair<std::string, std::string>>& entries);

}  // namespace zhf::splat
