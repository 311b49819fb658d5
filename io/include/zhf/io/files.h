// File reading and all-or-nothing writing.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace zhf::io {

// Writes content to a temporary file beside path, flushes it to disk and renames it over
// path, so readers see either the old file or the complete new one. Throws OutputError.
void write_file_atomically(const std::string& path, const std::string& content);

// A new empty file beside a destination (destination.tmp.XXXXXX, unique, so concurrent runs
// never share one) that becomes the destination only on commit(); otherwise the destructor
// removes it. For files another program writes by name (gnuplot); zhf's own output goes
// through write_file_atomically. Throws OutputError naming the destination.
class PendingFile {
 public:
  explicit PendingFile(std::string destination);
  ~PendingFile();
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

  const std::string& path() const { return temp_; }
  int fd() const { return fd_; }  // open for writing until commit()
  // Flushes to disk, closes and renames over the destination.
  void commit();

 private:
  std::string destination_;
  std::string temp_;
  int fd_ = -1;
  bool committed_ = false;
};

// Throws InputError naming the path when it is missing or unreadable.
std::string read_text_file(const std::string& path);

// Throws InputError naming the path (and line/column) when it is empty or not valid JSON.
nlohmann::json read_json_file(const std::string& path);
// The same for text already in memory; path only names it in errors.
nlohmann::json parse_json_text(const std::string& text, const std::string& path);

// JSON text as zhf writes it everywhere: two-space indent, arrays of numbers on one line
// (matrix rows stay readable), keys in insertion order, numbers round-trip exact, trailing
// newline.
std::string json_text(const nlohmann::ordered_json& value);

}  // namespace zhf::io
