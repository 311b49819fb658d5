// PlayCanvas's compressed .ply (SuperSplat's default export), a binary PLY of three elements:
//   chunk  one per 256 splats: min_x min_y min_z max_x max_y max_z, min_scale_x..z, max_scale_x..z
//          and, in newer files, min_r min_g min_b max_r max_g max_b; float32
//   vertex one per splat: packed_position, packed_rotation, packed_scale, packed_color; uint32
//   sh     one per splat, when the scene has SH above degree 0: f_rest_0..K-1, uint8, K = 9, 24, 45
// Positions and log-scales: 11, 10 and 11 bits (x from the top bit down) of t in [0, 1] between
// the chunk's min and max, value = min (1 - t) + max t. Rotation: the top 2 bits name the largest
// of rot_0..3 (made positive, left out and recovered from the unit norm), the other three follow
// in order, 10 bits each of q / sqrt(2) + 1/2. Colour: bytes r, g, b from the top down, of
// 0.5 + Y00 f_dc between the chunk's colour min and max (0 and 1 without them), and the low byte
// alpha = sigmoid(opacity). SH: byte b stands for 8 ((b + 0.5) / 256 - 1/2); 0 and 255 for -4, 4.
// Written in Morton (Z-order) of the positions by default, as splat-transform writes it: the
// splats of a chunk lie close together, so its bounds, and the positions' steps, are small. The
// records wait in a private temporary file (float, the canonical record) until the order is known;
// memory holds 20 bytes a splat (position, index, key).
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <fstream>
#include <vector>

#include "format_io.h"
#include "scene_io.h"
#include "zhf/io/errors.h"
#include "zhf/io/private_dir.h"
#include "zhf/runtime/sh_eval.h"

