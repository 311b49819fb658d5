#include <algorithm>
#include <cmath>
#include <vector>

#include "format_io.h"
#include "scene_io.h"
#include "zhf/io/errors.h"
#include "zhf/io/limits.h"
#include "zhf/runtime/sh_eval.h"

namespace zhf::splat {
namespace {

using io::InputError;

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
    if (splats_ > io::kMaxPlyVertices)
      throw InputError(path + ": " + std::to_string(splats_) + " splats; at most " + std::to_string(io::kMaxPlyVertices));
    degree_ = 0;
  }

  void read(std::uint64_t first, std::uint64_t count, double* records) override {
    const Canonical c(0);
    buffer_.resize(count * kSplatBytes);
    file_.read(reinterpret_cast<char*>(buffer_.data()), std::streamsize(buffer_.size()));
    if (std::uint64_t(file_.gcount()) != buffer_.size()) throw InputError(path_ + ": truncated");
    static const char* const kFloatNames[] = {"x", "y", "z", "scale_0", "scale_1", "scale_2"};
    constexpr int kFirstScale = 3;  // the scales, which must be above 0
    for (std::uint64_t s = 0; s < count; ++s) {
      const unsigned char* b = buffer_.data() + s * kSplatBytes;
      double* v = records + s * c.size();
      double f[6];
      for (int i = 0; i < 6; ++i) {
        f[i] = get_float(b + 4 * i);
        if (!std::isfinite(f[i])) {
          if (keep_nonfinite_) continue;
          throw InputError(where(path_, first + s, kFloatNames[i]) + " is " + runtime::format_number(f[i]));
        }
        if (i >= kFirstScale && !(f[i] > 0)) throw InputError(where(path_, first + s, kFloatNames[i]) + " is " + runtime::format_number(f[i]) + ", not above 0");
      }
      for (int i = 0; i < 3; ++i) {
        v[Canonical::kPosition + i] = f[i];
        v[Canonical::kNormal + i] = 0;
        v[c.scale() + i] = std::log(f[3 + i]);
        v[Canonical::kDc + i] = (b[24 + i] / 255.0 - 0.5) / runtime::kInvSqrt4Pi;
      }
      v[c.opacity()] = opacity_of_alpha(b[27] / 255.0);
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
        b[24 + i] = static_cast<unsigned char>(clamped_round(255 * (0.5 + runtime::kInvSqrt4Pi * v[Canonical::kDc + i]), 255, clamped_));
        stored(0, v[Canonical::kDc + i], (b[24 + i] / 255.0 - 0.5) / runtime::kInvSqrt4Pi);
      }
      b[27] = static_cast<unsigned char>(clamped_round(255 * sigmoid(v[c_.opacity()]), 255, clamped_));
      const double* q = v + c_.rotation();
      const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
      for (int i = 0; i < 4; ++i) b[28 + i] = static_cast<unsigned char>(std::min(255.0, std::nearbyint(128 * q[i] / norm + 128)));
    }
    out_.write(reinterpret_cast<const char*>(buffer_.data()), buffer_.size());
  }

 private:
  io::PendingFile& out_;
  Canonical c_;
  std::vector<unsigned char> buffer_;
};

}  // namespace

std::unique_ptr<SceneReader> open_splat_reader(const std::string& path, const Formats&) { return std::make_unique<SplatFileReader>(path); }
std::unique_ptr<SceneWriter> open_splat_writer(io::PendingFile& out, const WriteOptions& options) {
  return std::make_unique<SplatFileWriter>(out, options.degree);
}

}  // namespace zhf::splat
