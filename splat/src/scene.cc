#include "zhf/runtime/limits.h"
#include "zhf/splat/scene.h"

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/numbers.h"
#include "zhf/io/ply.h"
#include "zhf/io/signals.h"
#include "zhf/runtime/finite.h"
#include "zhf/runtime/orthogonal.h"
#include "zhf/runtime/rotator.h"
#include "zhf_kernels.h"

namespace zhf::splat {
namespace {

namespace ply = io::ply;
using io::InputError;


// Where the transformed properties are (indices into the header's properties; -1: absent).
struct Layout {
  std::array<int, 3> position{-1, -1, -1}, normal{-1, -1, -1}, dc{-1, -1, -1}, log_scale{-1, -1, -1};
  std::array<int, 4> rotation{-1, -1, -1, -1};  // w, x, y, z
  std::vector<int> rest;                         // f_rest_0..K-1, channel-major (K / 3 per channel)
  int degree = -1;
  std::vector<int> changed;  // every property a transform may change
};

// The named properties, all float or double: all present, or none (false).
template <std::size_t K>
bool group(const ply::Header& header, const std::array<const char*, K>& names, std::array<int, K>& out, const std::string& source) {
  int present = 0;
  for (std::size_t i = 0; i < K; ++i) {
    out[i] = header.find(names[i]);
    if (out[i] < 0) continue;
    ++present;
    if (!ply::is_float(header.properties[out[i]].type))
      throw InputError(source + ": property " + names[i] + " is not float or double");
  }
  if (present != 0 && present != int(K))
    throw InputError(source + ": property " + names[0] + " and its " + std::to_string(K - 1) + " companions must all be present, or none");
  return present == int(K);
}

Layout layout_of(const ply::Header& header, const std::string& source) {
  Layout layout;
  if (!group<3>(header, {"x", "y", "z"}, layout.position, source)) throw InputError(source + ": no x, y, z properties");
  group<3>(header, {"nx", "ny", "nz"}, layout.normal, source);
  group<4>(header, {"rot_0", "rot_1", "rot_2", "rot_3"}, layout.rotation, source);
  group<3>(header, {"scale_0", "scale_1", "scale_2"}, layout.log_scale, source);
  const bool colour = group<3>(header, {"f_dc_0", "f_dc_1", "f_dc_2"}, layout.dc, source);
  std::size_t rest = 0;
  for (const ply::Property& p : header.properties) rest += p.name.rfind("f_rest_", 0) == 0;
  if (rest != 0 && rest != 9 && rest != 24 && rest != 45)
    throw InputError(source + ": " + std::to_string(rest) + " f_rest properties; SH degree 1, 2, 3 has 9, 24, 45");
  if (rest > 0 && !colour) throw InputError(source + ": f_rest properties without f_dc_0..2");
  for (std::size_t i = 0; i < rest; ++i) {
    const std::string name = "f_rest_" + std::to_string(i);
    const int index = header.find(name);
    if (index < 0) throw InputError(source + ": " + std::to_string(rest) + " f_rest properties, but no " + name);
    if (!ply::is_float(header.properties[index].type)) throw InputError(source + ": property " + name + " is not float or double");
    layout.rest.push_back(index);
  }
  layout.degree = !colour ? -1 : rest == 0 ? 0 : rest == 9 ? 1 : rest == 24 ? 2 : 3;
  for (int i : layout.position) layout.changed.push_back(i);
  for (const auto* g : {&layout.normal, &layout.log_scale})
    if ((*g)[0] >= 0) layout.changed.insert(layout.changed.end(), g->begin(), g->end());
  if (layout.rotation[0] >= 0) layout.changed.insert(layout.changed.end(), layout.rotation.begin(), layout.rotation.end());
  layout.changed.insert(layout.changed.end(), layout.rest.begin(), layout.rest.end());
  return layout;
}

// One splat's transform, on the values of all its properties.
class SplatMath {
 public:
  // splats: how many there are (three colour vectors each decide how the SH is applied).
  SplatMath(const Layout& layout, const Transform& t, std::uint64_t splats) : layout_(layout), t_(t) {
    const runtime::Matrix3& r = t.r;
    reflection_ = runtime::determinant(r.data()) < 0;
    runtime::Matrix3 proper = r;
    if (reflection_)
      for (double& x : proper) x = -x;
    turn_ = runtime::quaternion_from_rotation(proper);
    log_scale_ = std::log(t.scale);
    if (layout.degree >= 1) {
      const runtime::Convention& convention = t.convention ? *t.convention : *runtime::find_convention("3dgs");
      const runtime::Matrix3 q = convention.rotation_in_zhf_terms(r);
      rotator_ = std::make_unique<runtime::Rotator<double>>(
          runtime::Rotator<double>::with(gen::fastest_kernels<double>(layout.degree + 1)));
      sh_ = std::make_unique<runtime::OrthogonalTransform<double>>(*rotator_, q.data());
      prepared_.emplace(sh_->prepare(3 * splats));
    }
  }