namespace zhf::splat {
namespace {

namespace ply = io::ply;
using io::InputError;

constexpr std::uint64_t kChunk = 256;  // splats a chunk row describes
static_assert(kChunkSplats % kChunk == 0, "a block of splats holds whole chunks");
constexpr int kChunkFloats = 18;
constexpr std::array<const char*, kChunkFloats> kChunkNames = {
    "min_x",       "min_y",       "min_z",       "max_x", "max_y", "max_z", "min_scale_x", "min_scale_y", "min_scale_z",
    "max_scale_x", "max_scale_y", "max_scale_z", "min_r", "min_g", "min_b", "max_r",       "max_g",       "max_b"};
constexpr int kChunkWithoutColour = 12;
constexpr std::array<const char*, 4> kPackedNames = {"packed_position", "packed_rotation", "packed_scale", "packed_color"};
using runtime::kSqrt2;

double unorm(std::uint32_t value, int bits) {
  const std::uint32_t mask = (1u << bits) - 1;
  return double(value & mask) / mask;
}

// t in [0, 1] as `bits` bits, nearest.
std::uint32_t unorm_bits(double t, int bits) {
  const double mask = double((1u << bits) - 1);
  return static_cast<std::uint32_t>(std::clamp(std::nearbyint(t * mask), 0.0, mask));
}

double lerp(double low, double high, double t) { return low * (1 - t) + high * t; }

double sh_value(unsigned char b) { return b == 0 ? -4.0 : b == 255 ? 4.0 : 8 * ((b + 0.5) / 256 - 0.5); }

// The byte whose value is nearest v (beyond [-4, 4]: the end, counted).
unsigned char sh_byte(double v, std::uint64_t& clamped) {
  if (v < -4 || v > 4) ++clamped;
  const int guess = int(std::clamp(std::floor((v / 8 + 0.5) * 256), 0.0, 255.0));
  int best = guess;
  for (int b : {guess - 1, guess + 1})
    if (b >= 0 && b <= 255 && std::abs(sh_value(static_cast<unsigned char>(b)) - v) < std::abs(sh_value(static_cast<unsigned char>(best)) - v))
      best = b;
  return static_cast<unsigned char>(best);
}

class CompressedPlyReader : public SceneReader {
 public:
  explicit CompressedPlyReader(const std::string& path) : path_(path) {
    std::ifstream file = open_input(path);
    header_ = ply::read_header_elements(file, path);
    if (header_.format != ply::Format::kBinaryLittleEndian) throw InputError(path + ": a compressed .ply is binary little-endian");
    const ply::Element* chunk = element("chunk");
    const ply::Element* vertex = element("vertex");
    const ply::Element* sh = element("sh");
    if (!chunk || !vertex) throw InputError(path + ": a compressed .ply has the elements chunk and vertex");
    if (header_.elements.size() != (sh ? 3u : 2u)) throw InputError(path + ": an element other than chunk, vertex and sh");
    const std::size_t chunk_columns = chunk->properties.size();
    if (chunk_columns != kChunkFloats && chunk_columns != kChunkWithoutColour)
      throw InputError(path + ": element chunk has " + std::to_string(chunk_columns) + " properties, not 12 or 18");
    for (std::size_t i = 0; i < chunk_columns; ++i) {
      const int at = chunk->find(kChunkNames[i]);
      if (at < 0 || chunk->properties[at].type != ply::Type::kFloat32)
        throw InputError(path + ": element chunk has no float property " + kChunkNames[i]);
      chunk_index_[i] = at;
    }
    colours_ = chunk_columns == kChunkFloats;
    if (vertex->properties.size() != kPackedNames.size())
      throw InputError(path + ": element vertex has " + std::to_string(vertex->properties.size()) + " properties, not the 4 packed ones");
    for (std::size_t i = 0; i < kPackedNames.size(); ++i) {
      const int at = vertex->find(kPackedNames[i]);
      if (at < 0 || vertex->properties[at].type != ply::Type::kUint32)
        throw InputError(path + ": element vertex has no uint property " + kPackedNames[i]);
      packed_index_[i] = at;
    }
    splats_ = vertex->count;
    const std::uint64_t chunks = (splats_ + kChunk - 1) / kChunk;
    if (chunk->count != chunks)
      throw InputError(path + ": " + std::to_string(chunk->count) + " chunks for " + std::to_string(splats_) + " splats; expected " +
                       std::to_string(chunks));
    degree_ = 0;
    if (sh) {
      const std::size_t k = sh->properties.size();
      if (k != 9 && k != 24 && k != 45)
        throw InputError(path + ": element sh has " + std::to_string(k) + " properties; SH degree 1, 2, 3 has 9, 24, 45");
      for (std::size_t i = 0; i < k; ++i) {
        const int at = sh->find("f_rest_" + std::to_string(i));
        if (at < 0 || sh->properties[at].type != ply::Type::kUint8)
          throw InputError(path + ": element sh has no uchar property f_rest_" + std::to_string(i));
        sh_index_.push_back(at);
      }
      if (sh->count != splats_)
        throw InputError(path + ": " + std::to_string(sh->count) + " sh rows for " + std::to_string(splats_) + " splats");
      degree_ = k == 9 ? 1 : k == 24 ? 2 : 3;
    }
    // Every section's place, and the whole size, before anything is read.
    std::uint64_t offset = header_.text.size();
    for (const ply::Element& e : header_.elements) {
      std::ifstream& stream = e.name == "chunk" ? chunk_file_ : e.name == "vertex" ? vertex_file_ : sh_file_;
      stream = open_input(path);
      stream.seekg(std::streamoff(offset));
      offset += e.count * e.record_bytes;
    }
    const std::uint64_t size = regular_file_size(path, "a compressed .ply is checked against its size first");
    if (size != offset)
      throw InputError(path + ": " + std::to_string(size) + " bytes, but the header says " + std::to_string(offset) +
                       (size < offset ? ": truncated" : ": bytes after the last splat"));
    last_ = &header_.elements.back();
  }

