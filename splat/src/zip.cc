#include "zip.h"

#include <algorithm>
#include <cstring>
#include <fstream>

#include <zlib.h>

#include "format_io.h"
#include "zhf/io/errors.h"
#include "zhf/splat/limits.h"

namespace zhf::splat {
namespace {

using io::InputError;

constexpr std::uint32_t kLocalHeader = 0x04034b50, kCentralHeader = 0x02014b50, kEndOfDirectory = 0x06054b50;
constexpr std::size_t kLocalHeaderBytes = 30, kCentralHeaderBytes = 46, kEndBytes = 22;
constexpr std::size_t kEndZoneBytes = 22 + 0xffff;  // the end record and the format's longest comment
constexpr std::uint16_t kStored = 0, kDeflated = 8;
// 1980-01-01 00:00 in DOS form: the same entries give the same archive.
constexpr std::uint16_t kDosTime = 0, kDosDate = (1 << 5) | 1;

std::uint16_t u16(const unsigned char* p) { return std::uint16_t(p[0] | (p[1] << 8)); }

std::string read_at(std::ifstream& file, std::uint64_t offset, std::size_t size, const std::string& path) {
  std::string bytes(size, '\0');
  file.clear();
  file.seekg(std::streamoff(offset));
  file.read(bytes.data(), std::streamsize(size));
  if (std::size_t(file.gcount()) != size) throw InputError(path + ": truncated ZIP archive");
  return bytes;
}

void put16(std::string& out, std::uint16_t v) {
  out += char(v & 0xff);
  out += char(v >> 8);
}
void put32(std::string& out, std::uint32_t v) {
  for (int b = 0; b < 4; ++b) out += char((v >> (8 * b)) & 0xff);
}

}  // namespace

ZipReader::ZipReader(const std::string& path) : path_(path) {
  file_size_ = regular_file_size(path, "a ZIP archive is read through its directory at the end");
  std::ifstream file = open_input(path);
  const std::size_t tail = std::size_t(std::min<std::uint64_t>(file_size_, kEndZoneBytes));
  if (tail < kEndBytes) throw InputError(path + ": not a ZIP archive (too short)");
  const std::string end_zone = read_at(file, file_size_ - tail, tail, path);
  std::size_t at = std::string::npos;
  for (std::size_t i = tail - kEndBytes + 1; i-- > 0;)
    if (get_uint32(reinterpret_cast<const unsigned char*>(end_zone.data() + i)) == kEndOfDirectory) {
      at = i;
      break;
    }
  if (at == std::string::npos) throw InputError(path + ": not a ZIP archive (no end of central directory)");
  const auto* end = reinterpret_cast<const unsigned char*>(end_zone.data() + at);
  const std::uint16_t count = u16(end + 10);
  const std::uint32_t directory_size = get_uint32(end + 12), directory_at = get_uint32(end + 16);
  if (u16(end + 4) != 0 || u16(end + 6) != 0 || u16(end + 8) != count) throw InputError(path + ": a multi-part ZIP archive");
  if (count > kMaxZipEntries) throw InputError(path + ": " + std::to_string(count) + " entries; at most " + std::to_string(kMaxZipEntries));
  if (directory_at == kZip32Marker || std::uint64_t(directory_at) + directory_size > file_size_ - tail + at)
    throw InputError(path + ": the central directory is not inside the archive (ZIP64 is not read)");
  const std::string directory = read_at(file, directory_at, directory_size, path);
  for (std::size_t offset = 0, k = 0; k < count; ++k) {
    if (directory.size() - offset < kCentralHeaderBytes) throw InputError(path + ": the central directory ends early");
    const auto* h = reinterpret_cast<const unsigned char*>(directory.data() + offset);
    if (get_uint32(h) != kCentralHeader) throw InputError(path + ": entry " + std::to_string(k) + ": not a central directory header");
    Entry e;
    const std::uint16_t flags = u16(h + 8);
    e.method = u16(h + 10);
    e.crc = get_uint32(h + 16);
    e.compressed = get_uint32(h + 20);
    e.size = get_uint32(h + 24);
    const std::size_t name_bytes = u16(h + 28), extra = u16(h + 30), comment = u16(h + 32);
    e.local_header = get_uint32(h + 42);
    if (directory.size() - offset - kCentralHeaderBytes < name_bytes + extra + comment)
      throw InputError(path + ": entry " + std::to_string(k) + ": runs past the central directory");
    const std::string name = directory.substr(offset + kCentralHeaderBytes, name_bytes);
    const std::string what = path + ": entry '" + runtime::excerpt(name) + "'";
    if (flags & 1) throw InputError(what + ": encrypted");
    if (e.method != kStored && e.method != kDeflated) throw InputError(what + ": compression method " + std::to_string(e.method) + "; zhf reads stored and deflated");
    if (e.compressed == kZip32Marker || e.size == kZip32Marker || e.local_header == kZip32Marker) throw InputError(what + ": ZIP64 is not read");
    if (e.method == kStored && e.compressed != e.size) throw InputError(what + ": stored, but its two sizes differ");
    // Deflate expands at most about 1032:1: a larger claim is refused before anything is allocated.
    if (double(e.size) > kMaxCompressionRatio * double(std::max<std::uint64_t>(e.compressed, 1)))
      throw InputError(what + ": " + std::to_string(e.size) + " bytes claimed from " + std::to_string(e.compressed));
    if (!entries_.emplace(name, e).second) throw InputError(what + ": appears twice");
    offset += kCentralHeaderBytes + name_bytes + extra + comment;
  }
}

std::string ZipReader::read(const std::string& name, std::uint64_t max_bytes) const {
  const auto found = entries_.find(name);
  if (found == entries_.end()) throw InputError(path_ + ": no entry '" + runtime::excerpt(name) + "'");
  const Entry& e = found->second;
  const std::string what = path_ + ": entry '" + runtime::excerpt(name) + "'";
  if (e.size > max_bytes) throw InputError(what + ": " + std::to_string(e.size) + " bytes; at most " + std::to_string(max_bytes));
  std::ifstream file = open_input(path_);
  if (e.local_header > file_size_ || file_size_ - e.local_header < kLocalHeaderBytes) throw InputError(what + ": its header is past the end");
  const std::string local = read_at(file, e.local_header, kLocalHeaderBytes, path_);
  const auto* h = reinterpret_cast<const unsigned char*>(local.data());
  if (get_uint32(h) != kLocalHeader) throw InputError(what + ": not a local header");
  const std::uint64_t data_at = e.local_header + kLocalHeaderBytes + u16(h + 26) + u16(h + 28);
  if (data_at > file_size_ || file_size_ - data_at < e.compressed) throw InputError(what + ": runs past the end of the archive");
  std::string data = read_at(file, data_at, std::size_t(e.compressed), path_);
  if (e.method == kDeflated) {
    std::string out(std::size_t(e.size), '\0');
    z_stream z{};
    if (inflateInit2(&z, -MAX_WBITS) != Z_OK) throw InputError(what + ": cannot start inflating");
    z.next_in = reinterpret_cast<Bytef*>(data.data());
    z.avail_in = uInt(data.size());
    z.next_out = reinterpret_cast<Bytef*>(out.data());
    z.avail_out = uInt(out.size());
    const int result = inflate(&z, Z_FINISH);
    const bool whole = result == Z_STREAM_END && z.avail_out == 0 && z.avail_in == 0;
    inflateEnd(&z);
    if (!whole) throw InputError(what + ": its deflated data does not give " + std::to_string(e.size) + " bytes");
    data = std::move(out);
  }
  if (crc32(0, reinterpret_cast<const Bytef*>(data.data()), uInt(data.size())) != e.crc) throw InputError(what + ": CRC mismatch");
  return data;
}

void write_zip(io::PendingFile& out, const std::vector<std::pair<std::string, std::string>>& entries) {
  std::string directory;
  std::uint64_t offset = 0;
  for (const auto& [name, bytes] : entries) {
    if (offset + kLocalHeaderBytes + name.size() + bytes.size() >= kZip32Marker)
      throw io::OutputError("a .sog over 4 GiB (ZIP64 is not written)");
    const std::uint32_t crc = std::uint32_t(crc32(0, reinterpret_cast<const Bytef*>(bytes.data()), uInt(bytes.size())));
    std::string header;
    put32(header, kLocalHeader);
    put16(header, 20);           // version needed: 2.0
    put16(header, 0x800);        // names in UTF-8
    put16(header, kStored);
    put16(header, kDosTime);
    put16(header, kDosDate);
    put32(header, crc);
    put32(header, std::uint32_t(bytes.size()));
    put32(header, std::uint32_t(bytes.size()));
    put16(header, std::uint16_t(name.size()));
    put16(header, 0);
    out.write(header + name);
    out.write(bytes);
    put32(directory, kCentralHeader);
    put16(directory, 20);  // made by: 2.0
    directory += header.substr(4, 26);
    put16(directory, 0);  // comment
    put16(directory, 0);  // disk
    put16(directory, 0);  // internal attributes
    put32(directory, 0);  // external attributes
    put32(directory, std::uint32_t(offset));
    directory += name;
    offset += header.size() + name.size() + bytes.size();
  }
  std::string end;
  put32(end, kEndOfDirectory);
  put16(end, 0);
  put16(end, 0);
  put16(end, std::uint16_t(entries.size()));
  put16(end, std::uint16_t(entries.size()));
  put32(end, std::uint32_t(directory.size()));
  put32(end, std::uint32_t(offset));
  put16(end, 0);
  out.write(directory + end);
}

}  // namespace zhf::splat