  void apply(double* v) const {
    const runtime::Matrix3& r = t_.r;
    const auto& p = layout_.position;
    const double x = v[p[0]], y = v[p[1]], z = v[p[2]];
    for (int i = 0; i < 3; ++i)
      v[p[i]] = t_.scale * (r[3 * i] * x + r[3 * i + 1] * y + r[3 * i + 2] * z) + t_.translation[i];
    const auto& n = layout_.normal;
    if (n[0] >= 0) {
      const double a = v[n[0]], b = v[n[1]], c = v[n[2]];
      for (int i = 0; i < 3; ++i) v[n[i]] = r[3 * i] * a + r[3 * i + 1] * b + r[3 * i + 2] * c;
    }
    const auto& q = layout_.rotation;
    if (q[0] >= 0) {
      // Q' = R Q, or for a reflection R Q F = (-R) Q Rz(pi): the quaternion of Rz(pi) is (0, 0, 0, 1).
      std::array<double, 4> turned = runtime::quaternion_product(turn_, {v[q[0]], v[q[1]], v[q[2]], v[q[3]]});
      if (reflection_) turned = runtime::quaternion_product(turned, {0, 0, 0, 1});
      for (int i = 0; i < 4; ++i) v[q[i]] = turned[i];
    }
    if (layout_.log_scale[0] >= 0)
      for (int i : layout_.log_scale) v[i] += log_scale_;
    if (prepared_) {
      const int n2 = (layout_.degree + 1) * (layout_.degree + 1), per = n2 - 1;
      double in[16], out[16];
      for (int c = 0; c < 3; ++c) {
        in[0] = v[layout_.dc[c]];
        for (int j = 0; j < per; ++j) in[1 + j] = v[layout_.rest[c * per + j]];
        prepared_->apply(in, out);
        for (int j = 0; j < per; ++j) v[layout_.rest[c * per + j]] = out[1 + j];
      }
    }
  }

 private:
  const Layout& layout_;
  const Transform& t_;
  bool reflection_ = false;
  std::array<double, 4> turn_{};
  double log_scale_ = 0;
  std::unique_ptr<runtime::Rotator<double>> rotator_;
  std::unique_ptr<runtime::OrthogonalTransform<double>> sh_;
  std::optional<runtime::OrthogonalTransform<double>::Prepared> prepared_;
};

// The first failing splat of a chunk, found by the workers; its message is made once, after.
class FirstFailure {
 public:
  void note(std::uint64_t splat) {
    std::uint64_t seen = first_.load();
    while (splat < seen && !first_.compare_exchange_weak(seen, splat)) {
    }
  }
  std::optional<std::uint64_t> splat() const {
    const std::uint64_t s = first_.load();
    return s == kNone ? std::nullopt : std::optional<std::uint64_t>(s);
  }

