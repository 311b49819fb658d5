// PlayCanvas's SOG (version 2), as splat-transform writes it: meta.json and lossless WebP images,
// bundled in a ZIP (.sog) or as files beside meta.json. Texel i (row-major) holds splat i:
//   means_l, means_u  low and high bytes of x, y, z as 16 bits t between meta's mins and maxs of
//                     sign(p) ln(|p| + 1); p = sign(v) (e^|v| - 1), v = min + (max - min) t / 65535
//   quats             the three smallest of w x y z (the largest made positive and left out), each
//                     255 (q sqrt(2) / 2 + 1/2), and 252 + the left-out component's index
//   scales            three indices into meta's 256-entry codebook of log-scales
//   sh0               three indices into meta's codebook of f_dc, and 255 sigmoid(opacity)
//   shN_labels        a 16-bit palette entry in red (low) and green (high), when bands > 0
//   shN_centroids     the palette: entry e at row e / 64, columns (e % 64) K .. + K - 1 for its K
//                     coefficients, red, green, blue indices into meta's SH codebook
// Per-splat images are width = ceil(sqrt(count) / 4) 4 by height = ceil(count / width / 4) 4.
// zhf reads every SOG into the canonical record. A SOG turned into a SOG keeps its palette, turning
// the positions and orientations of each splat and the palette's entries once: the labels, scales
// and colours are carried byte for byte. From any other scene SogWriter fits the codebooks and
// the palette anew.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>

#include <webp/decode.h>
#include <webp/encode.h>

#include "format_io.h"
#include "palette.h"
#include "scene_io.h"
#include "splat_math.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/json.h"
#include "zhf/io/limits.h"
#include "zhf/io/signals.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/splat/limits.h"
#include "zip.h"

namespace zhf::splat {
namespace {

namespace ply = io::ply;
using io::InputError;

constexpr int kCodebook = 256;
constexpr int kPaletteRow = 64;  // palette entries a centroid row holds
constexpr int kQuatTag = 252;
constexpr int kCodebookSteps = 10;  // Lloyd steps of a 256-level codebook
using runtime::kSqrt2;
constexpr std::array<std::array<int, 3>, 4> kStoredComponents = {{{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}}};

double log_transform(double x) { return std::copysign(std::log(std::abs(x) + 1), x); }
double inverse_log_transform(double v) { return std::copysign(std::exp(std::abs(v)) - 1, v); }

int coefficients_of(int bands) { return (bands + 1) * (bands + 1) - 1; }

std::array<int, 2> image_size(std::uint64_t count) {
  const int width = int(std::ceil(std::sqrt(double(count)) / 4)) * 4;
  const int height = width == 0 ? 0 : int((count + width * 4 - 1) / (width * 4)) * 4;
  return {width, height};
}

struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgba;
  const unsigned char* texel(std::uint64_t i) const { return rgba.data() + 4 * i; }
};

// The files of a SOG, from its ZIP or beside its meta.json.
class SogFiles {
 public:
  explicit SogFiles(const std::string& path) : path_(path) {
    if (std::filesystem::path(path).filename() != "meta.json") zip_.emplace(path);
  }
  std::string read(const std::string& name, std::uint64_t max_bytes) const {
    if (zip_) return zip_->read(name, max_bytes);
    return io::read_text_file((std::filesystem::path(path_).parent_path() / name).string(), max_bytes);
  }
  std::string where(const std::string& name) const { return zip_ ? path_ + ": " + name : (std::filesystem::path(path_).parent_path() / name).string(); }

