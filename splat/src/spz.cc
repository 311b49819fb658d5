// Niantic's .spz, versions 2, 3 and 4 read, 3 and 4 written. Versions 2 and 3 are one gzip stream
// of a 16-byte header
//   magic 0x5053474e ("NGSP"), version, splat count (uint32); SH degree, fractional bits, flags,
//   reserved (uint8)
// and the attributes one after another; version 4 is a plain 32-byte header (the same fields, then
// the stream count (uint8), the table's offset (uint32) and 12 zero bytes; extension records may
// sit between it and the table), a table of (compressed, decompressed) uint64 sizes, and each
// attribute as its own zstd frame. The attributes, each for every splat in turn: positions (x, y, z as 24-bit signed fixed
// point with that many fractional bits), alphas (255 sigmoid(opacity)), colours (255 (0.5 + 0.15
// f_dc)), log-scales (16 (s + 10)), rotations and SH (128 + 128 v, coefficient by coefficient,
// the channel inner). Rotations, quaternion order x y z w: version 3 the smallest three in 32
// bits (the largest component's index in the top 2, then the other three in order, 10 bits each:
// a sign and 9 bits of |q| / sqrt(1/2)); version 2 x, y, z as 127.5 (q + 1) with w >= 0 rebuilt.
// A stream whose attribute is empty (SH at degree 0) is left out, as the reference library does.
// Header flags: 1 antialiased, 2 extension records, which sit between the header and the table in
// version 4 and after the attributes in the gzip stream of version 3 (type, byte length, payload).
// The records are read here with their values as stored; the file's axes (a coordinate-system
// record, else --spz-axes) go to the transform as a change of axes (scene_io.h: axes()).
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <vector>

#include <zlib.h>
#include <zstd.h>

#include "format_io.h"
#include "scene_io.h"
#include "spz_records.h"
#include "zhf/io/errors.h"
#include "zhf/io/limits.h"
#include "zhf/io/private_dir.h"
#include "zhf/splat/limits.h"

namespace zhf::splat {
namespace {

using io::InputError;

constexpr std::uint32_t kMagic = 0x5053474e;
constexpr std::size_t kHeaderBytes = 16, kZstdHeaderBytes = 32;
constexpr int kZstdLevel = 12;  // the reference library's
constexpr int kAttributes = 6;
constexpr unsigned char kFlagAntialiased = 1, kFlagExtensions = 2;
constexpr int kFractionalBits = 12;  // written: positions to +-2048 in steps of 1/4096
constexpr double kColourScale = 0.15;
const double kSqrtHalf = std::sqrt(0.5);
constexpr int kBand4M4 = 23;  // band 4's m = 4 among the coefficients above band 0

int coefficients(int degree) { return (degree + 1) * (degree + 1) - 1; }

// Bytes per splat of each attribute, in file order.
std::array<std::uint64_t, kAttributes> attribute_bytes(int version, int degree) {
  return {9, 1, 3, 3, std::uint64_t(version >= 3 ? 4 : 3), std::uint64_t(3 * coefficients(degree))};
}

// A zlib stream, ended however its owner's work ends.
struct Inflater {
  z_stream z{};
  explicit Inflater(const std::string& path) {
    if (inflateInit2(&z, 16 + MAX_WBITS) != Z_OK) throw InputError(path + ": gzip: cannot start inflating");
  }
  ~Inflater() { inflateEnd(&z); }
  Inflater(const Inflater&) = delete;
  Inflater& operator=(const Inflater&) = delete;
};

struct Deflater {
  z_stream z{};
  Deflater() {
    if (deflateInit2(&z, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 16 + MAX_WBITS, 9, Z_DEFAULT_STRATEGY) != Z_OK)
      throw io::OutputError("gzip: cannot start deflating");
  }
  ~Deflater() { deflateEnd(&z); }
  Deflater(const Deflater&) = delete;
  Deflater& operator=(const Deflater&) = delete;
};

// One attribute's decompressed bytes, read in order.
class AttributeStream {
 public:
  virtual ~AttributeStream() = default;
  virtual void read(unsigned char* out, std::size_t size) = 0;
  // After the last splat: the stream must end here, and the file (or its part) with it.
  virtual void expect_end() = 0;
};

// The decompressed stream from some offset on: each attribute is read by its own inflater, so
// memory stays bounded whatever the count (the earlier bytes are inflated and dropped).
class GzipReader : public AttributeStream {
 public:
  GzipReader(const std::string& path, std::uint64_t skip) : path_(path), file_(open_input(path)), inflater_(path) {
    std::vector<unsigned char> scratch(1 << 16);
    while (skip > 0) {
      const std::size_t n = std::size_t(std::min<std::uint64_t>(skip, scratch.size()));
      read(scratch.data(), n);
      skip -= n;
    }
  }
  void read(unsigned char* out, std::size_t size) override {
    z_.next_out = out;
    z_.avail_out = static_cast<uInt>(size);
    while (z_.avail_out > 0) {
      if (ended_) throw InputError(path_ + ": the decompressed data ends before the last splat");
      refill();
      const int result = inflate(&z_, Z_NO_FLUSH);
      if (result == Z_STREAM_END) ended_ = true;
      else if (result != Z_OK) throw InputError(path_ + ": gzip: " + (z_.msg ? runtime::excerpt(z_.msg) : "corrupt data"));
    }
  }