 private:
  static constexpr std::uint64_t kNone = ~std::uint64_t(0);
  std::atomic<std::uint64_t> first_{kNone};
};

std::string splat_where(const std::string& source, std::uint64_t splat, const ply::Property& p) {
  return source + ": splat " + std::to_string(splat) + ": property " + p.name;
}

// ---- binary little-endian ----

void transform_binary(std::istream& file, io::PendingFile& pending, const ply::Header& header, const Layout& layout,
                      const SplatMath& math, const std::string& source, int threads,
                      const std::function<void(std::uint64_t, std::uint64_t)>& progress) {
  const std::size_t bytes = header.record_bytes, properties = header.properties.size();
  const bool all_float = std::all_of(header.properties.begin(), header.properties.end(),
                                     [](const ply::Property& p) { return p.type == ply::Type::kFloat32; });
  // Chunk `first` onwards into buffer; returns how many splats it holds.
  auto read_chunk = [&](std::vector<unsigned char>& buffer, std::uint64_t first) {
    const std::uint64_t count = std::min(kChunkSplats, header.vertices - first);
    buffer.resize(count * bytes);
    file.read(reinterpret_cast<char*>(buffer.data()), std::streamsize(buffer.size()));
    if (std::uint64_t(file.gcount()) != buffer.size())
      throw InputError(source + ": truncated: the data ends in splat " + std::to_string(first + file.gcount() / bytes) + " of " +
                       std::to_string(header.vertices));
    return count;
  };
  // Two buffers: while the workers transform one, another thread writes the one before and reads
  // the next into it (or the calling thread does, when no thread can be started).
  std::vector<unsigned char> chunk, other;
  std::uint64_t count = header.vertices > 0 ? read_chunk(chunk, 0) : 0;
  bool other_holds_output = false;
  for (std::uint64_t done = 0; done < header.vertices;) {
    const std::uint64_t next = done + count;
    std::future<std::uint64_t> io = std::async(std::launch::async | std::launch::deferred, [&, next, other_holds_output] {
      if (other_holds_output) pending.write(reinterpret_cast<const char*>(other.data()), other.size());
      return next < header.vertices ? read_chunk(other, next) : std::uint64_t(0);
    });
    FirstFailure failure;
    runtime::parallel_chunks(count, threads, [&](std::size_t begin, std::size_t end) {
      std::vector<double> v(properties);
      std::vector<float> floats(all_float ? properties : 0);
      for (std::size_t s = begin; s < end; ++s) {
        unsigned char* record = chunk.data() + s * bytes;
        bool finite = true;
        if (all_float) {
          // The common file: every property float32. Values converted in one loop, and all written
          // back (an unchanged float survives float -> double -> float exactly).
          std::memcpy(floats.data(), record, bytes);
          for (std::size_t i = 0; i < properties; ++i) v[i] = floats[i];
          finite = runtime::all_finite(floats.data(), properties);
        } else {
          for (std::size_t i = 0; i < properties; ++i) {
            v[i] = ply::read_binary(record, header.properties[i]);
            finite = finite && std::isfinite(v[i]);
          }
        }
        if (!finite) {
          failure.note(done + s);
          return;
        }
        math.apply(v.data());
        if (all_float) {
          for (std::size_t i = 0; i < properties; ++i) floats[i] = static_cast<float>(v[i]);
          std::memcpy(record, floats.data(), bytes);
        } else {
          for (int i : layout.changed) ply::write_binary(record, header.properties[i], v[i]);
        }
      }
    });
    const std::uint64_t next_count = io.get();
    if (const auto bad = failure.splat()) {
      const unsigned char* record = chunk.data() + (*bad - done) * bytes;
      for (const ply::Property& p : header.properties)
        if (!std::isfinite(ply::read_binary(record, p)))
          throw InputError(splat_where(source, *bad, p) + " is " + runtime::format_number(ply::read_binary(record, p)));
    }
    std::swap(chunk, other);  // other: this chunk's output, to write; chunk: the next input
    other_holds_output = true;
    done = next;
    count = next_count;
    io::throw_if_interrupted();
    progress(done, header.vertices);
  }
  if (other_holds_output) pending.write(reinterpret_cast<const char*>(other.data()), other.size());
  if (file.peek() != std::char_traits<char>::eof()) throw InputError(source + ": bytes after the last splat");
}

// ---- ASCII ----

// A token of the property's type as a double: floats strictly (finite), integers in range.
std::optional<double> parse_token(std::string_view token, ply::Type type, std::string& problem) {
  if (ply::is_float(type)) {
    const io::ParsedNumber x = io::parse_number(token);
    if (!x.value) problem = x.problem;
    return x.value;
  }
  long long value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  const long long low = type == ply::Type::kInt8 ? -128 : type == ply::Type::kInt16 ? -32768 : type == ply::Type::kInt32 ? -2147483648LL : 0;
  const long long high = type == ply::Type::kInt8 ? 127 : type == ply::Type::kUint8 ? 255 : type == ply::Type::kInt16 ? 32767
                         : type == ply::Type::kUint16 ? 65535 : type == ply::Type::kInt32 ? 2147483647LL : 4294967295LL;
  if (error != std::errc() || end != token.data() + token.size() || value < low || value > high) {
    problem = "is not an integer of the property's type";
    return std::nullopt;
  }
  return double(value);
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    if (i == line.size()) break;
    std::size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
    tokens.push_back(line.substr(i, j - i));
    i = j;
  }
  return tokens;
}

void transform_ascii(std::istream& file, io::PendingFile& pending, const ply::Header& header, const Layout& layout,
                     const SplatMath& math, const std::string& source, int threads,
                     const std::function<void(std::uint64_t, std::uint64_t)>& progress) {
  const std::size_t properties = header.properties.size();
  std::vector<bool> changed(properties, false);
  for (int i : layout.changed) changed[i] = true;
  std::vector<std::string> lines;
  std::vector<std::string> output;
  std::vector<char> buffer(runtime::kMaxPlyAsciiLine + 2);
  for (std::uint64_t done = 0; done < header.vertices;) {
    const std::uint64_t count = std::min(kChunkSplats, header.vertices - done);
    lines.resize(count);
    for (std::uint64_t s = 0; s < count; ++s) {
      file.getline(buffer.data(), std::streamsize(buffer.size()));
      if (file.fail() && !file.eof())
        throw InputError(source + ": splat " + std::to_string(done + s) + ": a line longer than " + std::to_string(runtime::kMaxPlyAsciiLine) + " bytes");
      if (file.gcount() == 0 && file.eof())
        throw InputError(source + ": truncated: the data ends before splat " + std::to_string(done + s) + " of " +
                         std::to_string(header.vertices));
      lines[s].assign(buffer.data());
    }
    output.assign(count, std::string());
    FirstFailure failure;
    runtime::parallel_chunks(count, threads, [&](std::size_t begin, std::size_t end) {
      std::vector<double> v(properties);
      std::string problem;
      for (std::size_t s = begin; s < end; ++s) {
        const std::vector<std::string_view> tokens = split(lines[s]);
        bool ok = tokens.size() == properties;
        for (std::size_t i = 0; ok && i < properties; ++i) {
          const std::optional<double> x = parse_token(tokens[i], header.properties[i].type, problem);
          ok = x.has_value();
          if (ok) v[i] = *x;
        }
        if (!ok) {
          failure.note(done + s);
          return;
        }
        math.apply(v.data());
        // Transformed values written anew (float32: 9 digits, double: 17, both round-trip);
        // every other token as it was.
        std::string& line = output[s];
        for (std::size_t i = 0; i < properties; ++i) {
          if (i) line += ' ';
          if (!changed[i]) {
            line.append(tokens[i]);
            continue;
          }
          char text[40];
          const bool single = header.properties[i].type == ply::Type::kFloat32;
          std::snprintf(text, sizeof text, single ? "%.9g" : "%.17g", single ? double(float(v[i])) : v[i]);
          line += text;
        }
        line += '\n';
      }
    });
    if (const auto bad = failure.splat()) {
      const std::string& line = lines[*bad - done];
      const std::vector<std::string_view> tokens = split(line);
      if (tokens.size() != properties)
        throw InputError(source + ": splat " + std::to_string(*bad) + ": " + std::to_string(tokens.size()) + " numbers, the header has " +
                         std::to_string(properties) + " properties");
      std::string problem;
      for (std::size_t i = 0; i < properties; ++i)
        if (!parse_token(tokens[i], header.properties[i].type, problem))
          throw InputError(splat_where(source, *bad, header.properties[i]) + ": '" + runtime::excerpt(tokens[i]) + "' " + problem);
    }
    for (const std::string& line : output) pending.write(line);
    done += count;
    io::throw_if_interrupted();
    progress(done, header.vertices);
  }
  for (char c; file.get(c);)
    if (c != ' ' && c != '\t' && c != '\n') throw InputError(source + ": data after the last splat");
}

}  // namespace

