#include "zhf/io/files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include "zhf/io/errors.h"

namespace zhf::io {

PendingFile::PendingFile(std::string destination) : destination_(std::move(destination)) {
  std::string pattern = destination_ + ".tmp.XXXXXX";
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  fd_ = mkstemp(name.data());
  if (fd_ < 0) throw OutputError(destination_ + ": cannot create a temporary file beside it: " + std::strerror(errno));
  temp_ = name.data();
  // mkstemp makes the file 0600; give it the mode a plain create would have had.
  const mode_t mask = umask(0);
  umask(mask);
  fchmod(fd_, 0666 & ~mask);
}

PendingFile::~PendingFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_) std::remove(temp_.c_str());
}

void PendingFile::commit() {
  // fsync flushes the file whoever wrote it: zhf through fd_, or another program by name.
  const bool flushed = fsync(fd_) == 0;
  const bool closed = ::close(fd_) == 0;
  fd_ = -1;
  if (!flushed || !closed) throw OutputError(destination_ + ": flush failed: " + std::strerror(errno));
  if (std::rename(temp_.c_str(), destination_.c_str()) != 0)
    throw OutputError(destination_ + ": cannot move the new file into place: " + std::strerror(errno));
  committed_ = true;
}

void write_file_atomically(const std::string& path, const std::string& content) {
  PendingFile file(path);
  const char* data = content.data();
  size_t left = content.size();
  while (left > 0) {
    const ssize_t written = ::write(file.fd(), data, left);
    if (written < 0) {
      if (errno == EINTR) continue;
      throw OutputError(path + ": write failed: " + std::strerror(errno));
    }
    data += written;
    left -= static_cast<size_t>(written);
  }
  file.commit();
}

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open: " + std::strerror(errno));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InputError(path + ": read failed");
  return buffer.str();
}

nlohmann::json read_json_file(const std::string& path) { return parse_json_text(read_text_file(path), path); }

nlohmann::json parse_json_text(const std::string& text, const std::string& path) {
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) throw InputError(path + ": file is empty");
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    // e.what() is "[json.exception.parse_error.101] parse error at line 3, column 5: ...";
    // out_of_range.406 is a number too large for a double ("1e400").
    std::string what = e.what();
    const auto pos = what.find("] ");
    if (pos != std::string::npos) what = what.substr(pos + 2);
    throw InputError(path + ": not valid JSON: " + what);
  }
}

namespace {

bool is_flat_numeric_array(const nlohmann::ordered_json& value) {
  if (!value.is_array() || value.empty()) return false;
  for (const auto& item : value)
    if (!item.is_number()) return false;
  return true;
}

void write_json(const nlohmann::ordered_json& value, int indent, std::string& out) {
  const std::string pad(indent + 2, ' ');
  if (value.is_object() && !value.empty()) {
    out += "{\n";
    size_t i = 0;
    for (auto it = value.begin(); it != value.end(); ++it, ++i) {
      out += pad + nlohmann::ordered_json(it.key()).dump() + ": ";
      write_json(it.value(), indent + 2, out);
      out += (i + 1 < value.size()) ? ",\n" : "\n";
    }
    out += std::string(indent, ' ') + "}";
  } else if (value.is_array() && !value.empty() && !is_flat_numeric_array(value)) {
    out += "[\n";
    for (size_t i = 0; i < value.size(); ++i) {
      out += pad;
      write_json(value[i], indent + 2, out);
      out += (i + 1 < value.size()) ? ",\n" : "\n";
    }
    out += std::string(indent, ' ') + "]";
  } else {
    std::string flat = value.dump();
    if (is_flat_numeric_array(value)) {
      // dump() gives "[1,2,3]"; a space after each comma reads better.
      std::string spaced;
      for (char c : flat) {
        spaced += c;
        if (c == ',') spaced += ' ';
      }
      flat = spaced;
    }
    out += flat;
  }
}

}  // namespace

std::string json_text(const nlohmann::ordered_json& value) {
  std::string out;
  write_json(value, 0, out);
  return out + "\n";
}

}  // namespace zhf::io