  // What is left of the decompressed stream, at most max_bytes (InputError beyond).
  std::string read_rest(std::size_t max_bytes, const char* what) {
    std::string rest;
    std::array<unsigned char, 1 << 12> block;
    while (!ended_) {
      z_.next_out = block.data();
      z_.avail_out = static_cast<uInt>(block.size());
      refill();
      const int result = inflate(&z_, Z_NO_FLUSH);
      if (result == Z_STREAM_END) ended_ = true;
      else if (result != Z_OK) throw InputError(path_ + ": gzip: " + (z_.msg ? runtime::excerpt(z_.msg) : "corrupt data"));
      rest.append(reinterpret_cast<const char*>(block.data()), block.size() - z_.avail_out);
      if (rest.size() > max_bytes) throw InputError(path_ + ": more than " + std::to_string(max_bytes) + " bytes of " + what);
    }
    return rest;
  }

  void expect_end() override {
    unsigned char extra;
    z_.next_out = &extra;
    z_.avail_out = 1;
    while (!ended_) {
      refill();
      const int result = inflate(&z_, Z_NO_FLUSH);
      if (z_.avail_out == 0) throw InputError(path_ + ": decompressed bytes after the last splat");
      if (result == Z_STREAM_END) ended_ = true;
      else if (result != Z_OK) throw InputError(path_ + ": gzip: " + (z_.msg ? runtime::excerpt(z_.msg) : "corrupt data"));
    }
    if (z_.avail_in > 0 || file_.peek() != std::char_traits<char>::eof()) throw InputError(path_ + ": bytes after the gzip stream");
  }

 private:
  void refill() {
    if (z_.avail_in > 0) return;
    file_.read(reinterpret_cast<char*>(in_.data()), std::streamsize(in_.size()));
    if (file_.gcount() == 0) throw InputError(path_ + ": truncated: the gzip stream ends early");
    z_.next_in = in_.data();
    z_.avail_in = static_cast<uInt>(file_.gcount());
  }

  std::string path_;
  std::ifstream file_;
  Inflater inflater_;
  z_stream& z_ = inflater_.z;
  std::array<unsigned char, 1 << 16> in_{};
  bool ended_ = false;
};

// Version 4: one zstd frame, `size` bytes at `offset` of the file.
class ZstdReader : public AttributeStream {
 public:
  ZstdReader(const std::string& path, std::uint64_t offset, std::uint64_t size) : path_(path), file_(open_input(path)), left_(size) {
    if (!stream_) throw InputError(path + ": zstd: cannot start decompressing");
    file_.seekg(std::streamoff(offset));
  }
  ~ZstdReader() override { ZSTD_freeDStream(stream_); }
  ZstdReader(const ZstdReader&) = delete;
  ZstdReader& operator=(const ZstdReader&) = delete;

