#include "zhf/io/files.h"

#include <fcntl.h>
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <utility>
#include <vector>

#include "zhf/io/errors.h"
#include "zhf/io/limits.h"
#include "zhf/io/private_dir.h"
#include "zhf/io/signals.h"
#include "zhf/runtime/read_file.h"

namespace zhf::io {
namespace {

std::string error_text() { return std::strerror(errno); }

std::string directory_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

// The path a write to `path` lands on: symlinks followed (a dangling one names the file to create).
std::string resolve_symlinks(const std::string& path) {
  std::string current = path;
  for (int hop = 0; hop < 40; ++hop) {
    struct stat st {};
    if (lstat(current.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return current;
    char target[PATH_MAX];
    const ssize_t length = readlink(current.c_str(), target, sizeof target - 1);
    if (length < 0) throw OutputError(path + ": cannot read the symbolic link: " + error_text());
    target[length] = '\0';
    current = target[0] == '/' ? std::string(target) : directory_of(current) + "/" + target;
  }
  throw OutputError(path + ": too many levels of symbolic links");
}

void write_all(int fd, const char* data, size_t size, const std::string& name) {
  while (size > 0) {
    const ssize_t written = ::write(fd, data, size);
    if (written < 0) {
      if (errno == EINTR) continue;
      throw OutputError(name + ": write failed: " + error_text());
    }
    data += written;
    size -= static_cast<size_t>(written);
  }
}

mode_t creation_mode() {
  const mode_t mask = umask(0);
  umask(mask);
  return 0666 & ~mask;
}

}  // namespace

std::string read_text_file(const std::string& path, std::size_t max_bytes) { return runtime::read_file(path, max_bytes); }

PendingFile::PendingFile(const std::string& destination) : destination_(resolve_symlinks(destination)) {
  struct stat st {};
  const bool exists = stat(destination_.c_str(), &st) == 0;
  if (exists && S_ISDIR(st.st_mode)) throw OutputError(destination + ": is a directory");
  const bool through = exists && !S_ISREG(st.st_mode);
  std::string pattern;
  if (through) {
    private_dir_ = make_private_dir("zhf-out");
    pattern = private_dir_ + "/out.XXXXXX";
  } else {
    pattern = destination_ + ".tmp.XXXXXX";
  }
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  fd_ = mkstemp(name.data());
  if (fd_ < 0) {
    const std::string why = error_text();
    if (!private_dir_.empty()) rmdir(private_dir_.c_str());
    throw OutputError(destination + ": cannot create a temporary file beside it: " + why);
  }
  temp_ = name.data();
  register_temporary(private_dir_.empty() ? temp_ : private_dir_);
  // mkstemp makes the file 0600; give it the mode of the file it replaces, or of a plain create.
  fchmod(fd_, exists && !through ? (st.st_mode & 07777) : creation_mode());
}

PendingFile::~PendingFile() {
  unregister_temporary(private_dir_.empty() ? temp_ : private_dir_);
  if (fd_ >= 0) ::close(fd_);
  if (!committed_) std::remove(temp_.c_str());
  if (!private_dir_.empty()) {
    if (committed_) std::remove(temp_.c_str());
    rmdir(private_dir_.c_str());
  }
}

void PendingFile::write(const std::string& text) { write_all(fd_, text.data(), text.size(), destination_); }
void PendingFile::write(const char* data, std::size_t size) { write_all(fd_, data, size, destination_); }

void PendingFile::write_at(std::uint64_t offset, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t written = ::pwrite(fd_, data, size, static_cast<off_t>(offset));
    if (written < 0) {
      if (errno == EINTR) continue;
      throw OutputError(destination_ + ": write failed: " + error_text());
    }
    data += written;
    offset += static_cast<std::uint64_t>(written);
    size -= static_cast<size_t>(written);
  }
}

void PendingFile::commit(OnInterrupt on_interrupt) {
  // A signal that came after the work's last check leaves the old file.
  if (on_interrupt == OnInterrupt::kKeepThePrevious) throw_if_interrupted();
  flush();
  if (written_through()) return move_into_place();  // may wait for a reader: the watchdog may end it
  const CommitSection section;
  move_into_place();
}

void PendingFile::flush() {
  // fsync flushes the file whoever wrote it: zhf through fd_, or another program by name.
  const bool flushed = fsync(fd_) == 0;
  const bool closed = ::close(fd_) == 0;
  fd_ = -1;
  if (!flushed || !closed) throw OutputError(destination_ + ": flush failed: " + error_text());
}

void PendingFile::move_into_place() {
  if (private_dir_.empty()) {
    if (std::rename(temp_.c_str(), destination_.c_str()) != 0)
      throw OutputError(destination_ + ": cannot move the new file into place: " + error_text());
    committed_ = true;
    unregister_temporary(temp_);  // it is the output now
    note_output_written(destination_);
    return;
  }
  // A FIFO or device: its bytes go through it; it stays what it is.
  const std::string text = runtime::read_file(temp_, kMaxPassThroughBytes);
  const int out = ::open(destination_.c_str(), O_WRONLY | O_CLOEXEC);
  if (out < 0) throw OutputError(destination_ + ": cannot open for writing: " + error_text());
  try {
    write_all(out, text.data(), text.size(), destination_);
  } catch (...) {
    ::close(out);
    throw;
  }
  ::close(out);
  committed_ = true;
  note_output_written(destination_);
}

PendingFile& PendingFiles::add(const std::string& destination) {
  files_.push_back(std::make_unique<PendingFile>(destination));
  return *files_.back();
}

void PendingFiles::commit() {
  throw_if_interrupted();
  for (const auto& file : files_) file->flush();
  for (const auto& file : files_)
    if (file->written_through()) file->move_into_place();
  const CommitSection section;
  for (const auto& file : files_)
    if (!file->written_through()) file->move_into_place();
}

void write_file_atomically(const std::string& path, const std::string& content, OnInterrupt on_interrupt) {
  PendingFile file(path);
  file.write(content);
  file.commit(on_interrupt);
}

namespace {

bool is_flat_numeric_array(const nlohmann::ordered_json& value) {
  if (!value.is_array() || value.empty()) return false;
  for (const auto& item : value) {
    if (!item.is_number()) return false;
    if (item.is_number_float() && !std::isfinite(item.get<double>()))
      throw std::logic_error("json_text: a non-finite number has no JSON form");
  }
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
    if (value.is_number_float() && !std::isfinite(value.get<double>()))
      throw std::logic_error("json_text: a non-finite number has no JSON form");
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