  void read(std::uint64_t first, std::uint64_t count, double* records) override {
    const Canonical c(degree_);
    const ply::Element& chunk = *element("chunk");
    const ply::Element& vertex = *element("vertex");
    const std::uint64_t chunks = (count + kChunk - 1) / kChunk;
    fill(chunk_file_, chunk_bytes_, chunks * chunk.record_bytes);
    fill(vertex_file_, vertex_bytes_, count * vertex.record_bytes);
    if (degree_ > 0) fill(sh_file_, sh_bytes_, count * element("sh")->record_bytes);
    std::array<double, kChunkFloats> bounds{};
    for (std::uint64_t s = 0; s < count; ++s) {
      if (s % kChunk == 0) {
        const unsigned char* row = chunk_bytes_.data() + (s / kChunk) * chunk.record_bytes;
        for (int i = 0; i < (colours_ ? kChunkFloats : kChunkWithoutColour); ++i) {
          bounds[i] = ply::read_binary(row, chunk.properties[chunk_index_[i]]);
          if (!std::isfinite(bounds[i]))
            throw InputError(path_ + ": chunk " + std::to_string((first + s) / kChunk) + ": " + kChunkNames[i] + " is " +
                             runtime::format_number(bounds[i]));
        }
      }
      const unsigned char* packed = vertex_bytes_.data() + s * vertex.record_bytes;
      std::array<std::uint32_t, 4> word{};
      for (int i = 0; i < 4; ++i) word[i] = get_uint32(packed + vertex.properties[packed_index_[i]].offset);
      double* v = records + s * c.size();
      const std::array<int, 3> shifts = {21, 11, 0}, widths = {11, 10, 11};
      for (int i = 0; i < 3; ++i) {
        v[Canonical::kPosition + i] = lerp(bounds[i], bounds[3 + i], unorm(word[0] >> shifts[i], widths[i]));
        v[Canonical::kNormal + i] = 0;
        v[c.scale() + i] = lerp(bounds[6 + i], bounds[9 + i], unorm(word[2] >> shifts[i], widths[i]));
        const double t = unorm(word[3] >> (24 - 8 * i), 8);
        v[Canonical::kDc + i] = ((colours_ ? lerp(bounds[12 + i], bounds[15 + i], t) : t) - 0.5) / runtime::kInvSqrt4Pi;
      }
      v[c.opacity()] = opacity_of_alpha(unorm(word[3], 8));
      const int largest = int(word[1] >> 30);
      double* q = v + c.rotation();
      double norm = 0;
      for (int i = 0, j = 0; i < 4; ++i) {
        if (i == largest) continue;
        q[i] = (unorm(word[1] >> (20 - 10 * j), 10) - 0.5) * kSqrt2;
        norm += q[i] * q[i];
        ++j;
      }
      q[largest] = std::sqrt(std::max(0.0, 1 - norm));
      if (degree_ > 0) {
        const ply::Element& sh = *element("sh");
        const unsigned char* row = sh_bytes_.data() + s * sh.record_bytes;
        for (int i = 0; i < c.rest; ++i) v[Canonical::kRest + i] = sh_value(row[sh.properties[sh_index_[i]].offset]);
      }
    }
  }

  void finish() override {
    std::ifstream& last = last_->name == "chunk" ? chunk_file_ : last_->name == "vertex" ? vertex_file_ : sh_file_;
    if (last.peek() != std::char_traits<char>::eof()) throw InputError(path_ + ": bytes after the last splat (the file grew)");
  }

 private:
  const ply::Element* element(const std::string& name) const {
    for (const ply::Element& e : header_.elements)
      if (e.name == name) return &e;
    return nullptr;
  }
  void fill(std::ifstream& file, std::vector<unsigned char>& buffer, std::uint64_t bytes) {
    buffer.resize(bytes);
    file.read(reinterpret_cast<char*>(buffer.data()), std::streamsize(bytes));
    if (std::uint64_t(file.gcount()) != bytes) throw InputError(path_ + ": truncated");
  }

  std::string path_;
  ply::Header header_;
  const ply::Element* last_ = nullptr;
  std::ifstream chunk_file_, vertex_file_, sh_file_;
  std::array<int, kChunkFloats> chunk_index_{};
  std::array<int, 4> packed_index_{};
  std::vector<int> sh_index_;
  bool colours_ = false;
  std::vector<unsigned char> chunk_bytes_, vertex_bytes_, sh_bytes_;
};

// 10 bits of each coordinate interleaved, x lowest (Fabian Giesen's bit spreading).
std::uint32_t morton_code(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  auto spread = [](std::uint32_t v) {
    v &= 0x3ff;
    v = (v ^ (v << 16)) & 0xff0000ff;
    v = (v ^ (v << 8)) & 0x0300f00f;
    v = (v ^ (v << 4)) & 0x030c30c3;
    return (v ^ (v << 2)) & 0x09249249;
  };
  return (spread(z) << 2) | (spread(y) << 1) | spread(x);
}

// Sorts `order` (indices into positions, 3 floats each) by the Morton code of the positions in
// their bounding box, stably; a run of more than one chunk on one code is sorted again within its
// own box, as splat-transform does, so dense regions are ordered too.
void morton_sort(const std::vector<float>& positions, std::uint32_t* order, std::size_t n) {
  if (n < 2) return;
  std::array<float, 3> low{INFINITY, INFINITY, INFINITY}, high{-INFINITY, -INFINITY, -INFINITY};
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) {
      low[a] = std::min(low[a], positions[3 * order[i] + a]);
      high[a] = std::max(high[a], positions[3 * order[i] + a]);
    }
  std::array<double, 3> scale{};
  for (int a = 0; a < 3; ++a) scale[a] = high[a] > low[a] ? 1024.0 / (double(high[a]) - low[a]) : 0;
  if (scale[0] == 0 && scale[1] == 0 && scale[2] == 0) return;  // all at one point
  std::vector<std::pair<std::uint32_t, std::uint32_t>> keyed(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::array<std::uint32_t, 3> cell{};
    for (int a = 0; a < 3; ++a) cell[a] = std::uint32_t(std::min(1023.0, (double(positions[3 * order[i] + a]) - low[a]) * scale[a]));
    keyed[i] = {morton_code(cell[0], cell[1], cell[2]), order[i]};
  }
  std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t i = 0; i < n; ++i) order[i] = keyed[i].second;
  for (std::size_t start = 0, end = 0; start < n; start = end) {
    while (end < n && keyed[end].first == keyed[start].first) ++end;
    if (end - start > kChunk) morton_sort(positions, order + start, end - start);
  }
}