  void read(unsigned char* out, std::size_t size) override {
    ZSTD_outBuffer output{out, size, 0};
    while (output.pos < output.size) {
      if (ended_) throw InputError(path_ + ": a zstd stream ends before the last splat");
      refill();
      step(output);
    }
  }

  void expect_end() override {
    unsigned char extra;
    ZSTD_outBuffer output{&extra, 1, 0};
    while (!ended_) {
      refill();
      step(output);
      if (output.pos > 0) throw InputError(path_ + ": decompressed bytes after the last splat");
    }
    if (input_.pos < input_.size || left_ > 0) throw InputError(path_ + ": bytes after a zstd frame");
  }

 private:
  void refill() {
    if (input_.pos < input_.size) return;
    if (left_ == 0) throw InputError(path_ + ": truncated: a zstd stream ends early");
    file_.read(reinterpret_cast<char*>(in_.data()), std::streamsize(std::min<std::uint64_t>(left_, in_.size())));
    if (file_.gcount() == 0) throw InputError(path_ + ": truncated");
    left_ -= std::uint64_t(file_.gcount());
    input_ = {in_.data(), std::size_t(file_.gcount()), 0};
  }
  void step(ZSTD_outBuffer& output) {
    const std::size_t result = ZSTD_decompressStream(stream_, &output, &input_);
    if (ZSTD_isError(result)) throw InputError(path_ + ": zstd: " + runtime::excerpt(ZSTD_getErrorName(result)));
    if (result == 0) ended_ = true;
  }