 private:
  std::string path_;
  std::optional<ZipReader> zip_;
};

Image decode_webp(const std::string& bytes, const std::string& where, int width, int height) {
  Image image;
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
  if (!WebPGetInfo(data, bytes.size(), &image.width, &image.height)) throw InputError(where + ": not a WebP image zhf can decode");
  // The size meta.json gives, whose total read_sog has held to kMaxSogDecodedBytes: checked
  // before the texels are allocated.
  if (image.width != width || image.height != height)
    throw InputError(where + ": " + std::to_string(image.width) + " x " + std::to_string(image.height) + " texels; meta.json's count needs " +
                     std::to_string(width) + " x " + std::to_string(height));
  image.rgba.resize(std::size_t(width) * height * 4);
  if (!WebPDecodeRGBAInto(data, bytes.size(), image.rgba.data(), image.rgba.size(), width * 4))
    throw InputError(where + ": not a WebP image zhf can decode");
  return image;
}

// Lossless, with the colour under a transparent texel kept exactly (sh0's alpha is opacity).
std::string encode_webp(const Image& image) {
  WebPConfig config;
  WebPPicture picture;
  if (!WebPConfigInit(&config) || !WebPPictureInit(&picture)) throw io::OutputError("WebP: cannot start encoding");
  config.lossless = 1;
  config.exact = 1;
  picture.use_argb = 1;
  picture.width = image.width;
  picture.height = image.height;
  WebPMemoryWriter writer;
  WebPMemoryWriterInit(&writer);
  picture.writer = WebPMemoryWrite;
  picture.custom_ptr = &writer;
  const bool done = WebPPictureImportRGBA(&picture, image.rgba.data(), image.width * 4) && WebPEncode(&config, &picture);
  WebPPictureFree(&picture);
  std::string out(reinterpret_cast<const char*>(writer.mem), writer.size);
  WebPMemoryWriterClear(&writer);
  if (!done) throw io::OutputError("WebP: encoding failed");
  return out;
}

struct Meta {
  std::uint64_t count = 0;
  std::string model;  // "" or "antialiased"
  std::array<double, 3> mins{}, maxs{};
  std::vector<double> scales, colours, sh;  // codebooks
  int bands = 0, palette = 0;
  std::array<std::string, 2> means_files, sh_files;
  std::string scales_file, quats_file, sh0_file;
};

std::vector<double> codebook(const io::json::Field& f) {
  std::vector<double> out;
  for (const io::json::Field& x : f.items(kCodebook)) out.push_back(x.number());
  return out;
}

std::string file_name(const io::json::Field& f) {
  const std::string& name = f.string();
  if (name.empty() || name.size() > 255 || name.find('/') != std::string::npos || name.find('\\') != std::string::npos || name[0] == '.' ||
      !runtime::is_printable_text(name))
    f.fail("'" + runtime::excerpt(name) + "' is not a plain file name");
  return name;
}

Meta parse_meta(const std::string& text, const std::string& source) {
  const io::json::Json root = io::json::parse(text, source);
  const io::json::Field top(root, source);
  top.allow_only({"version", "asset", "count", "model", "means", "scales", "quats", "sh0", "shN"});
  if (top.member("version").integer(1, 2) != 2) top.member("version").fail("SOG version 1; zhf reads version 2");
  Meta m;
  m.count = std::uint64_t(top.member("count").integer(0LL, (long long)std::min<std::uint64_t>(io::kMaxPlyVertices, kMaxSogSplats)));
  if (const auto model = top.find("model")) m.model = model->one_of({"default", "antialiased"}) == "antialiased" ? "antialiased" : "";
  const io::json::Field means = top.member("means");
  means.allow_only({"mins", "maxs", "files"});
  const std::vector<io::json::Field> mins = means.member("mins").items(3), maxs = means.member("maxs").items(3);
  for (int i = 0; i < 3; ++i) {
    m.mins[i] = mins[i].number();
    m.maxs[i] = maxs[i].number(m.mins[i], std::numeric_limits<double>::max());
    if (std::abs(m.maxs[i]) > kMaxSogLogPosition || std::abs(m.mins[i]) > kMaxSogLogPosition)
      maxs[i].fail("beyond the log-position a float can undo (" + runtime::format_number(kMaxSogLogPosition) + ")");
  }
  const std::vector<io::json::Field> files = means.member("files").items(2);
  for (int i = 0; i < 2; ++i) m.means_files[i] = file_name(files[i]);
  for (const char* key : {"scales", "quats", "sh0"}) {
    const io::json::Field part = top.member(key);
    part.allow_only({"codebook", "files"});
    const std::string name = file_name(part.member("files").items(1)[0]);
    if (std::string(key) == "quats") {
      m.quats_file = name;
      if (part.find("codebook")) part.member("codebook").fail("quats have no codebook");
      continue;
    }
    (std::string(key) == "scales" ? m.scales_file : m.sh0_file) = name;
    (std::string(key) == "scales" ? m.scales : m.colours) = codebook(part.member("codebook"));
  }
  if (const auto shn = top.find("shN")) {
    shn->allow_only({"count", "bands", "codebook", "files"});
    m.bands = shn->member("bands").integer(1, 3);
    m.palette = shn->member("count").integer(1, kMaxSogPalette);
    m.sh = codebook(shn->member("codebook"));
    const std::vector<io::json::Field> names = shn->member("files").items(2);
    for (int i = 0; i < 2; ++i) m.sh_files[i] = file_name(names[i]);
  }
  return m;
}

// A whole SOG in memory: meta.json and its decoded images (4 bytes a texel each).
struct Sog {
  Meta meta;
  Image means_low, means_high, quats, scales, sh0, labels, centroids;
  std::string scales_bytes, sh0_bytes, labels_bytes;  // as stored, for a SOG written from it
};

Sog read_sog(const std::string& path) {
  const SogFiles files(path);
  Sog s;
  s.meta = parse_meta(files.read("meta.json", kMaxSogMetaBytes), files.where("meta.json"));
  const auto [width, height] = image_size(s.meta.count);
  const std::uint64_t palette_texels =
      s.meta.bands > 0 ? std::uint64_t(kPaletteRow) * coefficients_of(s.meta.bands) * ((s.meta.palette + kPaletteRow - 1) / kPaletteRow) : 0;
  const std::uint64_t decoded = 4 * (std::uint64_t(width) * height * (s.meta.bands > 0 ? 6 : 5) + palette_texels);
  if (decoded > kMaxSogDecodedBytes)
    throw InputError(files.where("meta.json") + ": " + std::to_string(s.meta.count) + " splats decode to " + std::to_string(decoded) +
                     " bytes of images; zhf reads a SOG of up to " + std::to_string(kMaxSogDecodedBytes));
  auto load = [&](const std::string& name, std::string* keep, int w, int h) {
    const std::string bytes = files.read(name, kMaxSogImageBytes);
    Image image = decode_webp(bytes, files.where(name), w, h);
    if (keep) *keep = bytes;
    return image;
  };
  s.means_low = load(s.meta.means_files[0], nullptr, width, height);
  s.means_high = load(s.meta.means_files[1], nullptr, width, height);
  s.quats = load(s.meta.quats_file, nullptr, width, height);
  s.scales = load(s.meta.scales_file, &s.scales_bytes, width, height);
  s.sh0 = load(s.meta.sh0_file, &s.sh0_bytes, width, height);
  if (s.meta.bands > 0) {
    s.labels = load(s.meta.sh_files[1], &s.labels_bytes, width, height);
    s.centroids = load(s.meta.sh_files[0], nullptr, kPaletteRow * coefficients_of(s.meta.bands), (s.meta.palette + kPaletteRow - 1) / kPaletteRow);
  }
  return s;
}

// Palette entry e's coefficient j of channel ch, from the SH codebook.
double palette_value(const Sog& s, int entry, int j, int ch) {
  const int k = coefficients_of(s.meta.bands);
  const std::uint64_t texel = std::uint64_t(entry / kPaletteRow) * s.centroids.width + (entry % kPaletteRow) * k + j;
  return s.meta.sh[s.centroids.texel(texel)[ch]];
}

// Splat i as the canonical record of the SOG's degree.
void decode_splat(const Sog& sog, std::uint64_t i, double* v, const std::string& path) {
  const Meta& m = sog.meta;
  const Canonical c(m.bands);
  const int per = c.rest / 3;
  const unsigned char *low = sog.means_low.texel(i), *high = sog.means_high.texel(i), *q = sog.quats.texel(i);
  const unsigned char *scale = sog.scales.texel(i), *colour = sog.sh0.texel(i);
  for (int a = 0; a < 3; ++a) {
    const double t = double(low[a] | (high[a] << 8)) / 65535;
    v[Canonical::kPosition + a] = inverse_log_transform(m.mins[a] + (m.maxs[a] - m.mins[a]) * t);
    v[Canonical::kNormal + a] = 0;
    v[Canonical::kDc + a] = m.colours[colour[a]];
    v[c.scale() + a] = m.scales[scale[a]];
  }
  v[c.opacity()] = opacity_of_alpha(colour[3] / 255.0);
  if (q[3] < kQuatTag) throw InputError(where(path, i, "quats") + ": tag " + std::to_string(q[3]) + " is not 252..255");
  const int largest = q[3] - kQuatTag;
  double* r = v + c.rotation();  // w x y z
  double squares = 0;
  for (int k = 0; k < 3; ++k) {
    const double x = (q[k] / 255.0 * 2 - 1) / kSqrt2;
    r[kStoredComponents[largest][k]] = x;
    squares += x * x;
  }
  r[largest] = std::sqrt(std::max(0.0, 1 - squares));
  if (m.bands == 0) return;
  const unsigned char* label = sog.labels.texel(i);
  const int entry = label[0] | (label[1] << 8);
  if (entry >= m.palette)
    throw InputError(where(path, i, "shN_labels") + ": palette entry " + std::to_string(entry) + "; the palette has " + std::to_string(m.palette));
  for (int ch = 0; ch < 3; ++ch)
    for (int j = 0; j < per; ++j) v[Canonical::kRest + ch * per + j] = palette_value(sog, entry, j, ch);
}

class SogReader : public SceneReader {
 public:
  explicit SogReader(const std::string& path) : path_(path), sog_(read_sog(path)) {
    splats_ = sog_.meta.count;
    degree_ = sog_.meta.bands;
    antialiased_ = sog_.meta.model == "antialiased";
  }
  void read(std::uint64_t first, std::uint64_t count, double* records) override {
    const Canonical c(degree_);
    for (std::uint64_t s = 0; s < count; ++s) decode_splat(sog_, first + s, records + s * c.size(), path_);
  }
  void finish() override {}