class CompressedPlyWriter : public SceneWriter {
 public:
  CompressedPlyWriter(io::PendingFile& out, int degree, std::uint64_t splats, bool morton)
      : out_(out), c_(degree), morton_(morton) {
    if (morton_) {
      records_.open(dir_.path() + "/records", std::ios::binary | std::ios::in | std::ios::out | std::ios::trunc);
      if (!records_) throw io::OutputError(dir_.path() + ": cannot write a temporary file");
      positions_.reserve(3 * splats);
    }
    const std::uint64_t chunks = (splats + kChunk - 1) / kChunk;
    std::ostringstream h;
    h << "ply\nformat binary_little_endian 1.0\ncomment written by zhf splat\nelement chunk " << chunks << "\n";
    for (const char* name : kChunkNames) h << "property float " << name << "\n";
    h << "element vertex " << splats << "\n";
    for (const char* name : kPackedNames) h << "property uint " << name << "\n";
    if (c_.rest > 0) {
      h << "element sh " << splats << "\n";
      for (int i = 0; i < c_.rest; ++i) h << "property uchar f_rest_" << i << "\n";
    }
    h << "end_header\n";
    out_.write(h.str());
    chunk_at_ = h.str().size();
    vertex_at_ = chunk_at_ + chunks * kChunkFloats * 4;
    sh_at_ = vertex_at_ + splats * 16;
  }

  void write(std::uint64_t count, const double* records) override {
    if (!morton_) return pack_block(count, records);
    std::vector<float> floats(count * c_.size());
    for (std::uint64_t s = 0; s < count; ++s)
      for (int i = 0; i < c_.size(); ++i) {
        floats[s * c_.size() + i] = clamped_float(records[s * c_.size() + i], clamped_);
        if (i < 3) positions_.push_back(floats[s * c_.size() + i]);
      }
    records_.write(reinterpret_cast<const char*>(floats.data()), std::streamsize(floats.size() * sizeof(float)));
    if (!records_) throw io::OutputError(dir_.path() + ": cannot write a temporary file");
  }

