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
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string_view>
#include <vector>

#include "convert.h"
#include "format_io.h"
#include "registry.h"
#include "scene_io.h"
#include "splat_math.h"
#include "zhf/dispatch/checks.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/numbers.h"
#include "zhf/io/ply.h"
#include "zhf/io/signals.h"
#include "zhf/runtime/enum_names.h"
#include "zhf/runtime/orthogonal.h"
#include "zhf/runtime/parallel.h"
#include "zhf/runtime/rotator.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/splat/limits.h"

namespace zhf::splat {
namespace {

namespace ply = io::ply;
using io::InputError;

// Splats a worker converts and transforms at a time (splat_math.h's apply_many): their values fit
// in cache (64 x 62 doubles at degree 3), and the SH of many go through one call.
constexpr std::size_t kTransformBlock = 64;

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
    std::future<std::uint64_t> io = runtime::start_beside([&, next, other_holds_output] {
      if (other_holds_output) pending.write(reinterpret_cast<const char*>(other.data()), other.size());
      return next < header.vertices ? read_chunk(other, next) : std::uint64_t(0);
    });
    FirstFailure failure;
    runtime::parallel_chunks(count, threads, [&](std::size_t begin, std::size_t end) {
      // kTransformBlock splats at a time: their values in double, transformed together.
      std::vector<double> v(kTransformBlock * properties);
      std::vector<float> floats(all_float ? kTransformBlock * properties : 0);
      for (std::size_t first = begin; first < end; first += kTransformBlock) {
        const std::size_t part = std::min(kTransformBlock, end - first);
        unsigned char* records = chunk.data() + first * bytes;
        if (all_float) {
          // The common file: every property float32. Values checked and converted in one loop
          // each, and all written back (an unchanged float survives float -> double -> float
          // exactly).
          std::memcpy(floats.data(), records, part * bytes);
          if (!dispatch::all_finite(floats.data(), part * properties))
            for (std::size_t s = 0; s < part; ++s)
              if (!dispatch::all_finite(floats.data() + s * properties, properties)) {
                failure.note(done + first + s);
                return;
              }
          for (std::size_t i = 0; i < part * properties; ++i) v[i] = floats[i];
        } else {
          for (std::size_t s = 0; s < part; ++s)
            for (std::size_t i = 0; i < properties; ++i) {
              v[s * properties + i] = ply::read_binary(records + s * bytes, header.properties[i]);
              if (!std::isfinite(v[s * properties + i])) {
                failure.note(done + first + s);
                return;
              }
            }
        }
        math.apply_many(v.data(), part, properties);
        if (all_float) {
          for (std::size_t i = 0; i < part * properties; ++i) floats[i] = static_cast<float>(v[i]);
          std::memcpy(records, floats.data(), part * bytes);
        } else {
          for (std::size_t s = 0; s < part; ++s)
            for (int i : layout.changed) ply::write_binary(records + s * bytes, header.properties[i], v[s * properties + i]);
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

void transform_ascii(std::istream& file, io::PendingFile& pending, const ply::Header& header, const Layout& layout,
                     const SplatMath& math, const std::string& source, int threads,
                     const std::function<void(std::uint64_t, std::uint64_t)>& progress) {
  const std::size_t properties = header.properties.size();
  std::vector<bool> changed(properties, false);
  for (int i : layout.changed) changed[i] = true;
  std::vector<std::string> lines;
  std::vector<std::string> output;
  std::vector<char> buffer;
  for (std::uint64_t done = 0; done < header.vertices;) {
    const std::uint64_t count = std::min(kChunkSplats, header.vertices - done);
    lines.resize(count);
    for (std::uint64_t s = 0; s < count; ++s) lines[s] = ply::read_ascii_line(file, buffer, source, done + s, header.vertices);
    output.assign(count, std::string());
    FirstFailure failure;
    runtime::parallel_chunks(count, threads, [&](std::size_t begin, std::size_t end) {
      std::vector<double> v(properties);
      for (std::size_t s = begin; s < end; ++s) {
        const std::vector<std::string_view> tokens = ply::split_ascii(lines[s]);
        if (!ply::parse_ascii(tokens, header, v.data())) {
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
      std::vector<double> v(properties);
      ply::parse_ascii_or_throw(lines[*bad - done], header, source, *bad, v.data());
    }
    for (const std::string& line : output) pending.write(line);
    done += count;
    io::throw_if_interrupted();
    progress(done, header.vertices);
  }
  ply::check_ascii_end(file, source);
}

// A .ply whose header starts with the element "chunk": PlayCanvas's compressed layout.
bool looks_compressed(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  try {
    const ply::Header header = ply::read_header_elements(file, path);
    return header.elements.front().name == "chunk";
  } catch (const InputError&) {
    return false;  // the .ply reader says what is wrong
  }
}

FileFormat input_format(const std::string& in, const Formats& formats) {
  // A name without a known extension (a device, a pipe) is a .ply, the format zhf splat began with.
  FileFormat from = FileFormat::kPly;
  if (formats.in) from = *formats.in;
  else if (file_format_of(in, from) && from == FileFormat::kPly && looks_compressed(in)) from = FileFormat::kCompressedPly;
  return from;
}

}  // namespace

Summary transform_file(const std::string& in, const std::string& out, const Transform& transform, int threads,
                       const std::function<void(std::uint64_t, std::uint64_t)>& progress, const Formats& formats) {
  return transform_files({in}, out, transform, threads, progress, formats);
}

Summary transform_files(const std::vector<std::string>& ins, const std::string& out, const Transform& transform, int threads,
                        const std::function<void(std::uint64_t, std::uint64_t)>& progress, const Formats& formats) {
  if (!(transform.scale > 0) || !std::isfinite(transform.scale)) throw InputError("scale: must be a finite number above 0");
  if (ins.empty() || ins.size() > std::size_t(kMaxMergedScenes))
    throw InputError("--in: " + std::to_string(ins.size()) + " scenes; give 1 to " + std::to_string(kMaxMergedScenes));
  std::vector<Input> inputs;
  for (const std::string& in : ins) inputs.push_back({in, input_format(in, formats)});
  const std::string& in = ins.front();
  const FileFormat from = inputs.front().format;
  FileFormat to = FileFormat::kPly;
  if (formats.out) to = *formats.out;
  else file_format_of(out, to);
  // A .sog turned whole into a .sog: its palette turned once, its codebooks and labels kept.
  if (to == FileFormat::kSog && from == FileFormat::kSog && inputs.size() == 1 && !formats.filters.any() && !formats.sh_degree &&
      !formats.max_sh_error) {
    if (std::filesystem::path(out).filename() == "meta.json") throw InputError(out + ": zhf writes a bundled .sog; name the output .sog");
    Summary summary;
    summary.in = summary.out = FileFormat::kSog;
    return transform_sog(in, out, transform, formats, summary);
  }
  if (to == FileFormat::kSog && std::filesystem::path(out).filename() == "meta.json")
    throw InputError(out + ": zhf writes a bundled .sog; name the output .sog");
  if (inputs.size() > 1 || from != FileFormat::kPly || to != FileFormat::kPly || formats.sh_degree || formats.max_sh_error || formats.filters.any())
    return convert(inputs, out, to, formats, transform, threads, progress);
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
  const SplatMath math(layout, transform);
  io::PendingFile pending(out);
  pending.write(header.text);
  if (header.format == ply::Format::kAscii) {
    transform_ascii(file, pending, header, layout, math, in, threads, progress);
  } else {
    transform_binary(file, pending, header, layout, math, in, threads, progress);
  }
  pending.commit();
  Summary summary;
  summary.splats = header.vertices;
  summary.sh_degree = layout.degree;
  summary.ascii = header.format == ply::Format::kAscii;
  return summary;
}

SceneInfo describe_file(const std::string& in, const Formats& formats) {
  SceneInfo info;
  info.format = input_format(in, formats);
  const std::unique_ptr<SceneReader> reader = open_reader(info.format, in, formats);
  info.splats = reader->splats();
  info.sh_degree = reader->degree();
  info.axes_source = reader->axes_source();
  info.antialiased = reader->antialiased();
  for (const SpzExtension& e : reader->extensions()) info.extension_types.push_back(e.type);
  const Canonical c(reader->degree());
  const runtime::Matrix3& axes = reader->axes();
  std::vector<double> records;
  info.low.fill(std::numeric_limits<double>::infinity());
  info.high.fill(-std::numeric_limits<double>::infinity());
  for (std::uint64_t done = 0; done < info.splats;) {
    const std::uint64_t count = std::min(kChunkSplats, info.splats - done);
    records.resize(count * c.size());
    reader->read(done, count, records.data());
    for (std::uint64_t s = 0; s < count; ++s) {
      const double* p = records.data() + s * c.size() + Canonical::kPosition;
      for (int i = 0; i < 3; ++i) {
        const double x = axes[3 * i] * p[0] + axes[3 * i + 1] * p[1] + axes[3 * i + 2] * p[2];
        info.low[i] = std::min(info.low[i], x);
        info.high[i] = std::max(info.high[i], x);
      }
    }
    done += count;
    io::throw_if_interrupted();
  }
  reader->finish();
  if (info.splats == 0) info.low = info.high = {};
  return info;
}

}  // namespace zhf::splat
