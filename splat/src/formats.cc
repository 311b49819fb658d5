#include "formats.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

#include "splat_math.h"
#include "zhf/io/errors.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/sh_eval.h"

namespace zhf::splat {
namespace {

namespace ply = io::ply;
using io::InputError;

// Where each field sits in the canonical record of one SH degree.
struct Canonical {
  explicit Canonical(int degree) : rest(3 * ((degree + 1) * (degree + 1) - 1)) {}
  int rest;  // f_rest values
  static constexpr int kPosition = 0, kNormal = 3, kDc = 6, kRest = 9;
  int opacity() const { return kRest + rest; }
  int scale() const { return kRest + rest + 1; }
  int rotation() const { return kRest + rest + 4; }
  int size() const { return kRest + rest + 8; }
};

std::ifstream open_input(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open: " + std::strerror(errno));
  return file;
}

// The size of a regular file, or an error saying why a stream without one cannot be read.
std::uint64_t regular_file_size(const std::string& path, const char* why) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path + ": not a regular file (" + why + ")");
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path + ": cannot read its size: " + ec.message());
  return size;
}

std::string where(const std::string& path, std::uint64_t splat, const std::string& field) {
  return path + ": splat " + std::to_string(splat) + ": " + field;
}

// ---- binary .ply, any column order, to the canonical record ----

class PlyReader : public SceneReader {
 public:
  explicit PlyReader(const std::string& path) : path_(path), file_(open_input(path)) {
    header_ = ply::read_header(file_, path);
    if (header_.format != ply::Format::kBinaryLittleEndian)
      throw InputError(path + ": ASCII .ply converts to .ply only (write .ply, or convert it to binary first)");
    layout_ = layout_of(header_, path);
    if (layout_.degree < 0) throw InputError(path + ": no f_dc_0..2 properties: nothing to convert the colour from");
    for (const char* name : {"opacity", "scale_0", "rot_0"})
      if (header_.find(name) < 0) throw InputError(path + ": no property " + name + ": converting to another format needs it");
    if (!ply::is_float(header_.properties[layout_.opacity].type)) throw InputError(path + ": property opacity is not float or double");
    const std::uint64_t size = regular_file_size(path, "a converted .ply is checked against its size first");
    const std::uint64_t expected = header_.text.size() + header_.vertices * header_.record_bytes;
    if (size != expected)
      throw InputError(path + ": " + std::to_string(size) + " bytes, but the header says " + std::to_string(expected) +
                       (size < expected ? ": truncated" : ": bytes after the last splat"));
    splats_ = header_.vertices;
    degree_ = layout_.degree;
    const Canonical c(degree_);
    source_.assign(c.size(), -1);
    for (int i = 0; i < 3; ++i) {
      source_[Canonical::kPosition + i] = layout_.position[i];
      source_[Canonical::kNormal + i] = layout_.normal[i];
      source_[Canonical::kDc + i] = layout_.dc[i];
      source_[c.scale() + i] = layout_.log_scale[i];
    }
    for (int i = 0; i < c.rest; ++i) source_[Canonical::kRest + i] = layout_.rest[i];
    source_[c.opacity()] = layout_.opacity;
    for (int i = 0; i < 4; ++i) source_[c.rotation() + i] = layout_.rotation[i];
  }

  void read(std::uint64_t first, std::uint64_t count, double* records) override {
    const Canonical c(degree_);
    buffer_.resize(count * header_.record_bytes);
    file_.read(reinterpret_cast<char*>(buffer_.data()), std::streamsize(buffer_.size()));
    if (std::uint64_t(file_.gcount()) != buffer_.size()) throw InputError(path_ + ": truncated");
    for (std::uint64_t s = 0; s < count; ++s) {
      const unsigned char* record = buffer_.data() + s * header_.record_bytes;
      double* v = records + s * c.size();
      for (int i = 0; i < c.size(); ++i) {
        v[i] = source_[i] < 0 ? 0 : ply::read_binary(record, header_.properties[source_[i]]);
        if (!std::isfinite(v[i]))
          throw InputError(where(path_, first + s, "property " + header_.properties[source_[i]].name) + " is " + runtime::format_number(v[i]));
      }
      const double* q = v + c.rotation();
      if (q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0) throw InputError(where(path_, first + s, "rot_0..3 are all zero"));
    }
  }