Summary transform_file(const std::string& in, const std::string& out, const Transform& transform, int threads,
                       const std::function<void(std::uint64_t, std::uint64_t)>& progress) {
  if (!(transform.scale > 0) || !std::isfinite(transform.scale)) throw InputError("scale: must be a finite number above 0");
  std::ifstream file(in, std::ios::binary);
  if (!file) throw InputError(in + ": cannot open: " + std::strerror(errno));
  const ply::Header header = ply::read_header(file, in);
  const Layout layout = layout_of(header, in);
  if (header.format == ply::Format::kBinaryLittleEndian) {
    // A regular file's size says at once whether the data is whole.
    std::error_code ec;
    const auto size = std::filesystem::file_size(in, ec);
    const std::uint64_t expected = header.text.size() + header.vertices * header.record_bytes;
    if (!ec && std::filesystem::is_regular_file(in, ec) && size != expected)
      throw InputError(in + ": " + std::to_string(size) + " bytes, but the header says " + std::to_string(expected) + " (" +
                       std::to_string(header.vertices) + " splats of " + std::to_string(header.record_bytes) + " bytes)" +
                       (size < expected ? ": truncated" : ": bytes after the last splat"));
  }
  const SplatMath math(layout, transform, header.vertices);
  io::PendingFile pending(out);
  pending.write(header.text);
  if (header.format == ply::Format::kAscii) {
    transform_ascii(file, pending, header, layout, math, in, threads, progress);
  } else {
    transform_binary(file, pending, header, layout, math, in, threads, progress);
  }
  pending.commit();
  return Summary{header.vertices, layout.degree, header.format == ply::Format::kAscii};
}

}  // namespace zhf::splat