 private:
  std::string path_;
  Sog sog_;
};

// 256 levels for `values` (1D k-means from quantiles, a fixed number of Lloyd steps over the sorted
// values, so the same values give the same levels), ascending and rounded to float as the readers
// hold them.
std::vector<double> fit_codebook(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  std::vector<double> levels(kCodebook, values.empty() ? 0 : values.front());
  if (values.empty()) return levels;
  for (int k = 0; k < kCodebook; ++k) levels[k] = values[std::size_t((k + 0.5) / kCodebook * values.size())];
  for (int step = 0; step < kCodebookSteps; ++step) {
    std::vector<double> sums(kCodebook, 0);
    std::vector<std::size_t> counts(kCodebook, 0);
    int k = 0;
    for (double x : values) {
      while (k + 1 < kCodebook && std::abs(levels[k + 1] - x) <= std::abs(levels[k] - x)) ++k;
      sums[k] += x;
      ++counts[k];
    }
    for (int j = 0; j < kCodebook; ++j)
      if (counts[j]) levels[j] = sums[j] / double(counts[j]);
    std::sort(levels.begin(), levels.end());
  }
  for (double& x : levels) x = double(float(x));
  return levels;
}

unsigned char nearest_level(const std::vector<double>& levels, double x) {
  const auto above = std::lower_bound(levels.begin(), levels.end(), x);
  if (above == levels.begin()) return 0;
  if (above == levels.end()) return static_cast<unsigned char>(levels.size() - 1);
  return static_cast<unsigned char>(x - *(above - 1) <= *above - x ? above - 1 - levels.begin() : above - levels.begin());
}

// Positions (x y z per splat) as 16 bits of their log transform between the scene's bounds,
// which go to meta's mins and maxs.
void encode_means(const std::vector<double>& positions, std::uint64_t n, Meta& meta, Image& low, Image& high) {
  for (int a = 0; a < 3; ++a) {
    double least = INFINITY, most = -INFINITY;
    for (std::uint64_t i = 0; i < n; ++i) {
      least = std::min(least, log_transform(positions[3 * i + a]));
      most = std::max(most, log_transform(positions[3 * i + a]));
    }
    meta.mins[a] = n ? least : 0;
    meta.maxs[a] = n ? most : 0;
    for (std::uint64_t i = 0; i < n; ++i) {
      const double t = most > least ? (log_transform(positions[3 * i + a]) - least) / (most - least) : 0;
      const std::uint32_t v = std::uint32_t(std::clamp(std::nearbyint(65535 * t), 0.0, 65535.0));
      low.rgba[4 * i + a] = static_cast<unsigned char>(v & 0xff);
      high.rgba[4 * i + a] = static_cast<unsigned char>(v >> 8);
    }
  }
}

// Orientations (w x y z per splat, any norm): the three smallest components of the unit
// quaternion with its largest made positive, and the largest's index in the tag.
void encode_quats(const std::vector<double>& rotations, std::uint64_t n, Image& quats) {
  for (std::uint64_t i = 0; i < n; ++i) {
    const double* q = &rotations[4 * i];
    const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    int largest = 0;
    for (int a = 1; a < 4; ++a)
      if (std::abs(q[a]) > std::abs(q[largest])) largest = a;
    const double s = (q[largest] < 0 ? -1 : 1) * kSqrt2 / norm;
    for (int k = 0; k < 3; ++k)
      quats.rgba[4 * i + k] = static_cast<unsigned char>(std::clamp(std::nearbyint(255 * (q[kStoredComponents[largest][k]] * s * 0.5 + 0.5)), 0.0, 255.0));
    quats.rgba[4 * i + 3] = static_cast<unsigned char>(kQuatTag + largest);
  }
}

// The images of a SOG, encoded, by meta.json's file names.
struct SogImages {
  std::string means_low, means_high, scales, quats, sh0, centroids, labels;
};

// meta.json (its codebooks and bounds from `m`) and the images, bundled into out.
void write_bundle(io::PendingFile& out, const Meta& m, const SogImages& images) {
  nlohmann::ordered_json meta = {{"version", 2}, {"asset", {{"generator", "zhf splat"}}}, {"count", m.count}};
  if (!m.model.empty()) meta["model"] = m.model;
  meta["means"] = {{"mins", m.mins}, {"maxs", m.maxs}, {"files", {"means_l.webp", "means_u.webp"}}};
  meta["scales"] = {{"codebook", m.scales}, {"files", {"scales.webp"}}};
  meta["quats"] = {{"files", {"quats.webp"}}};
  meta["sh0"] = {{"codebook", m.colours}, {"files", {"sh0.webp"}}};
  std::vector<std::pair<std::string, std::string>> entries = {{"meta.json", ""},          {"means_l.webp", images.means_low},
                                                              {"means_u.webp", images.means_high}, {"scales.webp", images.scales},
                                                              {"quats.webp", images.quats}, {"sh0.webp", images.sh0}};
  if (m.bands > 0) {
    meta["shN"] = {{"count", m.palette}, {"bands", m.bands}, {"codebook", m.sh}, {"files", {"shN_centroids.webp", "shN_labels.webp"}}};
    entries.emplace_back("shN_centroids.webp", images.centroids);
    entries.emplace_back("shN_labels.webp", images.labels);
  }
  entries[0].second = io::json_text(meta);
  write_zip(out, entries);
}

Image blank_image(std::uint64_t count) {
  Image image;
  const auto [width, height] = image_size(count);
  image.width = width;
  image.height = height;
  image.rgba.assign(std::size_t(width) * height * 4, 0);
  return image;
}

// A SOG from canonical records of any format: every splat held (in float) until finish(), then
// the images: positions and orientations as above, log-scales and f_dc through 256-level
// codebooks (fit_codebook), opacity as a byte of sigmoid(opacity), and the SH above band 0
// through a palette (palette.h: at most kMaxSogPalette entries, a scene of that many splats or
// fewer exactly) whose values go through a 256-level codebook of their own. The splats keep the
// input's order.
class SogWriter : public SceneWriter {
 public:
  SogWriter(io::PendingFile& out, const WriteOptions& options)
      : out_(out), options_(options), size_(Canonical(options.degree).size()) {
    records_.reserve(std::size_t(options.splats) * size_);
  }
  void write(std::uint64_t count, const double* records) override {
    for (std::uint64_t i = 0; i < count * std::uint64_t(size_); ++i) records_.push_back(clamped_float(records[i], clamped_));
  }
  void finish() override {
    const Canonical c(options_.degree);
    const std::uint64_t n = records_.size() / size_;
    const int per = c.rest / 3;
    auto value = [&](std::uint64_t splat, int field) { return double(records_[splat * size_ + field]); };
    Meta m;
    m.count = n;
    m.bands = options_.degree;
    if (options_.antialiased) m.model = "antialiased";
    std::vector<double> positions(3 * n), rotations(4 * n), scales(3 * n), colours(3 * n);
    for (std::uint64_t i = 0; i < n; ++i) {
      for (int a = 0; a < 3; ++a) {
        positions[3 * i + a] = value(i, Canonical::kPosition + a);
        scales[3 * i + a] = value(i, c.scale() + a);
        colours[3 * i + a] = value(i, Canonical::kDc + a);
      }
      for (int a = 0; a < 4; ++a) rotations[4 * i + a] = value(i, c.rotation() + a);
    }
    Image means_low = blank_image(n), means_high = blank_image(n), quats = blank_image(n), scale_image = blank_image(n), sh0 = blank_image(n);
    encode_means(positions, n, m, means_low, means_high);
    encode_quats(rotations, n, quats);
    m.scales = fit_codebook(scales);
    m.colours = fit_codebook(colours);
    for (std::uint64_t i = 0; i < n; ++i) {
      for (int a = 0; a < 3; ++a) {
        scale_image.rgba[4 * i + a] = nearest_level(m.scales, value(i, c.scale() + a));
        const unsigned char level = nearest_level(m.colours, value(i, Canonical::kDc + a));
        sh0.rgba[4 * i + a] = level;
        stored(0, value(i, Canonical::kDc + a), m.colours[level]);
      }
      scale_image.rgba[4 * i + 3] = 255;
      sh0.rgba[4 * i + 3] = static_cast<unsigned char>(std::clamp(std::nearbyint(255 * sigmoid(value(i, c.opacity()))), 0.0, 255.0));
    }
    io::throw_if_interrupted();
    SogImages images;
    if (m.bands > 0) {
      const float* rest = records_.data() + Canonical::kRest;  // splat i's SH above band 0 at rest + i * size_
      const Palette palette = fit_palette(rest, std::size_t(size_), n, c.rest, kMaxSogPalette, options_.seed, options_.threads);
      m.palette = int(palette.entries.size() / c.rest);
      m.sh = fit_codebook(std::vector<double>(palette.entries.begin(), palette.entries.end()));
      Image centroids;
      centroids.width = kPaletteRow * per;
      centroids.height = (m.palette + kPaletteRow - 1) / kPaletteRow;
      centroids.rgba.assign(std::size_t(centroids.width) * centroids.height * 4, 255);
      std::vector<unsigned char> levels(palette.entries.size());
      for (std::size_t k = 0; k < levels.size(); ++k) levels[k] = nearest_level(m.sh, palette.entries[k]);
      for (int e = 0; e < m.palette; ++e)
        for (int ch = 0; ch < 3; ++ch)
          for (int j = 0; j < per; ++j) {
            const std::uint64_t texel = std::uint64_t(e / kPaletteRow) * centroids.width + (e % kPaletteRow) * per + j;
            centroids.rgba[4 * texel + ch] = levels[std::size_t(e) * c.rest + ch * per + j];
          }
      Image labels = blank_image(n);
      for (std::uint64_t i = 0; i < n; ++i) {
        const std::uint32_t entry = palette.labels[i];
        labels.rgba[4 * i] = static_cast<unsigned char>(entry & 0xff);
        labels.rgba[4 * i + 1] = static_cast<unsigned char>(entry >> 8);
        labels.rgba[4 * i + 3] = 255;
        for (int k = 0; k < c.rest; ++k)
          stored(Canonical::band(k % per), rest[i * size_ + k], m.sh[levels[std::size_t(entry) * c.rest + k]]);
      }
      images.centroids = encode_webp(centroids);
      images.labels = encode_webp(labels);
    }
    images.means_low = encode_webp(means_low);
    images.means_high = encode_webp(means_high);
    images.scales = encode_webp(scale_image);
    images.quats = encode_webp(quats);
    images.sh0 = encode_webp(sh0);
    write_bundle(out_, m, images);
  }

