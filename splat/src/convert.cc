#include "convert.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>

#include "format_io.h"
#include "registry.h"
#include "scene_io.h"
#include "splat_math.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/limits.h"
#include "zhf/io/ply.h"
#include "zhf/io/signals.h"
#include "zhf/runtime/orthogonal.h"
#include "zhf/runtime/parallel.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/splat/limits.h"

namespace zhf::splat {
namespace {

namespace ply = io::ply;
using io::InputError;

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

// A record of `from`'s degree as one of `to`'s: bands above `to`'s left out, bands above `from`'s zero.
void change_degree(const double* in, const Canonical& from, double* out, const Canonical& to) {
  std::copy(in, in + Canonical::kRest, out);
  const int per_from = from.rest / 3, per_to = to.rest / 3, common = std::min(per_from, per_to);
  for (int ch = 0; ch < 3; ++ch) {
    double* rest = out + Canonical::kRest + ch * per_to;
    std::copy(in + Canonical::kRest + ch * per_from, in + Canonical::kRest + ch * per_from + common, rest);
    std::fill(rest + common, rest + per_to, 0.0);
  }
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

// Several scenes read one after another as one: each input's records turned from its own axes
// into the .ply's (so the merged scene's axes are the .ply's) and widened to the highest SH
// degree among them, the bands it lacks zero (its colour unchanged).
class MergedReader : public SceneReader {
 public:
  MergedReader(const std::vector<Input>& inputs, const Formats& formats, const runtime::Convention* convention) {
    for (const Input& input : inputs) {
      Part part;
      part.name = input.path;
      part.reader = open_reader(input.format, input.path, formats);
      part.first = splats_;
      splats_ += part.reader->splats();
      if (splats_ > io::kMaxPlyVertices)
        throw InputError(input.path + ": the inputs hold " + std::to_string(splats_) + " splats up to it, more than a merged scene's " +
                         std::to_string(io::kMaxPlyVertices));
      degree_ = std::max(degree_, part.reader->degree());
      for (const SpzExtension& e : part.reader->extensions()) extensions_.push_back(e);
      parts_.push_back(std::move(part));
    }
    antialiased_ = std::all_of(parts_.begin(), parts_.end(), [](const Part& p) { return p.reader->antialiased(); });
    for (Part& part : parts_) {
      if (part.reader->axes() == runtime::kIdentity) continue;
      part.header = canonical_header(part.reader->degree(), 0);
      part.layout = layout_of(part.header, "canonical record");
      part.to_ply.r = part.reader->axes();
      part.to_ply.convention = convention;
      part.into_ply = std::make_unique<SplatMath>(part.layout, part.to_ply, Orientation::kAxes);
    }
  }

  void read(std::uint64_t first, std::uint64_t count, double* records) override {
    const Canonical whole(degree_);
    while (count > 0) {
      while (first >= parts_[next_].first + parts_[next_].reader->splats()) parts_[next_++].reader->finish();
      Part& part = parts_[next_];
      const Canonical own(part.reader->degree());
      const std::uint64_t n = std::min(count, part.first + part.reader->splats() - first);
      buffer_.resize(n * own.size());
      part.reader->read(first - part.first, n, buffer_.data());
      if (part.into_ply) part.into_ply->apply_many(buffer_.data(), n, own.size());
      for (std::uint64_t s = 0; s < n; ++s) change_degree(&buffer_[s * own.size()], own, records + s * whole.size(), whole);
      first += n;
      count -= n;
      records += n * whole.size();
    }
  }

  void finish() override {
    for (; next_ < parts_.size(); ++next_) parts_[next_].reader->finish();
  }

  std::vector<std::string> left_out(FileFormat to) const override {
    std::vector<std::string> phrases;
    for (const Part& part : parts_) {
      for (const std::string& phrase : part.reader->left_out(to)) phrases.push_back(part.name + ": " + phrase);
      if (part.reader->antialiased() && !antialiased_) phrases.push_back(part.name + ": its antialiasing mark (not every input has it)");
    }
    return phrases;
  }

 private:
  struct Part {
    std::string name;
    std::unique_ptr<SceneReader> reader;
    std::uint64_t first = 0;  // its first splat's index in the merged scene
    io::ply::Header header;   // of its records, where its axes are not the .ply's
    Layout layout;
    Transform to_ply;
    std::unique_ptr<SplatMath> into_ply;
  };
  std::vector<Part> parts_;
  std::size_t next_ = 0;  // the part being read
  std::vector<double> buffer_;
};

// What convert reads, opened anew for each pass: one input through its format's reader, several
// through a MergedReader.
struct Scene {
  Scene(const std::vector<Input>& inputs, const Formats& formats, const runtime::Convention* convention)
      : inputs(inputs), formats(formats), convention(convention), name(inputs.size() == 1 ? inputs[0].path : "the merged inputs") {}
  std::unique_ptr<SceneReader> open() const {
    if (inputs.size() == 1) return open_reader(inputs[0].format, inputs[0].path, formats);
    return std::make_unique<MergedReader>(inputs, formats, convention);
  }
  const std::vector<Input>& inputs;
  const Formats& formats;
  const runtime::Convention* convention;
  std::string name;  // for messages
};

// The SH degree to write: --sh-degree, the smallest within --max-sh-error (one pass over the
// scene first), or the scene's; then what the output format holds.
struct DegreeChoice {
  int kept = 0, dropped_by_format = -1;
  std::vector<double> energy;  // per band, when a pass measured it
};

DegreeChoice choose_degree(const Scene& scene, const std::string& out, FileFormat to, const Formats& formats, const SceneReader& reader,
                           Selection& selection) {
  DegreeChoice choice;
  const int degree = reader.degree();
  choice.kept = degree;
  if (formats.sh_degree && *formats.sh_degree > degree)
    throw InputError(scene.name + ": SH degree " + std::to_string(degree) + "; --sh-degree " + std::to_string(*formats.sh_degree) + " asks for more");
  // The first pass, for --max-sh-error's energies and the filters' count (of the splats kept).
  if (formats.max_sh_error || formats.filters.any()) {
    const std::unique_ptr<SceneReader> pass = scene.open();
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
// record, a chunk at a time. A file's own axes (scene_io.h: axes()) are changes of axes at the
// edges: into the .ply's after reading, the transform, back out before writing.
}  // namespace

Summary convert(const std::vector<Input>& inputs, const std::string& out, FileFormat to, const Formats& formats, const Transform& transform,
                int threads, const std::function<void(std::uint64_t, std::uint64_t)>& progress) {
  const Scene scene(inputs, formats, transform.convention);
  const std::unique_ptr<SceneReader> reader = scene.open();
  const FileFormat from = inputs.front().format;
  const bool filtering = formats.filters.any();
  // Its counts are the first pass's; the second judges again to leave the same splats out.
  Selection selection(formats.filters, reader->axes(), transform);
  DegreeChoice choice = choose_degree(scene, out, to, formats, *reader, selection);
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
  options.seed = formats.sog_seed;
  options.threads = threads;
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
      throw InputError(scene.name + ": extension record " + type + " (" + std::to_string(first.payload.size()) + " bytes): " +
                       file_format_extension(to) + " cannot carry it; give --drop-spz-extensions to convert without it");
    }
  }
  if (to == FileFormat::kSpz)
    summary.spz_axes_source = std::string(formats.spz_axes == SpzAxes::kRub ? "rub" : "raw") + " (written)" +
                              (formats.spz_as_reference ? ", as the reference library writes it" : "");
  const Canonical whole(degree), written(kept);
  const ply::Header header = canonical_header(kept, summary.written());
  const Layout layout = layout_of(header, "canonical record");
  // WebP holds no empty image.
  if (to == FileFormat::kSog && summary.written() == 0) throw InputError(out + ": no splats to write, and a .sog holds at least one");
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
        for (std::size_t s = begin; s < end; ++s) change_degree(&read[s * whole.size()], whole, &records[s * size], written);
      });
    }
    runtime::parallel_chunks(n, threads, [&](std::size_t begin, std::size_t end) {
      if (into) into->apply_many(&records[begin * size], end - begin, size);
      math.apply_many(&records[begin * size], end - begin, size);
      if (out_of) out_of->apply_many(&records[begin * size], end - begin, size);
    });
    // The first pass counted what the output's header holds: a file changed since is refused.
    if (written_splats + n > summary.written()) throw InputError(scene.name + ": changed while it was read");
    if (n > 0) writer->write(n, records.data());
    written_splats += n;
    done += count;
    io::throw_if_interrupted();
    progress(done, reader->splats());
  }
  reader->finish();
  if (written_splats != summary.written()) throw InputError(scene.name + ": changed while it was read");
  writer->finish();
  pending.commit();
  summary.clamped = writer->clamped();
  for (int band = 0; band <= kept; ++band) summary.sh_error[band] = writer->sh_error()[band];
  summary.left_out = reader->left_out(to);
  if (cut) {
    summary.dropped_energy_error = kept_bands_error(choice.energy, kept);
    summary.dropped_colour_error = colour_error;
    summary.dropped_bytes = reader->splats() * 3 * std::uint64_t(whole.rest / 3 - written.rest / 3) * format_row(to).sh_value_bytes;
  }
  return summary;
}

}  // namespace zhf::splat