  // The waiting records in Morton order, a block of whole chunks at a time.
  void finish() override {
    if (!morton_) return;
    const std::size_t n = positions_.size() / 3;
    std::vector<std::uint32_t> order(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = std::uint32_t(i);
    morton_sort(positions_, order.data(), n);
    std::vector<float> record(c_.size());
    std::vector<double> block;
    for (std::size_t first = 0; first < n; first += kChunkSplats) {
      const std::size_t count = std::min<std::size_t>(kChunkSplats, n - first);
      block.resize(count * c_.size());
      for (std::size_t s = 0; s < count; ++s) {
        records_.seekg(std::streamoff(std::uint64_t(order[first + s]) * c_.size() * sizeof(float)));
        records_.read(reinterpret_cast<char*>(record.data()), std::streamsize(record.size() * sizeof(float)));
        if (!records_) throw io::OutputError(dir_.path() + ": cannot read a temporary file");
        std::copy(record.begin(), record.end(), block.begin() + s * c_.size());
      }
      pack_block(count, block.data());
    }
  }

 private:
  void pack_block(std::uint64_t count, const double* records) {
    const std::uint64_t chunks = (count + kChunk - 1) / kChunk;
    chunk_bytes_.assign(chunks * kChunkFloats * 4, 0);
    vertex_bytes_.assign(count * 16, 0);
    sh_bytes_.assign(count * c_.rest, 0);
    for (std::uint64_t k = 0; k < chunks; ++k) {
      const std::uint64_t begin = k * kChunk, end = std::min(count, begin + kChunk);
      // The chunk's bounds as the reader sees them, in float: position, log-scale, colour.
      std::array<float, kChunkFloats> bounds{};
      for (int group = 0; group < 3; ++group)
        for (int i = 0; i < 3; ++i) {
          double low = INFINITY, high = -INFINITY;
          for (std::uint64_t s = begin; s < end; ++s) {
            const double x = field(records + s * c_.size(), group, i);
            low = std::min(low, x);
            high = std::max(high, x);
          }
          bounds[6 * group + i] = clamped_float(low, clamped_);
          bounds[6 * group + 3 + i] = clamped_float(high, clamped_);
        }
      for (int i = 0; i < kChunkFloats; ++i) put_float(&chunk_bytes_[(k * kChunkFloats + i) * 4], bounds[i]);
      for (std::uint64_t s = begin; s < end; ++s) pack(records + s * c_.size(), bounds, vertex_bytes_.data() + s * 16, sh_bytes_.data() + s * c_.rest);
    }
    out_.write_at(chunk_at_, reinterpret_cast<const char*>(chunk_bytes_.data()), chunk_bytes_.size());
    out_.write_at(vertex_at_, reinterpret_cast<const char*>(vertex_bytes_.data()), vertex_bytes_.size());
    out_.write_at(sh_at_, reinterpret_cast<const char*>(sh_bytes_.data()), sh_bytes_.size());
    chunk_at_ += chunk_bytes_.size();
    vertex_at_ += vertex_bytes_.size();
    sh_at_ += sh_bytes_.size();
  }

  // Group 0: position, 1: log-scale, 2: colour 0.5 + Y00 f_dc.
  double field(const double* v, int group, int i) const {
    return group == 0 ? v[Canonical::kPosition + i] : group == 1 ? v[c_.scale() + i] : 0.5 + runtime::kInvSqrt4Pi * v[Canonical::kDc + i];
  }

  void pack(const double* v, const std::array<float, kChunkFloats>& bounds, unsigned char* packed, unsigned char* sh) {
    const std::array<int, 3> shifts = {21, 11, 0}, widths = {11, 10, 11};
    std::array<std::uint32_t, 4> word{};
    auto t = [&](int group, int i) {
      const double low = bounds[6 * group + i], high = bounds[6 * group + 3 + i];
      return high > low ? (field(v, group, i) - low) / (high - low) : 0.0;
    };
    for (int i = 0; i < 3; ++i) {
      word[0] |= unorm_bits(t(0, i), widths[i]) << shifts[i];
      word[2] |= unorm_bits(t(1, i), widths[i]) << shifts[i];
      word[3] |= unorm_bits(t(2, i), 8) << (24 - 8 * i);
    }
    word[3] |= unorm_bits(sigmoid(v[c_.opacity()]), 8);
    const double* q = v + c_.rotation();
    int largest = 0;
    for (int i = 1; i < 4; ++i)
      if (std::abs(q[i]) > std::abs(q[largest])) largest = i;
    const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    const double sign = q[largest] < 0 ? -1 : 1;
    word[1] = std::uint32_t(largest) << 30;
    for (int i = 0, j = 0; i < 4; ++i) {
      if (i == largest) continue;
      word[1] |= unorm_bits(sign * q[i] / norm / kSqrt2 + 0.5, 10) << (20 - 10 * j);
      ++j;
    }
    for (int i = 0; i < 4; ++i) put_uint32(packed + 4 * i, word[i]);
    for (int i = 0; i < 3; ++i) {
      const double colour = lerp(bounds[12 + i], bounds[15 + i], unorm(word[3] >> (24 - 8 * i), 8));
      stored(0, v[Canonical::kDc + i], (colour - 0.5) / runtime::kInvSqrt4Pi);
    }
    for (int i = 0; i < c_.rest; ++i) {
      sh[i] = sh_byte(v[Canonical::kRest + i], clamped_);
      stored(Canonical::band(i % (c_.rest / 3)), v[Canonical::kRest + i], sh_value(sh[i]));
    }
  }

  io::PendingFile& out_;
  Canonical c_;
  bool morton_;
  io::PrivateDir dir_{"zhf-compressed-ply"};
  std::fstream records_;         // Morton order: the records as written, float
  std::vector<float> positions_;  // Morton order: x y z of each
  std::uint64_t chunk_at_ = 0, vertex_at_ = 0, sh_at_ = 0;
  std::vector<unsigned char> chunk_bytes_, vertex_bytes_, sh_bytes_;
};

}  // namespace

std::unique_ptr<SceneReader> open_compressed_ply_reader(const std::string& path, const Formats&) {
  return std::make_unique<CompressedPlyReader>(path);
}
std::unique_ptr<SceneWriter> open_compressed_ply_writer(io::PendingFile& out, const WriteOptions& options) {
  return std::make_unique<CompressedPlyWriter>(out, options.degree, options.splats, !options.keep_order);
}

}  // namespace zhf::splat