 private:
  io::PendingFile& out_;
  WriteOptions options_;
  int size_;
  std::vector<float> records_;
};

}  // namespace

std::unique_ptr<SceneReader> open_sog_reader(const std::string& path, const Formats&) { return std::make_unique<SogReader>(path); }
std::unique_ptr<SceneWriter> open_sog_writer(io::PendingFile& out, const WriteOptions& options) { return std::make_unique<SogWriter>(out, options); }

// A SOG turned whole: each splat's position and orientation, the SH palette once; labels, scales
// (their codebook shifted by log s) and colours carried.
Summary transform_sog(const std::string& in, const std::string& out, const Transform& transform, const Formats&, Summary summary) {
  const Sog sog = read_sog(in);
  const Meta& m = sog.meta;
  const std::uint64_t n = m.count;
  // Positions and orientations: the splats as degree-0 records through the transform.
  const Canonical geometry(0);
  const ply::Header header = canonical_header(0, 1);
  const Layout layout = layout_of(header, "canonical record");
  const SplatMath math(layout, transform);
  std::vector<double> positions(3 * n), rotations(4 * n), record(geometry.size());
  const Canonical full(m.bands);
  std::vector<double> full_record(full.size());
  for (std::uint64_t i = 0; i < n; ++i) {
    decode_splat(sog, i, full_record.data(), in);
    std::copy(full_record.begin(), full_record.begin() + Canonical::kRest, record.begin());
    std::copy(full_record.begin() + full.opacity(), full_record.end(), record.begin() + geometry.opacity());
    math.apply(record.data());
    for (int a = 0; a < 3; ++a) positions[3 * i + a] = record[Canonical::kPosition + a];
    for (int a = 0; a < 4; ++a) rotations[4 * i + a] = record[geometry.rotation() + a];
  }
  Meta written = m;
  Image means_low = sog.means_low, means_high = sog.means_high, quats = sog.quats;
  encode_means(positions, n, written, means_low, means_high);
  encode_quats(rotations, n, quats);
  const double log_scale = std::log(transform.scale);
  for (double& x : written.scales) x = double(float(x + log_scale));
  // The palette: each entry's SH as a record of its own, turned once.
  std::string centroids_bytes;
  if (m.bands > 0) {
    const Canonical c(m.bands);
    const int per = c.rest / 3;
    const ply::Header sh_header = canonical_header(m.bands, 1);
    const Layout sh_layout = layout_of(sh_header, "canonical record");
    Transform turn;
    turn.r = transform.r;
    turn.convention = transform.convention;
    const SplatMath sh_math(sh_layout, turn);
    std::vector<double> palette(std::size_t(m.palette) * c.size(), 0);
    for (int e = 0; e < m.palette; ++e) {
      double* v = &palette[std::size_t(e) * c.size()];
      v[c.rotation()] = 1;
      for (int ch = 0; ch < 3; ++ch)
        for (int j = 0; j < per; ++j) v[Canonical::kRest + ch * per + j] = palette_value(sog, e, j, ch);
    }
    sh_math.apply_many(palette.data(), std::size_t(m.palette), std::size_t(c.size()));
    std::vector<double> values;
    for (int e = 0; e < m.palette; ++e)
      for (int k = 0; k < c.rest; ++k) values.push_back(palette[std::size_t(e) * c.size() + Canonical::kRest + k]);
    written.sh = fit_codebook(values);
    Image centroids = sog.centroids;
    for (int band = 0; band <= m.bands; ++band) summary.sh_error[band] = 0;
    for (int e = 0; e < m.palette; ++e)
      for (int ch = 0; ch < 3; ++ch)
        for (int j = 0; j < per; ++j) {
          const double x = palette[std::size_t(e) * c.size() + Canonical::kRest + ch * per + j];
          const std::uint64_t texel = std::uint64_t(e / kPaletteRow) * centroids.width + (e % kPaletteRow) * per + j;
          const unsigned char level = nearest_level(written.sh, x);
          centroids.rgba[4 * texel + ch] = level;
          summary.sh_error[Canonical::band(j)] = std::max(summary.sh_error[Canonical::band(j)], std::abs(written.sh[level] - x));
        }
    centroids_bytes = encode_webp(centroids);
    summary.palette_entries = std::uint64_t(m.palette);
  }
  summary.splats = n;
  summary.sh_degree = summary.kept_degree = m.bands;
  summary.antialiased = m.model == "antialiased";
  SogImages images{encode_webp(means_low), encode_webp(means_high), sog.scales_bytes, encode_webp(quats), sog.sh0_bytes, centroids_bytes,
                   sog.labels_bytes};
  io::PendingFile pending(out);
  write_bundle(pending, written, images);
  pending.commit();
  return summary;
}

}  // namespace zhf::splat