  std::string path_;
  std::ifstream file_;
  std::uint64_t left_;
  ZSTD_DStream* stream_ = ZSTD_createDStream();
  ZSTD_inBuffer input_{nullptr, 0, 0};
  std::array<unsigned char, 1 << 16> in_{};
  bool ended_ = false;
};

class SpzReader : public SceneReader {
 public:
  SpzReader(const std::string& path, SpzAxes default_axes, bool as_reference) : path_(path) {
    const std::uint64_t size = regular_file_size(path, ".spz is checked against its size first");
    std::ifstream file = open_input(path);
    unsigned char h[kZstdHeaderBytes] = {};
    file.read(reinterpret_cast<char*>(h), kZstdHeaderBytes);
    const std::size_t got = std::size_t(file.gcount());
    const bool zstd = got >= 4 && get_uint32(h) == kMagic;
    if (!zstd) {
      if (got < 2 || h[0] != 0x1f || h[1] != 0x8b) throw InputError(path + ": not a .spz file (neither NGSP nor a gzip stream)");
      GzipReader header_stream(path, 0);
      header_stream.read(h, kHeaderBytes);
      if (get_uint32(h) != kMagic) throw InputError(path + ": not a .spz file (the magic is not NGSP)");
    } else if (got < kZstdHeaderBytes) {
      throw InputError(path + ": truncated: a version 4 header is 32 bytes");
    }
    version_ = get_uint32(h + 4);
    if (zstd ? version_ != 4 : version_ != 2 && version_ != 3)
      throw InputError(path + ": .spz version " + std::to_string(version_) + (zstd ? " in a plain header; expected 4" : "; zhf reads versions 2, 3 and 4"));
    splats_ = get_uint32(h + 8);
    if (splats_ > io::kMaxPlyVertices)
      throw InputError(path + ": " + std::to_string(splats_) + " splats; at most " + std::to_string(io::kMaxPlyVertices));
    degree_ = h[12];
    if (degree_ > kMaxSplatShDegree)
      throw InputError(path + ": SH degree " + std::to_string(degree_) + "; .spz holds degrees 0.." + std::to_string(kMaxSplatShDegree));
    fractional_bits_ = h[13];
    if (fractional_bits_ > kMaxSpzFractionalBits)
      throw InputError(path + ": " + std::to_string(fractional_bits_) + " fractional bits; at most " + std::to_string(kMaxSpzFractionalBits));
    const unsigned flags = h[14];
    if (flags & ~unsigned(kFlagAntialiased | kFlagExtensions))
      throw InputError(path + ": header flags " + hex32(flags) + ": zhf knows 0x1 (antialiased) and 0x2 (extension records)");
    antialiased_ = flags & kFlagAntialiased;
    const std::array<std::uint64_t, kAttributes> bytes = attribute_bytes(version_, degree_);
    std::uint64_t claimed = 0;
    for (std::uint64_t b : bytes) claimed += b * splats_;
    if (double(claimed) > splat::kMaxCompressionRatio * double(size))
      throw InputError(path + ": the header claims " + std::to_string(splats_) + " splats (" + std::to_string(claimed) +
                       " bytes), more than " + std::to_string(size) + " compressed bytes can hold");
    if (!zstd) {
      if (h[15] != 0) throw InputError(path + ": the header's reserved byte is not 0");
      std::uint64_t offset = kHeaderBytes;
      for (std::size_t a = 0; a < bytes.size(); ++a) {
        attributes_[a] = std::make_unique<GzipReader>(path, offset);
        offset += bytes[a] * splats_;
      }
      // Version 3 keeps its records after the attributes, to the end of the stream.
      if (flags & kFlagExtensions) {
        const std::string records = GzipReader(path, offset).read_rest(kMaxSpzExtensionBytes, "extension records");
        gzip_record_bytes_ = records.size();
        take_records(parse_spz_records(records, path), default_axes, as_reference);
      } else {
        take_records({}, default_axes, as_reference);
      }
      return;
    }
    for (std::size_t i = 20; i < kZstdHeaderBytes; ++i)
      if (h[i] != 0) throw InputError(path + ": the header's reserved bytes are not 0");
    const int streams = h[15];
    const std::uint32_t table = get_uint32(h + 16);
    // The reference library writes a stream per non-empty attribute; zhf's earlier files wrote all six.
    int present = 0;
    for (std::uint64_t b : bytes) present += b * splats_ > 0;
    const bool every_attribute = streams == kAttributes;
    if (streams != present && !every_attribute)
      throw InputError(path + ": " + std::to_string(streams) + " streams; " + std::to_string(splats_) + " splats of SH degree " +
                       std::to_string(degree_) + " have " + std::to_string(present));
    if (table < kZstdHeaderBytes || table > size || size - table < std::uint64_t(16 * streams))
      throw InputError(path + ": the table of streams at byte " + std::to_string(table) + " is not inside the file");
    if (table > kZstdHeaderBytes && !(flags & kFlagExtensions))
      throw InputError(path + ": " + std::to_string(table - kZstdHeaderBytes) + " bytes between the header and the table, and no extension flag");
    std::string records(table - kZstdHeaderBytes, '\0');
    if (records.size() > kMaxSpzExtensionBytes)
      throw InputError(path + ": " + std::to_string(records.size()) + " bytes of extension records; at most " + std::to_string(kMaxSpzExtensionBytes));
    file.clear();
    file.seekg(kZstdHeaderBytes);
    file.read(records.data(), std::streamsize(records.size()));
    take_records(parse_spz_records(records, path), default_axes, as_reference);
    std::uint64_t offset = table + 16 * std::uint64_t(streams);
    int stream = 0;
    for (int a = 0; a < kAttributes; ++a) {
      const std::uint64_t expected = bytes[a] * splats_;
      if (expected == 0 && !every_attribute) continue;
      unsigned char entry[16];
      file.read(reinterpret_cast<char*>(entry), 16);
      std::uint64_t compressed, decompressed;
      std::memcpy(&compressed, entry, 8);
      std::memcpy(&decompressed, entry + 8, 8);
      if (decompressed != expected)
        throw InputError(path + ": stream " + std::to_string(stream) + " holds " + std::to_string(decompressed) + " bytes; " +
                         std::to_string(splats_) + " splats need " + std::to_string(expected));
      if (compressed > size - offset) throw InputError(path + ": stream " + std::to_string(stream) + " runs past the end of the file");
      attributes_[a] = std::make_unique<ZstdReader>(path, offset, compressed);
      offset += compressed;
      ++stream;
    }
    if (offset != size) throw InputError(path + ": " + std::to_string(size - offset) + " bytes after the last stream");
  }

