#include "scene_io.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "format_io.h"
#include "splat_math.h"
#include "zhf/io/errors.h"

namespace zhf::splat {
namespace {

namespace ply = io::ply;
using io::InputError;

// ---- .ply (binary little-endian or ASCII), any column order, to the canonical record ----

// Extra properties named in a note before "and N more".
constexpr std::size_t kNamedProperties = 4;

class PlyReader : public SceneReader {
 public:
  explicit PlyReader(const std::string& path) : path_(path), file_(open_input(path)) {
    header_ = ply::read_header(file_, path);
    layout_ = layout_of(header_, path);
    if (layout_.degree < 0) throw InputError(path + ": no f_dc_0..2 properties: nothing to convert the colour from");
    for (const char* name : {"opacity", "scale_0", "rot_0"})
      if (header_.find(name) < 0) throw InputError(path + ": no property " + name + ": converting to another format needs it");
    if (!ply::is_float(header_.properties[layout_.opacity].type)) throw InputError(path + ": property opacity is not float or double");
    if (header_.format == ply::Format::kBinaryLittleEndian) {
      const std::uint64_t size = regular_file_size(path, "a converted .ply is checked against its size first");
      const std::uint64_t expected = header_.text.size() + header_.vertices * header_.record_bytes;
      if (size != expected)
        throw InputError(path + ": " + std::to_string(size) + " bytes, but the header says " + std::to_string(expected) +
                         (size < expected ? ": truncated" : ": bytes after the last splat"));
    }
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
    const bool ascii = header_.format == ply::Format::kAscii;
    if (!ascii) {
      buffer_.resize(count * header_.record_bytes);
      file_.read(reinterpret_cast<char*>(buffer_.data()), std::streamsize(buffer_.size()));
      if (std::uint64_t(file_.gcount()) != buffer_.size()) throw InputError(path_ + ": truncated");
    }
    std::vector<double> values(header_.properties.size());
    for (std::uint64_t s = 0; s < count; ++s) {
      const unsigned char* record = ascii ? nullptr : buffer_.data() + s * header_.record_bytes;
      if (ascii) ply::parse_ascii_or_throw(ply::read_ascii_line(file_, line_, path_, first + s, splats_), header_, path_, first + s, values.data());
      double* v = records + s * c.size();
      for (int i = 0; i < c.size(); ++i) {
        v[i] = source_[i] < 0 ? 0 : ascii ? values[source_[i]] : ply::read_binary(record, header_.properties[source_[i]]);
        if (!std::isfinite(v[i]) && !keep_nonfinite_)
          throw InputError(where(path_, first + s, "property " + header_.properties[source_[i]].name) + " is " + runtime::format_number(v[i]));
      }
      const double* q = v + c.rotation();
      if (q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0) throw InputError(where(path_, first + s, "rot_0..3 are all zero"));
      nonzero_normals_ = nonzero_normals_ || v[Canonical::kNormal] != 0 || v[Canonical::kNormal + 1] != 0 || v[Canonical::kNormal + 2] != 0;
    }
  }

  std::vector<std::string> left_out(FileFormat to) const override {
    std::vector<std::string> phrases;
    std::vector<std::string> extra;
    for (std::size_t p = 0; p < header_.properties.size(); ++p)
      if (std::find(source_.begin(), source_.end(), int(p)) == source_.end()) extra.push_back(header_.properties[p].name);
    if (!extra.empty()) {
      std::string names = "property " + runtime::excerpt(extra[0]);
      for (std::size_t i = 1; i < std::min<std::size_t>(extra.size(), kNamedProperties); ++i) names += ", " + runtime::excerpt(extra[i]);
      if (extra.size() > kNamedProperties) names += " and " + std::to_string(extra.size() - kNamedProperties) + " more";
      phrases.push_back(extra.size() == 1 ? names : "properties" + names.substr(8));
    }
    if (to == FileFormat::kPly) {
      int comments = 0;
      for (std::size_t at = 0; at < header_.text.size();) {
        const std::size_t end = header_.text.find('\n', at);
        const std::string_view line(header_.text.data() + at, (end == std::string::npos ? header_.text.size() : end) - at);
        comments += line.rfind("comment", 0) == 0 || line.rfind("obj_info", 0) == 0;
        at = end == std::string::npos ? header_.text.size() : end + 1;
      }
      if (comments > 0) phrases.push_back(std::to_string(comments) + " comment line" + (comments > 1 ? "s" : ""));
      if (header_.format == ply::Format::kAscii) phrases.push_back("ASCII (written binary)");
      bool doubles = false;
      for (int p : source_) doubles = doubles || (p >= 0 && header_.properties[p].type == ply::Type::kFloat64);
      if (doubles) phrases.push_back("double precision (written as float)");
    } else if (nonzero_normals_) {
      phrases.push_back("normals (nx, ny, nz; not all 0)");
    }
    return phrases;
  }

  void finish() override {
    if (header_.format == ply::Format::kAscii) {
      ply::check_ascii_end(file_, path_);
    } else if (file_.peek() != std::char_traits<char>::eof()) {
      throw InputError(path_ + ": bytes after the last splat");
    }
  }

 private:
  std::string path_;
  std::ifstream file_;
  std::vector<char> line_;  // an ASCII file's current line
  ply::Header header_;
  Layout layout_;
  std::vector<int> source_;  // canonical field -> header property, -1: none (normals: 0)
  std::vector<unsigned char> buffer_;
  bool nonzero_normals_ = false;
};

class PlyWriter : public SceneWriter {
 public:
  PlyWriter(io::PendingFile& out, int degree, std::uint64_t splats) : out_(out), size_(Canonical(degree).size()), rest_(Canonical(degree).rest) {
    out_.write(canonical_header(degree, splats).text);
  }
  void write(std::uint64_t count, const double* records) override {
    buffer_.resize(count * size_ * sizeof(float));
    unsigned char* at = buffer_.data();
    for (std::uint64_t s = 0; s < count; ++s)
      for (int field = 0; field < size_; ++field, at += sizeof(float)) {
        const double given = records[s * size_ + field];
        const float value = clamped_float(given, clamped_);
        if (field >= Canonical::kDc && field < Canonical::kRest + rest_)
          stored(field < Canonical::kRest ? 0 : Canonical::band((field - Canonical::kRest) % (rest_ / 3)), given, value);
        put_float(at, value);
      }
    out_.write(reinterpret_cast<const char*>(buffer_.data()), buffer_.size());
  }

 private:
  io::PendingFile& out_;
  int size_, rest_;
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

std::unique_ptr<SceneReader> open_ply_reader(const std::string& path, const Formats&) { return std::make_unique<PlyReader>(path); }
std::unique_ptr<SceneWriter> open_ply_writer(io::PendingFile& out, const WriteOptions& options) {
  return std::make_unique<PlyWriter>(out, options.degree, options.splats);
}

}  // namespace zhf::splat
