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

#include "format_io.h"
#include "formats.h"
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

}  // namespace

namespace {

int sh_value_bytes(FileFormat format);

// Per band (f_dc is band 0), the sum of the squared coefficients of every splat and channel:
// the energy zhf analyze sums, added in file order so the sums do not depend on the threads.
void add_band_energy(const double* records, std::uint64_t count, const Canonical& c, std::vector<double>& energy) {
  const int per_channel = c.rest / 3;
  for (std::uint64_t s = 0; s < count; ++s) {
    const double* v = records + s * c.size();
    for (int ch = 0; ch < 3; ++ch) {
      energy[0] += v[Canonical::kDc + ch] * v[Canonical::kDc + ch];
      for (int k = 0; k < per_channel; ++k) {
        const double x = v[Canonical::kRest + ch * per_channel + k];
        energy[Canonical::band(k)] += x * x;
      }
    }
  }
}

// The relative L2 error of keeping bands 0..kept, from the band energies.
double kept_bands_error(const std::vector<double>& energy, int kept) {
  double total = 0, dropped = 0;
  for (std::size_t l = 0; l < energy.size(); ++l) (int(l) > kept ? dropped : total) += energy[l];
  total += dropped;
  return total > 0 ? std::sqrt(dropped / total) : 0;
}

// The largest |colour change| of one splat's channel when bands above `kept` are left out, over
// kColourErrorDirections view directions (a golden-angle spiral, evaluated in the convention's
// basis): the rendered colour is the SH's value in the view direction.
class DroppedColour {
 public:
  DroppedColour(int degree, int kept, const runtime::Convention& convention) : first_(kept + 1) {
    const int n2 = (degree + 1) * (degree + 1), from = first_ * first_;
    width_ = n2 - from;
    const runtime::Matrix3 m = convention.from_zhf();
    const double golden = runtime::kPi * (3 - std::sqrt(5.0));
    std::vector<double> y(n2);
    for (int i = 0; i < kColourErrorDirections; ++i) {
      const double z = 1 - (2 * i + 1.0) / kColourErrorDirections, r = std::sqrt(1 - z * z);
      const double u[3] = {r * std::cos(golden * i), r * std::sin(golden * i), z};
      double w[3];
      for (int k = 0; k < 3; ++k) w[k] = m[3 * k] * u[0] + m[3 * k + 1] * u[1] + m[3 * k + 2] * u[2];
      runtime::eval_sh(degree + 1, w, y.data());
      basis_.insert(basis_.end(), y.begin() + from, y.end());
    }
  }
  double largest(const double* records, std::size_t count, const Canonical& c) const {
    if (width_ == 0) return 0;
    const int per_channel = c.rest / 3, skip = first_ * first_ - 1;  // f_rest index of the first dropped coefficient
    double most = 0;
    for (std::size_t s = 0; s < count; ++s)
      for (int ch = 0; ch < 3; ++ch) {
        const double* f = records + s * c.size() + Canonical::kRest + ch * per_channel + skip;
        for (int d = 0; d < kColourErrorDirections; ++d) {
          const double* b = &basis_[std::size_t(d) * width_];
          double e = 0;
          for (int k = 0; k < width_; ++k) e += f[k] * b[k];
          most = std::max(most, std::abs(e));
        }
      }
    return most;
  }