  void read(std::uint64_t, std::uint64_t count, double* records) override {
    const Canonical c(degree_);
    const std::array<std::uint64_t, kAttributes> bytes = attribute_bytes(version_, degree_);
    for (std::size_t a = 0; a < bytes.size(); ++a) {
      buffers_[a].resize(count * bytes[a]);
      if (!buffers_[a].empty()) attributes_[a]->read(buffers_[a].data(), buffers_[a].size());
    }
    const double position_scale = 1.0 / double(1 << fractional_bits_);
    const int dim = coefficients(degree_);
    for (std::uint64_t s = 0; s < count; ++s) {
      double* v = records + s * c.size();
      const unsigned char* p = buffers_[0].data() + 9 * s;
      const unsigned char* rgb = buffers_[2].data() + 3 * s;
      const unsigned char* scale = buffers_[3].data() + 3 * s;
      for (int i = 0; i < 3; ++i) {
        std::int32_t fixed = p[3 * i] | (p[3 * i + 1] << 8) | (p[3 * i + 2] << 16);
        if (fixed & 0x800000) fixed -= 0x1000000;
        v[Canonical::kPosition + i] = fixed * position_scale;
        v[Canonical::kNormal + i] = 0;
        v[Canonical::kDc + i] = (rgb[i] / 255.0 - 0.5) / kColourScale;
        v[c.scale() + i] = scale[i] / 16.0 - 10;
      }
      v[c.opacity()] = opacity_of_alpha(buffers_[1][s] / 255.0);
      double xyzw[4];
      if (version_ >= 3) {
        std::uint32_t word = get_uint32(buffers_[4].data() + 4 * s);
        const int largest = int(word >> 30);
        double squares = 0;
        for (int i = 3; i >= 0; --i) {
          if (i == largest) continue;
          const double magnitude = kSqrtHalf * double(word & 511u) / 511;
          xyzw[i] = (word >> 9) & 1u ? -magnitude : magnitude;
          squares += xyzw[i] * xyzw[i];
          word >>= 10;
        }
        xyzw[largest] = std::sqrt(std::max(0.0, 1 - squares));
      } else {
        const unsigned char* r = buffers_[4].data() + 3 * s;
        double squares = 0;
        for (int i = 0; i < 3; ++i) {
          xyzw[i] = r[i] / 127.5 - 1;
          squares += xyzw[i] * xyzw[i];
        }
        xyzw[3] = std::sqrt(std::max(0.0, 1 - squares));
      }
      double* q = v + c.rotation();  // w x y z
      q[0] = xyzw[3];
      for (int i = 0; i < 3; ++i) q[1 + i] = xyzw[i];
      const unsigned char* sh = buffers_[5].data() + 3 * dim * s;  // empty at degree 0
      for (int k = 0; k < dim; ++k)
        for (int ch = 0; ch < 3; ++ch) v[Canonical::kRest + ch * dim + k] = (sh[3 * k + ch] - 128.0) / 128;
      if (negate_band4_m4_)
        for (int ch = 0; ch < 3; ++ch) v[Canonical::kRest + ch * dim + kBand4M4] = -v[Canonical::kRest + ch * dim + kBand4M4];
    }
  }

  void finish() override {
    // Version 4: every stream its own frame; versions 2 and 3: one stream, ending after the last
    // attribute and the extension records.
    if (version_ == 4) {
      for (const auto& stream : attributes_)
        if (stream) stream->expect_end();
      return;
    }
    std::vector<unsigned char> records(gzip_record_bytes_);
    if (!records.empty()) attributes_.back()->read(records.data(), records.size());
    attributes_.back()->expect_end();
  }

