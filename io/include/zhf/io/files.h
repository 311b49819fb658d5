// Reading inputs and writing outputs by zhf's rules (docs/usage.md, "Files"):
// - every input is read with a size bound for its kind (its reader's limits.h), and JSON through
//   the strict reader of json.h;
// - an output is written whole or not at all: to a temporary file in the target's own directory,
//   flushed, then renamed over the target; a symlink is resolved and the file it names replaced;
//   a target that exists and is not a regular file (a FIFO, /dev/stdout, a device) is written
//   through, never replaced; a directory is refused.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>


namespace zhf::io {

// The whole file, at most max_bytes (InputError otherwise).
std::string read_text_file(const std::string& path, std::size_t max_bytes);

// Whether a commit goes ahead once SIGINT or SIGTERM has arrived (signals.h): by default it throws
// Interrupted and the destination stays as it was; an output the interrupt itself asks for
// (optimize's best table so far) is committed all the same.
enum class OnInterrupt { kKeepThePrevious, kCommit };

// A new empty file that becomes the destination only on commit(); otherwise the destructor
// removes it. Unique (concurrent runs never share one). For a regular (or missing) destination
// it sits beside it, so the commit is one rename; for a FIFO or device it sits in a private
// temporary directory and the commit copies its bytes through. Throws OutputError naming the
// destination.
class PendingFile {
 public:
  explicit PendingFile(const std::string& destination);
  ~PendingFile();
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

  const std::string& path() const { return temp_; }
  int fd() const { return fd_; }  // open for writing until commit()
  // Writes all of text to the file (for zhf's own outputs; another program writes by path()).
  void write(const std::string& text);
  void write(const char* data, std::size_t size);
  // At a byte offset of the file (always a regular file until commit), for a format whose
  // sections are filled out of order.
  void write_at(std::uint64_t offset, const char* data, std::size_t size);
  // Flushes to disk, closes and moves (or copies) the bytes to the destination.
  void commit(OnInterrupt on_interrupt = OnInterrupt::kKeepThePrevious);

 private:
  friend class PendingFiles;
  bool written_through() const { return !private_dir_.empty(); }
  void flush();            // to disk, and closed
  void move_into_place();  // the rename, or the bytes copied through a FIFO or device

  std::string destination_;  // symlinks resolved
  std::string temp_;
  std::string private_dir_;  // holds temp_ when the destination is written through
  int fd_ = -1;
  bool committed_ = false;
};

// Several outputs that make one result (a report and its plots, a kernel and its data), committed
// together or not at all: each is staged as a PendingFile; commit() throws Interrupted before
// anything is moved when a signal has arrived, else flushes them all, copies the outputs that are
// FIFOs or devices through (they cannot be undone, so they go first), and renames the others in
// one CommitSection (signals.h): an interrupt during the renames waits for the last, so the files
// are all as they were or all new.
class PendingFiles {
 public:
  PendingFile& add(const std::string& destination);
  void commit();

 private:
  std::vector<std::unique_ptr<PendingFile>> files_;
};

// PendingFile with content: the common case.
void write_file_atomically(const std::string& path, const std::string& content,
                           OnInterrupt on_interrupt = OnInterrupt::kKeepThePrevious);

// JSON text as zhf writes it everywhere: two-space indent, arrays of numbers on one line
// (matrix rows stay readable), keys in insertion order, numbers round-trip exact, trailing
// newline.
std::string json_text(const nlohmann::ordered_json& value);

}  // namespace zhf::io
