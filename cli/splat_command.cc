#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

#include "commands.h"
#include "options.h"
#include "transform_options.h"
#include "zhf/io/errors.h"
#include "zhf/io/rotation_text.h"
#include "zhf/runtime/conventions.h"
#include "zhf/runtime/errors.h"
#include "zhf/splat/limits.h"
#include "zhf/splat/scene.h"

namespace zhf::cli {
namespace {

struct SplatOptions {
  std::vector<std::string> in;  // several: merged into one output
  std::string out;
  TransformOptions transform;
  std::string translate, scale = "1", convention = "3dgs", threads = "0", format, in_format, spz_version = "4", spz_axes = "raw";
  std::string sh_degree, max_sh_error, crop_box, crop_sphere, min_opacity, seed = "1";
  bool identity = false, quiet = false, drop_spz_extensions = false, keep_order = false, info = false, spz_as_reference = false;
  bool drop_nonfinite = false;
};

template <std::size_t N>
std::array<double, N> numbers_option(const std::string& option, const std::string& text) {
  try {
    const std::vector<double> v = io::parse_numbers(text, N, option);
    std::array<double, N> a{};
    std::copy(v.begin(), v.end(), a.begin());
    return a;
  } catch (const io::InputError& e) {
    throw UsageError(e.what());
  }
}

// --drop-nonfinite, --crop-box, --crop-sphere, --min-opacity.
splat::Filters filter_options(const SplatOptions& o) {
  splat::Filters f;
  f.drop_nonfinite = o.drop_nonfinite;
  if (!o.crop_box.empty()) {
    f.crop_box = numbers_option<6>("--crop-box", o.crop_box);
    const std::array<double, 6>& b = *f.crop_box;
    for (int i = 0; i < 3; ++i)
      if (b[i] > b[3 + i])
        throw UsageError("--crop-box: x0 y0 z0 x1 y1 z1 with each low bound at most its high one; " + std::string(1, "xyz"[i]) + " runs " +
                         runtime::format_number(b[i]) + " to " + runtime::format_number(b[3 + i]));
  }
  if (!o.crop_sphere.empty()) {
    f.crop_sphere = numbers_option<4>("--crop-sphere", o.crop_sphere);
    if (!((*f.crop_sphere)[3] >= 0)) throw UsageError("--crop-sphere: x y z r with r >= 0; r is " + runtime::format_number((*f.crop_sphere)[3]));
  }
  if (!o.min_opacity.empty()) f.min_opacity = number_option("--min-opacity", o.min_opacity, 0, 1);
  return f;
}

std::optional<splat::FileFormat> format_option(const std::string& option, const std::string& name) {
  if (name.empty()) return std::nullopt;
  splat::FileFormat format;
  if (!splat::parse_file_format(name, format))
    throw UsageError(option + ": '" + runtime::excerpt(name) + "' is not " + splat::file_format_names());
  return format;
}

void spz_axes_options(const SplatOptions& o, splat::Formats& formats) {
  if (!splat::parse_spz_axes(o.spz_axes, formats.spz_axes)) throw UsageError("--spz-axes: '" + runtime::excerpt(o.spz_axes) + "' is not raw or rub");
  formats.spz_as_reference = o.spz_as_reference;
}

void describe_one(const std::string& in, const splat::Formats& formats);

// --info: what each scene holds, nothing written.
int describe(const SplatOptions& o) {
  if (!o.out.empty()) throw UsageError("--info: writes nothing; drop --out");
  if (transform_given(o.transform) || o.identity || !o.translate.empty() || o.scale != "1")
    throw UsageError("--info: transforms nothing; drop the rotation, --translate and --scale");
  if (filter_options(o).any()) throw UsageError("--info: describes the whole scene; drop the filters");
  splat::Formats formats;
  formats.in = format_option("--in-format", o.in_format);
  spz_axes_options(o, formats);
  for (const std::string& in : o.in) describe_one(in, formats);
  return kExitOk;
}

void describe_one(const std::string& in, const splat::Formats& formats) {
  const splat::SceneInfo info = splat::describe_file(in, formats);
  std::printf("%s: %s, %llu splats, SH degree %d\n", in.c_str(), splat::file_format_extension(info.format),
              (unsigned long long)info.splats, info.sh_degree);
  std::printf("bounds in the .ply's axes: x %.6g .. %.6g, y %.6g .. %.6g, z %.6g .. %.6g\n", info.low[0], info.high[0], info.low[1],
              info.high[1], info.low[2], info.high[2]);
  if (!info.axes_source.empty()) std::printf(".spz axes: %s\n", info.axes_source.c_str());
  if (info.format == splat::FileFormat::kSpz) {
    std::printf("antialiased: %s\n", info.antialiased ? "yes" : "no");
    std::string types;
    for (std::uint32_t t : info.extension_types) {
      char hex[16];
      std::snprintf(hex, sizeof hex, "0x%08x", t);
      types += (types.empty() ? "" : ", ") + std::string(hex);
    }
    std::printf("extension records: %zu%s\n", info.extension_types.size(), types.empty() ? "" : (" (" + types + ")").c_str());
  }
}

int run_splat(const SplatOptions& o) {
  if (o.info) return describe(o);
  if (o.out.empty()) throw UsageError("--out: required (or --info, which writes nothing)");
  const runtime::Convention* convention = runtime::find_convention(o.convention);
  if (!convention)
    throw UsageError("--convention: '" + runtime::excerpt(o.convention) + "' is not one of " + runtime::convention_names());
  splat::Transform t;
  // No rotation given: a conversion (translate and scale still apply). --identity says so
  // explicitly, and with a rotation it would drop it: refused.
  if (transform_given(o.transform)) {
    if (o.identity) throw UsageError("--identity: a rotation is given too; give one or the other");
    t.r = transform_matrix(o.transform, o.quiet);
  }
  t.scale = number_option("--scale", o.scale, splat::kMinSplatScale, splat::kMaxSplatScale);
  if (!o.translate.empty()) t.translation = numbers_option<3>("--translate", o.translate);
  t.convention = convention;
  const int threads = threads_option(o.threads);
  splat::Formats formats;
  formats.in = format_option("--in-format", o.in_format);
  formats.out = format_option("--format", o.format);
  formats.spz_version = static_cast<int>(integer_option("--spz-version", o.spz_version, 3, 4));
  spz_axes_options(o, formats);
  formats.drop_spz_extensions = o.drop_spz_extensions;
  formats.keep_order = o.keep_order;
  formats.sog_seed = static_cast<std::uint64_t>(integer_option("--seed", o.seed, 0, std::numeric_limits<long long>::max()));
  if (!o.sh_degree.empty() && !o.max_sh_error.empty()) throw UsageError("--sh-degree: --max-sh-error is given too; give one or the other");
  if (!o.sh_degree.empty()) formats.sh_degree = static_cast<int>(integer_option("--sh-degree", o.sh_degree, 0, splat::kMaxSplatShDegree));
  if (!o.max_sh_error.empty()) formats.max_sh_error = number_option("--max-sh-error", o.max_sh_error, 0, 1);
  formats.filters = filter_options(o);
  const bool bar = !o.quiet && isatty(STDERR_FILENO);
  if (o.in.size() > std::size_t(splat::kMaxMergedScenes))
    throw UsageError("--in: " + std::to_string(o.in.size()) + " scenes; at most " + std::to_string(splat::kMaxMergedScenes) + " are merged at once");
  const splat::Summary summary = splat::transform_files(o.in, o.out, t, threads, [bar](std::uint64_t done, std::uint64_t total) {
    if (bar) std::fprintf(stderr, "\rzhf splat: %3d%% (%llu of %llu splats)", int(100.0 * done / total), (unsigned long long)done,
                          (unsigned long long)total);
  }, formats);
  if (bar) std::fprintf(stderr, "\n");
  // What a lossy format could not hold is said even with --quiet.
  if (summary.dropped_degree > 0)
    std::fprintf(stderr, "zhf splat: %s: %s keeps SH degree 0 only; degrees 1..%d were dropped\n", io::excerpt(o.out).c_str(),
                 splat::file_format_extension(summary.out), summary.dropped_degree);
  if (summary.antialiasing_dropped)
    std::fprintf(stderr, "zhf splat: %s: the scene is marked antialiased, and %s has no such mark\n", io::excerpt(o.out).c_str(),
                 splat::file_format_extension(summary.out));
  if (summary.dropped_extensions > 0)
    std::fprintf(stderr, "zhf splat: %s: %d .spz extension records left out (--drop-spz-extensions)\n", io::excerpt(o.out).c_str(),
                 summary.dropped_extensions);
  if (!summary.left_out.empty()) {
    std::string phrases = summary.left_out[0];
    for (std::size_t i = 1; i < summary.left_out.size(); ++i) phrases += "; " + summary.left_out[i];
    // A merged scene's phrases name their input.
    const std::string from = o.in.size() == 1 ? " from " + io::excerpt(o.in[0]) : "";
    std::fprintf(stderr, "zhf splat: %s: not kept%s: %s\n", io::excerpt(o.out).c_str(), from.c_str(), phrases.c_str());
  }
  // What the filters left out is said even with --quiet, as a count by reason.
  if (formats.filters.any()) {
    std::string reasons;
    auto add = [&](std::uint64_t n, const char* why) {
      if (n > 0) reasons += (reasons.empty() ? "; left out " : ", ") + std::to_string(n) + " " + why;
    };
    add(summary.nonfinite, "with a NaN or infinite value");
    add(summary.outside, "outside the crop");
    add(summary.transparent, "below --min-opacity");
    std::fprintf(stderr, "zhf splat: %s: wrote %llu of %llu splats%s\n", io::excerpt(o.out).c_str(), (unsigned long long)summary.written(),
                 (unsigned long long)summary.splats, reasons.c_str());
  }
  if (summary.clamped > 0)
    std::fprintf(stderr, "zhf splat: %s: %llu values beyond the %s format's range were written as its nearest\n",
                 io::excerpt(o.out).c_str(), (unsigned long long)summary.clamped, splat::file_format_extension(summary.out));
  if (!o.quiet) {
    const std::string from = summary.in == splat::FileFormat::kPly ? (summary.ascii ? "ascii .ply" : "binary .ply")
                                                                   : splat::file_format_extension(summary.in);
    if (o.in.size() > 1) std::printf("merged %zu scenes, in the order given\n", o.in.size());
    std::printf("transformed %llu splats (%s, SH degree %s) into %s (%s)\n", (unsigned long long)summary.splats, from.c_str(),
                summary.sh_degree < 0 ? "none" : std::to_string(summary.sh_degree).c_str(), o.out.c_str(),
                splat::file_format_extension(summary.out));
    if (summary.kept_degree >= 0 && summary.kept_degree < summary.sh_degree && summary.dropped_degree < 0)
      std::printf("kept SH degree %d of %d: dropped energy %.3g (relative L2, as zhf analyze), largest colour change %.3g over %d view "
                  "directions, %llu bytes of SH left out\n",
                  summary.kept_degree, summary.sh_degree, summary.dropped_energy_error, summary.dropped_colour_error,
                  splat::kColourErrorDirections, (unsigned long long)summary.dropped_bytes);
    if (!summary.spz_axes_source.empty()) std::printf(".spz axes: %s\n", summary.spz_axes_source.c_str());
    if (summary.palette_entries > 0)
      std::printf("SH palette of %llu entries turned once (not per splat); labels, scales and colours carried as stored\n",
                  (unsigned long long)summary.palette_entries);
    if (summary.carried_extensions > 0) std::printf("%d .spz extension records carried unchanged\n", summary.carried_extensions);
    if (summary.sh_error[0] >= 0) {
      std::printf("the format's error in the colour, largest per SH band:");
      for (int band = 0; band < int(summary.sh_error.size()) && summary.sh_error[band] >= 0; ++band) std::printf(" %d: %.3g", band, summary.sh_error[band]);
      std::printf("\n");
    }
  }
  return kExitOk;
}

}  // namespace

void add_splat_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<SplatOptions>();
  CLI::App* c = app.add_subcommand(
      "splat",
      "Transform a 3D Gaussian Splatting scene (.ply, .compressed.ply, .splat, .spz, .glb, .sog): p' = s R p + t (rotate and scale about the origin, then translate), "
      "orientations, normals, log-scales and SH colours with it, in the .ply's axes (.spz and .glb are turned into them: docs/conventions.md); or convert it to another format");
  c->add_option("--in", o->in,
                "The scene: binary little-endian or ASCII .ply, compressed .ply, .splat, .spz, .glb (KHR_gaussian_splatting), or SOG (.sog, or a "
                "meta.json); given more than once, the scenes are merged into one output in that order (up to " +
                    std::to_string(splat::kMaxMergedScenes) + ")")
      ->required();
  c->add_option("--out", o->out, "Write the transformed scene here (.ply to .ply: same format, columns and comments)");
  c->add_flag("--info", o->info, "Say what the scene holds (format, splats, SH degree, bounds, axes, .spz records); write nothing");
  c->add_option("--format", o->format, "The output's format, " + splat::file_format_names() + " (default: --out's extension, else ply)");
  c->add_option("--spz-version", o->spz_version, "A .spz output's version: 4 (zstd, default) or 3 (gzip, for older readers)");
  c->add_option("--spz-axes", o->spz_axes,
                "A .spz's axes where it has no coordinate-system record, read and written: raw (the .ply's, default: the reference "
                "library's default, splat-transform) or rub (x right, y up, z back: Scaniverse, three.js)");
  c->add_flag("--spz-as-reference", o->spz_as_reference,
              "Convert a .spz's axes as the reference library (nianticlabs/spz) does where it differs from the systems' letters: "
              "coordinate-system records LFD, RFD, LBU, RBU, and the sign of band 4's m = 4 coefficient (docs/formats.md)");
  c->add_flag("--drop-spz-extensions", o->drop_spz_extensions, "Leave out a .spz's extension records (else carried into a .spz, refused for other formats)");
  c->add_flag("--keep-order", o->keep_order, "A compressed .ply output keeps the input's splat order (default: Morton order, as splat-transform writes)");
  c->add_option("--seed", o->seed, "A .sog written from another format: the seed of its SH palette's k-means (default 1)");
  c->add_option("--sh-degree", o->sh_degree, "Keep SH bands 0..K only (at most the scene's degree)");
  c->add_option("--max-sh-error", o->max_sh_error,
                "Keep the fewest SH bands whose dropped energy, relative L2 over the scene as zhf analyze measures it, is at most E");
  c->add_flag("--drop-nonfinite", o->drop_nonfinite, "Leave out splats with a NaN or infinite value (else refused); the count goes to stderr");
  c->add_option("--crop-box", o->crop_box, "x0 y0 z0 x1 y1 z1: keep the splats inside this box, where the transform puts them");
  c->add_option("--crop-sphere", o->crop_sphere, "x y z r: keep the splats within r of (x, y, z), where the transform puts them");
  c->add_option("--min-opacity", o->min_opacity, "Keep the splats whose opacity, sigmoid of the stored logit, is at least A (0..1)");
  c->add_option("--in-format", o->in_format, "The input's format, " + splat::file_format_names() + " (default: --in's extension and header, else ply)");
  add_transform_options(c, o->transform);
  c->add_flag("--identity", o->identity, "No rotation, the default when none is given (refused with one)");
  c->add_option("--translate", o->translate, "x y z: added after rotating and scaling");
  c->add_option("--scale", o->scale, "Uniform scale s > 0 (positions times s, log-scales plus log s); non-uniform is not a similarity");
  c->add_option("--convention", o->convention,
                "The SH coefficients' convention (default 3dgs): " + runtime::convention_names() + " (docs/conventions.md)");
  add_threads_option(c, o->threads);
  c->add_flag("--quiet", o->quiet, "No progress bar and no summary line");
  c->callback([o, &action] { action = [o] { return run_splat(*o); }; });
}

}  // namespace zhf::cli