 private:
  // The coordinate-system record sets the axes; the others are carried.
  void take_records(std::vector<SpzExtension> records, SpzAxes default_axes, bool as_reference) {
    SpzFileAxes file = spz_read_axes(records, default_axes, as_reference, path_);
    axes_ = file.axes;
    axes_source_ = std::move(file.source);
    negate_band4_m4_ = file.negate_band4_m4 && degree_ == 4;
    extensions_ = std::move(records);
  }

  std::string path_;
  std::uint32_t version_ = 3;
  int fractional_bits_ = 0;
  bool negate_band4_m4_ = false;          // spz_records.h: SpzFileAxes
  std::uint64_t gzip_record_bytes_ = 0;  // version 3's extension records after the attributes
  std::array<std::unique_ptr<AttributeStream>, kAttributes> attributes_;  // none for an empty attribute's left-out stream
  std::array<std::vector<unsigned char>, kAttributes> buffers_;
};

// SH byte with `bits` kept: 128 + 128 v rounded, then to the nearest multiple of 2^(8 - bits)
// (the reference library's default: 5 bits for band 1, 4 above, which compress better).
unsigned char sh_byte(double v, int bits, std::uint64_t& clamped) {
  const double q = std::nearbyint(128 * v) + 128;
  if (q < 0 || q > 255) ++clamped;
  const int bucket = 1 << (8 - bits);
  const int rounded = (int(std::clamp(q, 0.0, 255.0)) + bucket / 2) / bucket * bucket;
  return static_cast<unsigned char>(std::min(rounded, 255));
}

class SpzWriter : public SceneWriter {
 public:
  SpzWriter(io::PendingFile& out, const WriteOptions& o)
      : out_(out), c_(o.degree), degree_(o.degree), version_(o.spz_version), splats_(o.splats), antialiased_(o.antialiased),
        records_(spz_record_bytes(o.spz_extensions)) {
    const SpzFileAxes file = spz_write_axes(o.spz_axes, o.spz_as_reference);
    axes_ = file.axes;
    negate_band4_m4_ = file.negate_band4_m4 && degree_ == 4;
    if (records_.size() > kMaxSpzExtensionBytes) throw io::OutputError("extension records: more than " + std::to_string(kMaxSpzExtensionBytes) + " bytes");
    for (std::size_t a = 0; a < files_.size(); ++a) {
      files_[a].open(dir_.path() + "/" + std::to_string(a), std::ios::binary);
      if (!files_[a]) throw io::OutputError(dir_.path() + ": cannot write a temporary file");
    }
  }