 private:
  int first_, width_ = 0;
  std::vector<double> basis_;  // direction-major, the dropped coefficients of each
};

// A record of `from`'s degree as one of `to`'s (lower or equal): the bands above left out.
void keep_bands(const double* in, const Canonical& from, double* out, const Canonical& to) {
  std::copy(in, in + Canonical::kRest, out);
  const int per_from = from.rest / 3, per_to = to.rest / 3;
  for (int ch = 0; ch < 3; ++ch)
    std::copy(in + Canonical::kRest + ch * per_from, in + Canonical::kRest + ch * per_from + per_to, out + Canonical::kRest + ch * per_to);
  std::copy(in + from.opacity(), in + from.size(), out + to.opacity());
}

// The filters (Filters) on read records: the position judged is where the transform puts it,
// s R A p + t with A the file's axes in the .ply's (the value written, up to rounding).
class Selection {
 public:
  Selection(const Filters& filters, const runtime::Matrix3& axes, const Transform& t) : f_(filters), t_(t.translation) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) m_[3 * i + j] += t.scale * t.r[3 * i + k] * axes[3 * k + j];
  }
  // Moves the kept ones of `count` records to the front, in order, and returns how many; the
  // others are counted by their first reason.
  std::uint64_t keep(double* records, std::uint64_t count, const Canonical& c) {
    std::uint64_t kept = 0;
    for (std::uint64_t s = 0; s < count; ++s) {
      double* v = records + s * c.size();
      if (std::uint64_t* why = reason(v, c)) {
        ++*why;
      } else {
        if (kept != s) std::copy(v, v + c.size(), records + kept * c.size());
        ++kept;
      }
    }
    return kept;
  }
  std::uint64_t nonfinite = 0, outside = 0, transparent = 0;

 private:
  std::uint64_t* reason(const double* v, const Canonical& c) {
    if (f_.drop_nonfinite && !std::all_of(v, v + c.size(), [](double x) { return std::isfinite(x); })) return &nonfinite;
    double p[3];
    for (int i = 0; i < 3; ++i) p[i] = m_[3 * i] * v[0] + m_[3 * i + 1] * v[1] + m_[3 * i + 2] * v[2] + t_[i];
    if (const auto& b = f_.crop_box; b && !(p[0] >= (*b)[0] && p[1] >= (*b)[1] && p[2] >= (*b)[2] && p[0] <= (*b)[3] && p[1] <= (*b)[4] && p[2] <= (*b)[5]))
      return &outside;
    if (const auto& b = f_.crop_sphere) {
      const double d[3] = {p[0] - (*b)[0], p[1] - (*b)[1], p[2] - (*b)[2]};
      if (!(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] <= (*b)[3] * (*b)[3])) return &outside;
    }
    if (f_.min_opacity && !(sigmoid(v[c.opacity()]) >= *f_.min_opacity)) return &transparent;
    return nullptr;
  }
  const Filters& f_;
  std::array<double, 9> m_{};
  std::array<double, 3> t_;
};

// The SH degree to write: --sh-degree, the smallest within --max-sh-error (one pass over the
// scene first), or the scene's; then what the output format holds.
struct DegreeChoice {
  int kept = 0, dropped_by_format = -1;
  std::vector<double> energy;  // per band, when a pass measured it
};

DegreeChoice choose_degree(const std::string& in, const std::string& out, FileFormat from, FileFormat to, const Formats& formats,
                           const SceneReader& reader, Selection& selection) {
  DegreeChoice choice;
  const int degree = reader.degree();
  choice.kept = degree;
  if (formats.sh_degree && *formats.sh_degree > degree)
    throw InputError(in + ": SH degree " + std::to_string(degree) + "; --sh-degree " + std::to_string(*formats.sh_degree) + " asks for more");
  // The first pass, for --max-sh-error's energies and the filters' count (of the splats kept).
  if (formats.max_sh_error || formats.filters.any()) {
    const std::unique_ptr<SceneReader> pass = open_reader(from, in, formats);
    const Canonical c(degree);
    std::vector<double> records;
    if (formats.max_sh_error) choice.energy.assign(degree + 1, 0);
    for (std::uint64_t done = 0; done < pass->splats();) {
      const std::uint64_t count = std::min(kChunkSplats, pass->splats() - done);
      records.resize(count * c.size());
      pass->read(done, count, records.data());
      const std::uint64_t kept = formats.filters.any() ? selection.keep(records.data(), count, c) : count;
      if (formats.max_sh_error) add_band_energy(records.data(), kept, c, choice.energy);
      done += count;
      io::throw_if_interrupted();
    }
    pass->finish();
  }
  if (formats.sh_degree) {
    choice.kept = *formats.sh_degree;
  } else if (formats.max_sh_error) {
    choice.kept = 0;
    while (choice.kept < degree && kept_bands_error(choice.energy, choice.kept) > *formats.max_sh_error) ++choice.kept;
  }
  const int most = file_format_max_sh_degree(to);
  if (choice.kept > most) {
    // .splat keeps colour only and has always dropped degrees 1..3 with a note; degree 4, and any
    // degree asked for, is refused rather than dropped.
    if (most == 0 && choice.kept < kMaxSplatShDegree && !formats.sh_degree && !formats.max_sh_error) {
      choice.dropped_by_format = choice.kept;
      choice.kept = 0;
    } else {
      throw InputError(out + ": " + file_format_extension(to) + " holds SH degree " + std::to_string(most) + " at most; the scene has " +
                       std::to_string(choice.kept) + ": give --sh-degree " + std::to_string(most));
    }
  }
  return choice;
}