  void finish() override {
    if (file_.peek() != std::char_traits<char>::eof()) throw InputError(path_ + ": bytes after the last splat");
  }

 private:
  std::string path_;
  std::ifstream file_;
  ply::Header header_;
  Layout layout_;
  std::vector<int> source_;  // canonical field -> header property, -1: none (normals: 0)
  std::vector<unsigned char> buffer_;
};

// Float32 of a double, as the nearest finite float when it is beyond the range.
float clamped_float(double value, std::uint64_t& clamped) {
  constexpr double kMax = std::numeric_limits<float>::max();
  if (std::abs(value) > kMax) {
    ++clamped;
    return static_cast<float>(std::copysign(kMax, value));
  }
  return static_cast<float>(value);
}

// Little-endian float32, on a little-endian host as the .ply path (x86-64, AArch64).
void put_float(unsigned char* at, float value) { std::memcpy(at, &value, sizeof value); }

float get_float(const unsigned char* at) {
  float value;
  std::memcpy(&value, at, sizeof value);
  return value;
}

class PlyWriter : public SceneWriter {
 public:
  PlyWriter(io::PendingFile& out, int degree, std::uint64_t splats) : out_(out), size_(Canonical(degree).size()) {
    out_.write(canonical_header(degree, splats).text);
  }
  void write(std::uint64_t count, const double* records) override {
    buffer_.resize(count * size_ * sizeof(float));
    for (std::uint64_t i = 0; i < count * size_; ++i) put_float(&buffer_[i * sizeof(float)], clamped_float(records[i], clamped_));
    out_.write(reinterpret_cast<const char*>(buffer_.data()), buffer_.size());
  }
  int kept_degree(int degree) const override { return degree; }

 private:
  io::PendingFile& out_;
  int size_;
  std::vector<unsigned char> buffer_;
};

// ---- antimatter15's .splat: 32 bytes a splat, no SH above degree 0 ----
//   0: x, y, z           float32
//  12: scale_0..2        float32, exp of the log-scales
//  24: r, g, b, alpha    uint8: 255 (0.5 + Y00 f_dc), 255 sigmoid(opacity), rounded, clamped
//  28: rot_0..3 (w x y z) uint8: 128 q / |q| + 128, rounded, 255 at most
constexpr std::size_t kSplatBytes = 32;

class SplatFileReader : public SceneReader {
 public:
  explicit SplatFileReader(const std::string& path) : path_(path), file_(open_input(path)) {
    const std::uint64_t size = regular_file_size(path, ".splat has no header: its size gives the count");
    if (size % kSplatBytes != 0)
      throw InputError(path + ": " + std::to_string(size) + " bytes: not a whole number of 32-byte splats");
    splats_ = size / kSplatBytes;
    if (splats_ > runtime::kMaxPlyVertices)
      throw InputError(path + ": " + std::to_string(splats_) + " splats; at most " + std::to_string(runtime::kMaxPlyVertices));
    degree_ = 0;
  }

  void read(std::uint64_t first, std::uint64_t count, double* records) override {
    const Canonical c(0);
    buffer_.resize(count * kSplatBytes);
    file_.read(reinterpret_cast<char*>(buffer_.data()), std::streamsize(buffer_.size()));
    if (std::uint64_t(file_.gcount()) != buffer_.size()) throw InputError(path_ + ": truncated");
    static const char* const kFloatNames[] = {"x", "y", "z", "scale_0", "scale_1", "scale_2"};
    for (std::uint64_t s = 0; s < count; ++s) {
      const unsigned char* b = buffer_.data() + s * kSplatBytes;
      double* v = records + s * c.size();
      double f[6];
      for (int i = 0; i < 6; ++i) {
        f[i] = get_float(b + 4 * i);
        if (!std::isfinite(f[i])) throw InputError(where(path_, first + s, kFloatNames[i]) + " is " + runtime::format_number(f[i]));
        if (i >= 3 && !(f[i] > 0)) throw InputError(where(path_, first + s, kFloatNames[i]) + " is " + runtime::format_number(f[i]) + ", not above 0");
      }
      for (int i = 0; i < 3; ++i) {
        v[Canonical::kPosition + i] = f[i];
        v[Canonical::kNormal + i] = 0;
        v[c.scale() + i] = std::log(f[3 + i]);
        v[Canonical::kDc + i] = (b[24 + i] / 255.0 - 0.5) / runtime::kInvSqrt4Pi;
      }
      // Alpha 0 and 255 stand for a quarter step inside: a logit stays finite and writes back as
      // the same byte.
      const double alpha = std::clamp(b[27] / 255.0, 0.25 / 255, 254.75 / 255);
      v[c.opacity()] = std::log(alpha / (1 - alpha));
      // The quantised quaternion as it is (a writer normalises): reading a written file gives
      // back exactly what was written.
      for (int i = 0; i < 4; ++i) v[c.rotation() + i] = (b[28 + i] - 128.0) / 128;
      if (b[28] == 128 && b[29] == 128 && b[30] == 128 && b[31] == 128)
        throw InputError(where(path_, first + s, "rotation bytes all 128 (a zero quaternion)"));
    }
  }