  void write(std::uint64_t count, const double* records) override {
    const int dim = coefficients(degree_);
    std::array<std::vector<unsigned char>, kAttributes> bytes;
    for (std::uint64_t s = 0; s < count; ++s) {
      const double* v = records + s * c_.size();
      for (int i = 0; i < 3; ++i) {
        const double x = v[Canonical::kPosition + i] * double(1 << kFractionalBits);
        const std::uint32_t fixed = std::uint32_t(std::int32_t(clamped_round(x + 0x7fffff, 0xfffffe, clamped_)) - 0x7fffff);
        for (int b = 0; b < 3; ++b) bytes[0].push_back(static_cast<unsigned char>(fixed >> (8 * b)));
      }
      bytes[1].push_back(static_cast<unsigned char>(clamped_round(255 * sigmoid(v[c_.opacity()]), 255, clamped_)));
      for (int i = 0; i < 3; ++i) {
        bytes[2].push_back(static_cast<unsigned char>(clamped_round(255 * (0.5 + kColourScale * v[Canonical::kDc + i]), 255, clamped_)));
        stored(0, v[Canonical::kDc + i], (bytes[2].back() / 255.0 - 0.5) / kColourScale);
      }
      for (int i = 0; i < 3; ++i) bytes[3].push_back(static_cast<unsigned char>(clamped_round(16 * (v[c_.scale() + i] + 10), 255, clamped_)));
      const double* q = v + c_.rotation();
      const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
      const double xyzw[4] = {q[1] / norm, q[2] / norm, q[3] / norm, q[0] / norm};
      int largest = 0;
      for (int i = 1; i < 4; ++i)
        if (std::abs(xyzw[i]) > std::abs(xyzw[largest])) largest = i;
      const bool negate = xyzw[largest] < 0;
      std::uint32_t word = std::uint32_t(largest);
      for (int i = 0; i < 4; ++i) {
        if (i == largest) continue;
        const std::uint32_t sign = (xyzw[i] < 0) != negate;
        const std::uint32_t magnitude = std::min(511u, std::uint32_t(std::nearbyint(511 * std::abs(xyzw[i]) / kSqrtHalf)));
        word = (word << 10) | (sign << 9) | magnitude;
      }
      for (int b = 0; b < 4; ++b) bytes[4].push_back(static_cast<unsigned char>(word >> (8 * b)));
      for (int k = 0; k < dim; ++k)
        for (int ch = 0; ch < 3; ++ch) {
          const double given = negate_band4_m4_ && k == kBand4M4 ? -v[Canonical::kRest + ch * dim + k] : v[Canonical::kRest + ch * dim + k];
          bytes[5].push_back(sh_byte(given, Canonical::band(k) == 1 ? 5 : 4, clamped_));
          stored(Canonical::band(k), given, (bytes[5].back() - 128.0) / 128);
        }
    }
    for (std::size_t a = 0; a < files_.size(); ++a) {
      files_[a].write(reinterpret_cast<const char*>(bytes[a].data()), std::streamsize(bytes[a].size()));
      if (!files_[a]) throw io::OutputError(dir_.path() + ": cannot write a temporary file");
    }
  }

  void finish() override {
    for (std::ofstream& file : files_) {
      file.close();
      if (!file) throw io::OutputError(dir_.path() + ": cannot write a temporary file");
    }
    if (version_ == 4) finish_zstd();
    else finish_gzip();
  }

 private:
  // Each attribute's bytes, a block at a time.
  template <class F>
  void for_each_block(std::size_t attribute, F&& use) {
    std::vector<unsigned char> chunk(1 << 16);
    std::ifstream in(dir_.path() + "/" + std::to_string(attribute), std::ios::binary);
    while (in.read(reinterpret_cast<char*>(chunk.data()), std::streamsize(chunk.size())) || in.gcount() > 0)
      use(chunk.data(), std::size_t(in.gcount()));
  }

  void put_header(unsigned char* header, std::uint32_t version) const {
    put_uint32(header, kMagic);
    put_uint32(header + 4, version);
    put_uint32(header + 8, static_cast<std::uint32_t>(splats_));
    header[12] = static_cast<unsigned char>(degree_);
    header[13] = kFractionalBits;
    header[14] = static_cast<unsigned char>((antialiased_ ? kFlagAntialiased : 0) | (records_.empty() ? 0 : kFlagExtensions));
  }