// Any pair of formats but .ply to .ply, and any scene whose bands are cut: through the canonical
// record, a chunk at a time. A file's own axes (formats.h: axes()) are changes of axes at the
// edges: into the .ply's after reading, the transform, back out before writing.
Summary convert(const std::string& in, const std::string& out, FileFormat from, FileFormat to, const Formats& formats,
                const Transform& transform, int threads, const std::function<void(std::uint64_t, std::uint64_t)>& progress) {
  const std::unique_ptr<SceneReader> reader = open_reader(from, in, formats);
  const bool filtering = formats.filters.any();
  // Its counts are the first pass's; the second judges again to leave the same splats out.
  Selection selection(formats.filters, reader->axes(), transform);
  DegreeChoice choice = choose_degree(in, out, from, to, formats, *reader, selection);
  const int degree = reader->degree(), kept = choice.kept;
  const bool cut = kept < degree && choice.dropped_by_format < 0;
  Summary summary;
  summary.splats = reader->splats();
  summary.nonfinite = selection.nonfinite;
  summary.outside = selection.outside;
  summary.transparent = selection.transparent;
  summary.sh_degree = degree;
  summary.in = from;
  summary.out = to;
  summary.kept_degree = kept;
  summary.dropped_degree = choice.dropped_by_format;
  summary.antialiased = reader->antialiased();
  summary.antialiasing_dropped = reader->antialiased() && to != FileFormat::kSpz;
  summary.spz_axes_source = reader->axes_source();
  WriteOptions options;
  options.degree = kept;
  options.splats = summary.written();
  options.spz_version = formats.spz_version;
  options.spz_axes = formats.spz_axes;
  options.spz_as_reference = formats.spz_as_reference;
  options.antialiased = reader->antialiased();
  options.keep_order = formats.keep_order;
  if (!reader->extensions().empty()) {
    const SpzExtension& first = reader->extensions().front();
    if (formats.drop_spz_extensions) {
      summary.dropped_extensions = int(reader->extensions().size());
    } else if (to == FileFormat::kSpz) {
      options.spz_extensions = reader->extensions();
      summary.carried_extensions = int(reader->extensions().size());
    } else {
      char type[16];
      std::snprintf(type, sizeof type, "0x%08x", first.type);
      throw InputError(in + ": extension record " + type + " (" + std::to_string(first.payload.size()) + " bytes): " +
                       file_format_extension(to) + " cannot carry it; give --drop-spz-extensions to convert without it");
    }
  }
  if (to == FileFormat::kSpz)
    summary.spz_axes_source = std::string(formats.spz_axes == SpzAxes::kRub ? "rub" : "raw") + " (written)" +
                              (formats.spz_as_reference ? ", as the reference library writes it" : "");
  const Canonical whole(degree), written(kept);
  const ply::Header header = canonical_header(kept, summary.written());
  const Layout layout = layout_of(header, "canonical record");
  io::PendingFile pending(out);
  const std::unique_ptr<SceneWriter> writer = open_writer(to, pending, options);
  Transform into_ply, out_of_ply;
  into_ply.r = reader->axes();
  out_of_ply.r = writer->axes();
  into_ply.convention = out_of_ply.convention = transform.convention;
  const SplatMath math(layout, transform);
  std::optional<SplatMath> into, out_of;
  if (into_ply.r != runtime::kIdentity) into.emplace(layout, into_ply, Orientation::kAxes);
  if (out_of_ply.r != runtime::kIdentity) out_of.emplace(layout, out_of_ply, Orientation::kAxes);
  const runtime::Convention& convention = transform.convention ? *transform.convention : *runtime::find_convention("3dgs");
  const std::optional<DroppedColour> colour = cut ? std::optional<DroppedColour>(std::in_place, degree, kept, convention) : std::nullopt;
  const bool measure_energy = cut && choice.energy.empty();
  if (measure_energy) choice.energy.assign(degree + 1, 0);
  const std::size_t size = written.size();
  std::vector<double> records, read;
  std::mutex colour_mutex;
  double colour_error = 0;  // a maximum: the same whichever worker finds it
  std::uint64_t written_splats = 0;
  for (std::uint64_t done = 0; done < reader->splats();) {
    const std::uint64_t count = std::min(kChunkSplats, reader->splats() - done);
    std::uint64_t n = count;  // the chunk's splats written
    if (kept == degree) {
      records.resize(count * size);
      reader->read(done, count, records.data());
      if (filtering) n = selection.keep(records.data(), count, whole);
    } else {
      read.resize(count * whole.size());
      reader->read(done, count, read.data());
      if (filtering) n = selection.keep(read.data(), count, whole);
      records.resize(n * size);
      if (measure_energy) add_band_energy(read.data(), n, whole, choice.energy);
      runtime::parallel_chunks(n, threads, [&](std::size_t begin, std::size_t end) {
        if (colour) {
          const double e = colour->largest(&read[begin * whole.size()], end - begin, whole);
          const std::lock_guard<std::mutex> lock(colour_mutex);
          colour_error = std::max(colour_error, e);
        }
        for (std::size_t s = begin; s < end; ++s) keep_bands(&read[s * whole.size()], whole, &records[s * size], written);
      });
    }
    runtime::parallel_chunks(n, threads, [&](std::size_t begin, std::size_t end) {
      if (into) into->apply_many(&records[begin * size], end - begin, size);
      math.apply_many(&records[begin * size], end - begin, size);
      if (out_of) out_of->apply_many(&records[begin * size], end - begin, size);
    });
    // The first pass counted what the output's header holds: a file changed since is refused.
    if (written_splats + n > summary.written()) throw InputError(in + ": changed while it was read");
    if (n > 0) writer->write(n, records.data());
    written_splats += n;
    done += count;
    io::throw_if_interrupted();
    progress(done, reader->splats());
  }
  reader->finish();
  if (written_splats != summary.written()) throw InputError(in + ": changed while it was read");
  writer->finish();
  pending.commit();
  summary.clamped = writer->clamped();
  for (int band = 0; band <= kept; ++band) summary.sh_error[band] = writer->sh_error()[band];
  summary.left_out = reader->left_out(to);
  if (cut) {
    summary.dropped_energy_error = kept_bands_error(choice.energy, kept);
    summary.dropped_colour_error = colour_error;
    summary.dropped_bytes = reader->splats() * 3 * std::uint64_t(whole.rest / 3 - written.rest / 3) * sh_value_bytes(to);
  }
  return summary;
}

}  // namespace