  void finish() override {
    if (file_.peek() != std::char_traits<char>::eof()) throw InputError(path_ + ": bytes after the last splat (the file grew)");
  }

 private:
  std::string path_;
  std::ifstream file_;
  std::vector<unsigned char> buffer_;
};

// round(x) into 0..255, counting values outside.
unsigned char byte_of(double x, std::uint64_t& clamped) {
  const double r = std::nearbyint(x);
  if (r < 0 || r > 255) {
    ++clamped;
    return r < 0 ? 0 : 255;
  }
  return static_cast<unsigned char>(r);
}

class SplatFileWriter : public SceneWriter {
 public:
  SplatFileWriter(io::PendingFile& out, int degree) : out_(out), c_(degree) {}
  void write(std::uint64_t count, const double* records) override {
    buffer_.resize(count * kSplatBytes);
    for (std::uint64_t s = 0; s < count; ++s) {
      const double* v = records + s * c_.size();
      unsigned char* b = buffer_.data() + s * kSplatBytes;
      for (int i = 0; i < 3; ++i) {
        put_float(b + 4 * i, clamped_float(v[Canonical::kPosition + i], clamped_));
        float scale = clamped_float(std::exp(v[c_.scale() + i]), clamped_);
        if (scale == 0) {
          ++clamped_;
          scale = std::numeric_limits<float>::denorm_min();
        }
        put_float(b + 12 + 4 * i, scale);
        b[24 + i] = byte_of(255 * (0.5 + runtime::kInvSqrt4Pi * v[Canonical::kDc + i]), clamped_);
      }
      b[27] = byte_of(255 / (1 + std::exp(-v[c_.opacity()])), clamped_);
      const double* q = v + c_.rotation();
      const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
      for (int i = 0; i < 4; ++i) b[28 + i] = static_cast<unsigned char>(std::min(255.0, std::nearbyint(128 * q[i] / norm + 128)));
    }
    out_.write(reinterpret_cast<const char*>(buffer_.data()), buffer_.size());
  }
  int kept_degree(int) const override { return 0; }

 private:
  io::PendingFile& out_;
  Canonical c_;
  std::vector<unsigned char> buffer_;
};

}  // namespace

ply::Header canonical_header(int degree, std::uint64_t splats) {
  std::ostringstream text;
  text << "ply\nformat binary_little_endian 1.0\nelement vertex " << splats << "\n";
  for (const char* name : {"x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"}) text << "property float " << name << "\n";
  for (int i = 0; i < Canonical(degree).rest; ++i) text << "property float f_rest_" << i << "\n";
  for (const char* name : {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"})
    text << "property float " << name << "\n";
  text << "end_header\n";
  std::istringstream in(text.str());
  return ply::read_header(in, "canonical header");
}

std::unique_ptr<SceneReader> open_reader(FileFormat format, const std::string& path) {
  if (format == FileFormat::kSplat) return std::make_unique<SplatFileReader>(path);
  return std::make_unique<PlyReader>(path);
}

std::unique_ptr<SceneWriter> open_writer(FileFormat format, io::PendingFile& out, int degree, std::uint64_t splats) {
  if (format == FileFormat::kSplat) return std::make_unique<SplatFileWriter>(out, degree);
  return std::make_unique<PlyWriter>(out, degree, splats);
}

}  // namespace zhf::splat