  // Version 4: the header, the extension records, the table, then each non-empty attribute as its
  // own zstd frame.
  void finish_zstd() {
    const std::array<std::uint64_t, kAttributes> per_splat = attribute_bytes(4, degree_);
    std::vector<std::size_t> present;
    for (std::size_t a = 0; a < kAttributes; ++a)
      if (per_splat[a] * splats_ > 0) present.push_back(a);
    const std::uint32_t table_at = static_cast<std::uint32_t>(kZstdHeaderBytes + records_.size());
    unsigned char header[kZstdHeaderBytes] = {};
    put_header(header, 4);
    header[15] = static_cast<unsigned char>(present.size());
    put_uint32(header + 16, table_at);
    out_.write(reinterpret_cast<const char*>(header), kZstdHeaderBytes);
    out_.write(records_);
    std::vector<unsigned char> table(16 * present.size());
    out_.write(reinterpret_cast<const char*>(table.data()), table.size());  // filled in below
    ZSTD_CStream* stream = ZSTD_createCStream();
    if (!stream) throw io::OutputError("zstd: cannot start compressing");
    std::vector<unsigned char> out(ZSTD_CStreamOutSize());
    try {
      for (std::size_t i = 0; i < present.size(); ++i) {
        ZSTD_CCtx_reset(stream, ZSTD_reset_session_only);
        ZSTD_CCtx_setParameter(stream, ZSTD_c_compressionLevel, kZstdLevel);
        ZSTD_CCtx_setParameter(stream, ZSTD_c_checksumFlag, 1);  // a reader can tell a damaged frame
        std::uint64_t compressed = 0, decompressed = 0;
        auto feed = [&](const unsigned char* data, std::size_t size, ZSTD_EndDirective mode) {
          ZSTD_inBuffer input{data, size, 0};
          for (;;) {
            ZSTD_outBuffer output{out.data(), out.size(), 0};
            const std::size_t left = ZSTD_compressStream2(stream, &output, &input, mode);
            if (ZSTD_isError(left)) throw io::OutputError(std::string("zstd: ") + ZSTD_getErrorName(left));
            out_.write(reinterpret_cast<const char*>(out.data()), output.pos);
            compressed += output.pos;
            if (mode == ZSTD_e_end ? left == 0 : input.pos == input.size) break;
          }
        };
        for_each_block(present[i], [&](const unsigned char* data, std::size_t size) {
          feed(data, size, ZSTD_e_continue);
          decompressed += size;
        });
        feed(nullptr, 0, ZSTD_e_end);
        std::memcpy(&table[16 * i], &compressed, 8);
        std::memcpy(&table[16 * i + 8], &decompressed, 8);
      }
    } catch (...) {
      ZSTD_freeCStream(stream);
      throw;
    }
    ZSTD_freeCStream(stream);
    out_.write_at(table_at, reinterpret_cast<const char*>(table.data()), table.size());
  }

  // Versions 2 and 3: the header, the attributes one after another and the extension records,
  // through one gzip stream.
  void finish_gzip() {
    Deflater deflater;
    z_stream& z = deflater.z;
    std::vector<unsigned char> out(1 << 16);
    auto feed = [&](const unsigned char* data, std::size_t size, int flush) {
      z.next_in = const_cast<unsigned char*>(data);
      z.avail_in = static_cast<uInt>(size);
      for (;;) {
        z.next_out = out.data();
        z.avail_out = static_cast<uInt>(out.size());
        const int result = deflate(&z, flush);
        if (result == Z_STREAM_ERROR) throw io::OutputError("gzip: deflate failed");
        out_.write(reinterpret_cast<const char*>(out.data()), out.size() - z.avail_out);
        if (flush == Z_FINISH ? result == Z_STREAM_END : z.avail_in == 0 && z.avail_out != 0) break;
      }
    };
    unsigned char header[kHeaderBytes] = {};
    put_header(header, 3);
    feed(header, kHeaderBytes, Z_NO_FLUSH);
    for (std::size_t a = 0; a < kAttributes; ++a)
      for_each_block(a, [&](const unsigned char* data, std::size_t size) { feed(data, size, Z_NO_FLUSH); });
    feed(reinterpret_cast<const unsigned char*>(records_.data()), records_.size(), Z_NO_FLUSH);
    feed(nullptr, 0, Z_FINISH);
  }

  io::PendingFile& out_;
  Canonical c_;
  int degree_, version_;
  std::uint64_t splats_;
  bool antialiased_;
  bool negate_band4_m4_ = false;  // spz_records.h: SpzFileAxes
  std::string records_;  // the extension records carried, as stored
  io::PrivateDir dir_{"zhf-spz"};  // each attribute's bytes until the end, in file order
  std::array<std::ofstream, kAttributes> files_;
};

}  // namespace

std::unique_ptr<SceneReader> open_spz_reader(const std::string& path, const Formats& formats) {
  return std::make_unique<SpzReader>(path, formats.spz_axes, formats.spz_as_reference);
}
std::unique_ptr<SceneWriter> open_spz_writer(io::PendingFile& out, const WriteOptions& options) {
  return std::make_unique<SpzWriter>(out, options);
}

}  // namespace zhf::splat