namespace {

struct FormatName {
  FileFormat format;
  const char* name;
  const char* extension;
  int max_sh_degree;
  int sh_value_bytes;  // one SH coefficient of one channel, as stored before any compression
};
constexpr FormatName kFormatNames[] = {{FileFormat::kPly, "ply", ".ply", kMaxSplatShDegree, 4},
                                       {FileFormat::kCompressedPly, "compressed-ply", ".compressed.ply", 3, 1},
                                       {FileFormat::kSplat, "splat", ".splat", 0, 0},
                                       {FileFormat::kSpz, "spz", ".spz", kMaxSplatShDegree, 1},
                                       {FileFormat::kGlb, "glb", ".glb", 3, 4},
                                       {FileFormat::kSog, "sog", ".sog", 3, 0}};

const FormatName& named(FileFormat format) {
  for (const FormatName& f : kFormatNames)
    if (f.format == format) return f;
  return kFormatNames[0];
}

int sh_value_bytes(FileFormat format) { return named(format).sh_value_bytes; }

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

}  // namespace

bool parse_file_format(const std::string& name, FileFormat& format) {
  for (const FormatName& f : kFormatNames)
    if (name == f.name) {
      format = f.format;
      return true;
    }
  return false;
}

int file_format_max_sh_degree(FileFormat format) { return named(format).max_sh_degree; }

bool parse_spz_axes(const std::string& name, SpzAxes& axes) {
  if (name != "raw" && name != "rub") return false;
  axes = name == "rub" ? SpzAxes::kRub : SpzAxes::kRaw;
  return true;
}
const char* file_format_extension(FileFormat format) { return named(format).extension; }

std::string file_format_names() {
  std::vector<std::string> names;
  for (const FormatName& f : kFormatNames) names.push_back(f.name);
  return runtime::name_list(names);
}

bool file_format_of(const std::string& path, FileFormat& format) {
  std::string lower = std::filesystem::path(path).filename().string();
  for (char& c : lower) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  if (lower == "meta.json") {  // a SOG's files beside their meta.json
    format = FileFormat::kSog;
    return true;
  }
  std::size_t best = 0;
  for (const FormatName& f : kFormatNames) {
    const std::string extension = f.extension;
    if (lower.size() > extension.size() && extension.size() > best && lower.compare(lower.size() - extension.size(), extension.size(), extension) == 0) {
      format = f.format;
      best = extension.size();
    }
  }
  return best > 0;
}

Summary transform_file(const std::string& in, const std::string& out, const Transform& transform, int threads,
                       const std::function<void(std::uint64_t, std::uint64_t)>& progress, const Formats& formats) {
  if (!(transform.scale > 0) || !std::isfinite(transform.scale)) throw InputError("scale: must be a finite number above 0");
  // A name without a known extension (a device, a pipe) is a .ply, the format zhf splat began with.
  FileFormat from = FileFormat::kPly, to = FileFormat::kPly;
  if (formats.in) from = *formats.in;
  else if (file_format_of(in, from) && from == FileFormat::kPly && looks_compressed(in)) from = FileFormat::kCompressedPly;
  if (formats.out) to = *formats.out;
  else file_format_of(out, to);
  if (to == FileFormat::kSog) {
    if (formats.filters.any())
      throw InputError(out + ": a .sog is written from a .sog whole (its palette turned once); filter into another format");
    if (from != FileFormat::kSog)
      throw InputError(out + ": zhf writes a .sog from a .sog only (turning its palette); convert " + std::string(file_format_extension(from)) +
                       " to .ply, .spz, .glb, compressed .ply or .splat");
    Summary summary;
    summary.in = summary.out = FileFormat::kSog;
    return transform_sog(in, out, transform, formats, summary);
  }
  if (from != FileFormat::kPly || to != FileFormat::kPly || formats.sh_degree || formats.max_sh_error || formats.filters.any())
    return convert(in, out, from, to, formats, transform, threads, progress);
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
  info.format = formats.in ? *formats.in : FileFormat::kPly;
  if (!formats.in && file_format_of(in, info.format) && info.format == FileFormat::kPly && looks_compressed(in))
    info.format = FileFormat::kCompressedPly;
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
