#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <cstdio>
#include <memory>
#include <thread>
#include <string>
#include <vector>

#include "commands.h"
#include "options.h"
#include "zhf/frames/designs.h"
#include "zhf/frames/frame.h"
#include "zhf/codegen/needlet_lut.h"
#include "zhf/frames/needlets.h"
#include "zhf/pipeline/project.h"
#include "zhf/verify/needlets.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/signals.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/lobe_table.h"
#include "zhf/runtime/tolerances.h"

namespace zhf::cli {
namespace {

struct DesignsOptions {
  std::string t, points = "0", starts = "64", seed = "1", threads = "0";
  bool symmetric = false;
  std::string out;
};

int run_designs(const DesignsOptions& o) {
  frames::DesignSearch s;
  s.t = static_cast<int>(integer_option("--t", o.t, 1, frames::kMaxDesignStrength));
  s.symmetric = o.symmetric;
  const int best = frames::best_known_count(s.t);
  const frames::DesignChoice choice = frames::default_design(s.t);
  s.points = static_cast<int>(integer_option("--points", o.points, 0, frames::kMaxPoints));
  if (s.points == 0) {
    s.points = choice.points;
    s.symmetric = s.symmetric || choice.symmetric;
  }
  if (s.points < 2) throw UsageError("--points: a design needs at least 2 points");
  if (s.symmetric && s.points % 2) throw UsageError("--points: a symmetric design has an even count (got " + std::to_string(s.points) + ")");
  s.starts = static_cast<int>(integer_option("--starts", o.starts, 1, 100000));
  s.seed = seed_option("--seed", o.seed);
  const int threads = static_cast<int>(integer_option("--threads", o.threads, 0, runtime::kMaxThreads));
  s.threads = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
  s.interrupted = [] { return io::interrupt_requested().load(); };
  std::unique_ptr<io::PendingFile> out;
  if (!o.out.empty()) out = std::make_unique<io::PendingFile>(o.out);
  const auto t0 = std::chrono::steady_clock::now();
  const frames::Design d = frames::search_design(s);
  io::throw_if_interrupted();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (d.start < 0) {
    std::fprintf(stderr, "zhf designs: no %d-point %d-design in %d starts (best residual %.3g)\n", s.points, s.t, s.starts, d.residual);
    return kExitFailure;
  }
  std::printf("t = %d: %zu points (best known %s), residual %.2e, start %d, %.2f s\n", s.t, d.points.size(),
              best > 0 ? std::to_string(best).c_str() : "-", d.residual, d.start, seconds);
  if (out) {
    nlohmann::ordered_json j;
    j["format"] = frames::kDesignFormat;
    j["t"] = s.t;
    j["count"] = d.points.size();
    j["symmetric"] = s.symmetric;
    j["residual"] = d.residual;
    j["best_known_count"] = best > 0 ? nlohmann::ordered_json(best) : nlohmann::ordered_json(nullptr);
    j["search"] = {{"seed", s.seed}, {"start", d.start}};
    nlohmann::ordered_json points = nlohmann::ordered_json::array();
    for (const frames::Point& p : d.points) points.push_back({p[0], p[1], p[2]});
    j["points"] = points;
    out->write(io::json_text(j));
    out->commit();
  }
  return kExitOk;
}

struct FrameOptions {
  std::string points, table, bands;
  std::string out;
};

int run_frame(const FrameOptions& o) {
  if (o.points.empty() == o.table.empty()) throw UsageError("--points or --table: give exactly one");
  std::unique_ptr<io::PendingFile> out;
  if (!o.out.empty()) out = std::make_unique<io::PendingFile>(o.out);
  // Band ranges: --bands L0..L1 over every direction; a table without --bands: each band on its lobes.
  struct Job {
    std::vector<frames::Point> directions;
    int lmin, lmax;
  };
  std::vector<Job> jobs;
  int lmin = 0, lmax = -1;
  if (!o.bands.empty()) {
    const std::vector<int> bands = orders_option("--bands", o.bands, 0, frames::kMaxFrameBand);
    lmin = bands.front();
    lmax = bands.back();
    if (lmax - lmin + 1 != static_cast<int>(bands.size())) throw UsageError("--bands: give a range L0..L1");
  }
  if (!o.points.empty()) {
    if (o.bands.empty()) throw UsageError("--bands: required with --points");
    jobs.push_back({frames::read_points(o.points), lmin, lmax});
  } else {
    const runtime::LobeTable table = runtime::read_lobe_table(o.table);
    std::vector<frames::Point> all;
    for (const runtime::TableLobe& lobe : table.lobes) all.push_back({lobe.xyz[0], lobe.xyz[1], lobe.xyz[2]});
    if (!o.bands.empty()) {
      jobs.push_back({all, lmin, lmax});
    } else {
      for (const runtime::TableBand& band : table.bands) {
        std::vector<frames::Point> lobes;
        for (int d : band.lobes) lobes.push_back(all[d]);
        jobs.push_back({lobes, band.l, band.l});
      }
    }
  }
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  std::printf("%-7s %10s %9s %14s %14s %10s %11s  %s\n", "bands", "directions", "dimension", "A", "B", "sqrt(B/A)", "redundancy",
              "kind");
  for (const Job& job : jobs) {
    const frames::FrameBounds b = frames::frame_bounds(job.directions, job.lmin, job.lmax);
    const std::string kind = !b.frame() ? "not a frame" : b.parseval() ? "Parseval tight" : b.tight() ? "tight" : "frame";
    const std::string bands = std::to_string(b.lmin) + ".." + std::to_string(b.lmax);
    std::printf("%-7s %10d %9d %14.8g %14.8g %10.4g %11.4g  %s\n", bands.c_str(), b.directions, b.dimension, b.lower, b.upper,
                b.condition(), b.redundancy(), kind.c_str());
    rows.push_back({{"lmin", b.lmin},
                    {"lmax", b.lmax},
                    {"directions", b.directions},
                    {"dimension", b.dimension},
                    {"lower_bound", b.lower},
                    {"upper_bound", b.upper},
                    {"condition", b.frame() ? nlohmann::ordered_json(b.condition()) : nlohmann::ordered_json(nullptr)},
                    {"redundancy", b.redundancy()},
                    {"tight", b.tight()},
                    {"parseval", b.parseval()}});
    io::throw_if_interrupted();
  }
  if (out) {
    out->write(io::json_text(nlohmann::ordered_json{{"format", "zhf-frame-1"}, {"frames", rows}}));
    out->commit();
  }
  return kExitOk;
}

struct NeedletOptions {
  std::string dilation = "2", lmax, sizes = "64,256,1024,4096,16384";
  bool gauss = false;
  std::string size = "1024", interpolation = "linear", lang, langs = "cpp,glsl,hlsl", prefix = "zhf_needlets", compiler;
  std::string out, data;
  std::string j = "1", cut = "10", margin = "4";
};

double dilation_option(const std::string& text) {
  return number_option("--B", text, frames::kMinDilation, frames::kMaxDilation);
}

// Each level on the smallest shipped design exact for it, or on Gauss product nodes.
frames::NeedletFrame needlet_frame(double dilation, int lmax, bool gauss) {
  if (gauss) return frames::NeedletFrame(dilation, lmax);
  const std::string designs = pipeline::project().designs();
  return frames::NeedletFrame(dilation, lmax, [&](int degree) { return frames::design_cubature(designs, degree); });
}

codegen::NeedletLutOptions lut_options(const NeedletOptions& o, const std::string& command) {
  codegen::NeedletLutOptions lut;
  lut.table_size = static_cast<int>(integer_option("--size", o.size, frames::kMinTableSize, frames::kMaxTableSize));
  if (o.interpolation == "linear") lut.interpolation = frames::Interpolation::kLinear;
  else if (o.interpolation == "quadratic") lut.interpolation = frames::Interpolation::kQuadratic;
  else throw UsageError("--interpolation: '" + io::excerpt(o.interpolation) + "' is not linear or quadratic");
  std::string why;
  if (!codegen::valid_prefix(o.prefix, why)) throw UsageError("--prefix: " + why);
  lut.prefix = o.prefix;
  lut.command = command;
  return lut;
}

codegen::Language language_option(const std::string& option, const std::string& name) {
  codegen::Language language;
  if (!codegen::parse_language(name, language)) throw UsageError(option + ": '" + io::excerpt(name) + "' is not cpp, glsl or hlsl");
  return language;
}

int run_needlet_emit(const NeedletOptions& o, const std::string& command) {
  const double dilation = dilation_option(o.dilation);
  const int lmax = static_cast<int>(integer_option("--lmax", o.lmax, 1, frames::kMaxNeedletFrameBand));
  const codegen::NeedletLutOptions lut = lut_options(o, command);
  const codegen::Language language = language_option("--lang", o.lang);
  io::PendingFile out(o.out);
  std::unique_ptr<io::PendingFile> data;
  if (!o.data.empty()) data = std::make_unique<io::PendingFile>(o.data);
  const frames::NeedletFrame frame = needlet_frame(dilation, lmax, o.gauss);
  const codegen::EmittedFile file = codegen::emit_needlet_lut(frame, language, lut);
  out.write(file.text);
  if (data) {
    const std::vector<float> values = codegen::needlet_lut_data(frame, lut.table_size);
    std::string bytes(values.size() * sizeof(float), '\0');
    for (std::size_t i = 0; i < values.size(); ++i) {  // little-endian float32, whatever the host
      std::uint32_t word;
      std::memcpy(&word, &values[i], sizeof word);
      for (int b = 0; b < 4; ++b) bytes[4 * i + b] = static_cast<char>((word >> (8 * b)) & 0xff);
    }
    data->write(bytes);
    data->commit();
  }
  out.commit();
  std::printf("%s: %s, %d multiplies and %d adds per evaluation\n", o.out.c_str(), file.functions[0].name.c_str(),
              file.functions[0].ops.multiplies, file.functions[0].ops.adds);
  return kExitOk;
}

int run_needlet_verify(const NeedletOptions& o) {
  const double dilation = dilation_option(o.dilation);
  const int lmax = static_cast<int>(integer_option("--lmax", o.lmax, 1, frames::kMaxNeedletFrameBand));
  const codegen::NeedletLutOptions lut = lut_options(o, "zhf needlets verify");
  verify::NeedletLutVerify v;
  v.languages.clear();
  for (std::size_t start = 0; start <= o.langs.size();) {
    const std::size_t comma = std::min(o.langs.find(',', start), o.langs.size());
    const codegen::Language language = language_option("--langs", o.langs.substr(start, comma - start));
    if (std::find(v.languages.begin(), v.languages.end(), language) != v.languages.end())
      throw UsageError("--langs: '" + o.langs.substr(start, comma - start) + "' is listed twice");
    v.languages.push_back(language);
    start = comma + 1;
  }
  v.compiler = o.compiler;
  std::unique_ptr<io::PendingFile> out;
  if (!o.out.empty()) out = std::make_unique<io::PendingFile>(o.out);
  const frames::NeedletFrame frame = needlet_frame(dilation, lmax, o.gauss);
  const std::vector<verify::NeedletLutResult> results = verify::verify_needlet_lut(frame, lut, v);
  io::throw_if_interrupted();
  std::printf("needlet frame B = %g, bands 0..%d, %d coefficients; %d-entry tables, %s\n", dilation, lmax, frame.size(), lut.table_size,
              o.interpolation.c_str());
  std::printf("%-6s %14s %14s  %s\n", "lang", "vs mirror", "table error", "result");
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  bool pass = true, no_device = false;
  for (const verify::NeedletLutResult& r : results) {
    std::printf("%-6s %14.3e %14.3e  %s\n", r.language.c_str(), r.vs_mirror, r.table_error,
                r.pass ? "pass" : ("FAIL" + (r.error.empty() ? "" : ": " + r.error)).c_str());
    pass = pass && r.pass;
    no_device = no_device || r.error.rfind("no Vulkan device", 0) == 0;
    rows.push_back({{"language", r.language}, {"vs_mirror", r.vs_mirror}, {"table_error", r.table_error}, {"pass", r.pass},
                    {"error", r.error}});
  }
  if (out) {
    out->write(io::json_text(nlohmann::ordered_json{{"format", "zhf-needlet-verify-1"},
                                                    {"B", dilation},
                                                    {"lmax", lmax},
                                                    {"size", lut.table_size},
                                                    {"interpolation", o.interpolation},
                                                    {"tolerance", runtime::tolerance::kNeedletLutFloat},
                                                    {"results", rows}}));
    out->commit();
  }
  return pass ? kExitOk : no_device ? kExitNoDevice : kExitFailure;
}

// One level's needlet against the SH delta of the same top band: localisation, and the profiles.
int run_needlet_profile(const NeedletOptions& o) {
  const double dilation = dilation_option(o.dilation);
  const int j = static_cast<int>(integer_option("--j", o.j, 0, 16));
  if (std::pow(dilation, j + 1) > frames::kMaxProfileBand + 1)
    throw UsageError("--j: level " + o.j + " of B = " + o.dilation + " reaches past band " + std::to_string(frames::kMaxProfileBand));
  const int top = frames::needlet_top_band(dilation, j);
  std::unique_ptr<io::PendingFile> out;
  if (!o.out.empty()) out = std::make_unique<io::PendingFile>(o.out);
  const std::function<double(double)> needlet = frames::needlet_kernel(dilation, j);
  const auto delta = [&](double t) { return frames::sh_delta_kernel(top, t); };
  std::printf("B = %g, level %d: bands %d..%d (SH delta: bands 0..%d)\n", dilation, j, static_cast<int>(std::floor(std::pow(dilation, j - 1))) + 1, top, top);
  std::printf("%12s %22s %22s %16s %16s\n", "cap (deg)", "needlet outside", "SH delta outside", "needlet lobe", "SH delta lobe");
  for (double waves : {1.0, 2.0, 4.0}) {
    const double cap = waves * runtime::kPi / top;
    const frames::Localisation a = frames::localisation(needlet, top, cap), b = frames::localisation(delta, top, cap);
    std::printf("%12.2f %22.3e %22.3e %16.3e %16.3e\n", cap * 180 / runtime::kPi, a.outside_energy, b.outside_energy, a.sidelobe, b.sidelobe);
  }
  if (out) {
    std::string csv = "# zhf needlets profile: theta in degrees, needlet / its peak, SH delta / its peak\n";
    const double needlet_peak = needlet(1), delta_peak = delta(1);
    for (int i = 0; i <= 720; ++i) {
      const double theta = runtime::kPi * i / 720, t = std::cos(theta);
      char line[96];
      std::snprintf(line, sizeof line, "%.4f,%.9g,%.9g\n", theta * 180 / runtime::kPi, needlet(t) / needlet_peak, delta(t) / delta_peak);
      csv += line;
    }
    out->write(csv);
    out->commit();
  }
  return kExitOk;
}

// The talk's case: a signal cut to zero around the equator, in SH and in needlets.
int run_needlet_mask(const NeedletOptions& o) {
  const double dilation = dilation_option(o.dilation);
  const int lmax = static_cast<int>(integer_option("--lmax", o.lmax, 1, frames::kMaxNeedletFrameBand));
  const double cut = number_option("--cut", o.cut, 0.1, 80) * runtime::kPi / 180;
  const double margin = number_option("--margin", o.margin, 0, 64);
  const frames::NeedletFrame frame = needlet_frame(dilation, lmax, o.gauss);
  const frames::MaskExperiment m = frames::mask_experiment(frame, cut, margin);
  double worst_band = 0, least_band = 1e300;
  for (double e : m.band_error) worst_band = std::max(worst_band, e), least_band = std::min(least_band, e);
  std::printf("signal of bands 0..%d cut to 0 for |latitude| < %s deg; beyond: %s half-wavelengths of the top band past the cut\n", lmax,
              o.cut.c_str(), o.margin.c_str());
  std::printf("SH: every band disturbed, relative error %.3g .. %.3g; SH projection's ringing beyond the margin %.3g of the peak\n",
              least_band, worst_band, m.sh_ringing);
  std::printf("%6s %12s %10s %26s %24s\n", "level", "needlets", "beyond", "max error beyond / rms", "max error nearer / rms");
  for (const frames::MaskLevel& l : m.levels)
    std::printf("%6d %12d %10d %26.3e %24.3e\n", l.j, l.coefficients, l.outside, l.outside_error, l.inside_error);
  return kExitOk;
}

int run_needlet_window(const NeedletOptions& o) {
  const double dilation = dilation_option(o.dilation);
  const int lmax = static_cast<int>(integer_option("--lmax", o.lmax, 0, frames::kMaxNeedletBand));
  std::unique_ptr<io::PendingFile> out;
  if (!o.out.empty()) out = std::make_unique<io::PendingFile>(o.out);
  nlohmann::ordered_json b = nlohmann::ordered_json::array();
  const std::vector<frames::WindowValue> windows = frames::needlet_windows(dilation, lmax);
  for (std::size_t i = 0; i < windows.size(); ++i) {
    const frames::WindowValue& w = windows[i];
    b.push_back({w.j, w.l, w.value});
    if (i == 0 || windows[i - 1].j != w.j) std::printf("level %d: bands %d..", w.j, w.l);
    if (i + 1 == windows.size() || windows[i + 1].j != w.j) std::printf("%d\n", w.l);
  }
  std::printf("%zu windows\n", b.size());
  if (out) {
    out->write(io::json_text(nlohmann::ordered_json{{"format", "zhf-needlet-window-1"}, {"B", dilation}, {"lmax", lmax}, {"b", b}}));
    out->commit();
  }
  return kExitOk;
}

// The frame's levels, the kernel tables' error per size, and the tabulated rotation's error per
// size against the exact path; times on stdout only, so the JSON is the same on every run.
int run_needlet_tables(const NeedletOptions& o) {
  const double dilation = dilation_option(o.dilation);
  const int lmax = static_cast<int>(integer_option("--lmax", o.lmax, 1, frames::kMaxNeedletFrameBand));
  const std::vector<int> sizes = orders_option("--sizes", o.sizes, frames::kMinTableSize, frames::kMaxTableSize);
  if (sizes.size() > 16) throw UsageError("--sizes: at most 16 sizes (got " + std::to_string(sizes.size()) + ")");
  std::unique_ptr<io::PendingFile> out;
  if (!o.out.empty()) out = std::make_unique<io::PendingFile>(o.out);
  const frames::NeedletFrame frame = needlet_frame(dilation, lmax, o.gauss);
  nlohmann::ordered_json levels = nlohmann::ordered_json::array();
  std::printf("%6s %9s %7s  %s\n", "level", "bands", "points", "cubature");
  for (const frames::NeedletLevel& level : frame.levels()) {
    const std::string bands = std::to_string(level.lmin) + ".." + std::to_string(level.lmax);
    std::printf("%6d %9s %7zu  %s\n", level.j, bands.c_str(), level.cubature.points.size(), level.cubature.name.c_str());
    levels.push_back({{"j", level.j}, {"lmin", level.lmin}, {"lmax", level.lmax}, {"points", level.cubature.points.size()},
                      {"cubature", level.cubature.name}});
  }
  const auto how_name = [](frames::Interpolation how) { return how == frames::Interpolation::kLinear ? "linear" : "quadratic"; };
  const frames::Interpolation hows[] = {frames::Interpolation::kLinear, frames::Interpolation::kQuadratic};

  // Kernel tables: the worst level's error relative to its peak.
  nlohmann::ordered_json kernel_rows = nlohmann::ordered_json::array();
  std::printf("\nkernel table (max error / peak, worst level)\n%8s %12s %12s\n", "size", "linear", "quadratic");
  for (int size : sizes) {
    nlohmann::ordered_json row{{"size", size}};
    std::printf("%8d", size);
    for (frames::Interpolation how : hows) {
      double worst = 0;
      for (int a = 1; a < static_cast<int>(frame.levels().size()); ++a) {
        const auto kernel = [&](double t) { return frame.kernel(a, t); };
        worst = std::max(worst, frames::table_error(frames::UniformTable(kernel, size), kernel, how));
      }
      row[how_name(how)] = worst;
      std::printf(" %12.3e", worst);
      io::throw_if_interrupted();
    }
    std::printf("\n");
    kernel_rows.push_back(row);
  }

  // Rotation of a fixed unit-norm signal by a fixed turn: max coefficient error against the exact path.
  std::vector<double> f(runtime::coefficient_count(lmax + 1));
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = std::sin(1.0 + 0.7 * double(i)) / std::sqrt(double(f.size()) / 2);
  const std::vector<double> beta = frame.analyze(f);
  const runtime::Matrix3 r = runtime::rotation_from_zyz(0.3, 1.1, -0.7);
  auto t0 = std::chrono::steady_clock::now();
  const std::vector<double> exact = frame.rotate_exact(beta, r);
  const double exact_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  nlohmann::ordered_json rotation_rows = nlohmann::ordered_json::array();
  std::printf("\nrotation of %d coefficients (max error against the exact path; exact path %.3g ms)\n%8s %12s %12s %12s %12s\n",
              frame.size(), exact_seconds * 1e3, "size", "linear", "ms", "quadratic", "ms");
  for (int size : sizes) {
    nlohmann::ordered_json row{{"size", size}};
    std::printf("%8d", size);
    for (frames::Interpolation how : hows) {
      const frames::TabulatedNeedletRotation rotation(frame, size, how);
      t0 = std::chrono::steady_clock::now();
      const std::vector<double> turned = rotation.rotate(beta, r);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      double worst = 0;
      for (std::size_t i = 0; i < turned.size(); ++i) worst = std::max(worst, std::abs(turned[i] - exact[i]));
      row[how_name(how)] = worst;
      std::printf(" %12.3e %12.3g", worst, seconds * 1e3);
      io::throw_if_interrupted();
    }
    std::printf("\n");
    rotation_rows.push_back(row);
  }
  if (out) {
    out->write(io::json_text(nlohmann::ordered_json{{"format", "zhf-needlet-tables-1"},
                                                    {"B", dilation},
                                                    {"lmax", lmax},
                                                    {"coefficients", frame.size()},
                                                    {"levels", levels},
                                                    {"kernel_tables", kernel_rows},
                                                    {"rotation", rotation_rows}}));
    out->commit();
  }
  return kExitOk;
}

}  // namespace

void add_frames_commands(CLI::App& app, Action& action, const std::string& command_line) {
  auto d = std::make_shared<DesignsOptions>();
  CLI::App* c = app.add_subcommand("designs", "Find a spherical t-design: equal-weight points exact for every SH of degree <= t");
  c->add_option("--t", d->t, "Strength t, 1..50")->required();
  c->add_option("--points", d->points,
                "Point count (default: the smallest known for t <= 10, antipodal sets of the smallest known count for odd t "
                "(Womersley's 192 and 234 at 19 and 21), the efficient count ceil((t+1)^2/2)+1 for even t >= 12)");
  c->add_flag("--symmetric", d->symmetric, "Antipodal pairs: x and -x (odd bands vanish; half the unknowns)");
  c->add_option("--starts", d->starts, "Starts to try, 1..100000 (default 64); the first that converges wins");
  c->add_option("--seed", d->seed, "Random seed, 0..2^64-1 (default 1)");
  c->add_option("--threads", d->threads, "Threads, 0..256 (0: all cores); never changes the result");
  c->add_option("--json", d->out, "Write the design here (zhf-design-1)");
  c->callback([d, &action] { action = [d] { return run_designs(*d); }; });

  auto f = std::make_shared<FrameOptions>();
  CLI::App* fc = app.add_subcommand("frame", "Frame bounds of the zonal lobes at a set of directions, for a band range");
  fc->add_option("--points", f->points, "Directions: a JSON array of [x, y, z] or a design file");
  fc->add_option("--table", f->table, "A lobe table's lobes (without --bands: each band on its own lobes)");
  fc->add_option("--bands", f->bands, "Bands L0..L1 (0..63)");
  fc->add_option("--json", f->out, "Write the bounds here (zhf-frame-1)");
  fc->callback([f, &action] { action = [f] { return run_frame(*f); }; });

  CLI::App* nc = app.add_subcommand("needlets", "Spherical needlets: windows, kernel tables and tabulated rotation");
  nc->require_subcommand(1);
  auto w = std::make_shared<NeedletOptions>();
  CLI::App* wc = nc->add_subcommand("window", "The Littlewood-Paley windows b(l / B^j), every non-zero one for bands 0..lmax");
  wc->add_option("--B", w->dilation, "Dilation B, in [1.05, 64] (default 2)");
  wc->add_option("--lmax", w->lmax, "Highest band, 0..4096")->required();
  wc->add_option("--json", w->out, "Write the windows here: {\"B\", \"lmax\", \"b\": [[j, l, value], ...]}");
  wc->callback([w, &action] { action = [w] { return run_needlet_window(*w); }; });
  auto t = std::make_shared<NeedletOptions>();
  CLI::App* tc = nc->add_subcommand("tables", "The needlet frame of bands 0..lmax: levels, kernel look-up error and tabulated rotation error per table size");
  tc->add_option("--B", t->dilation, "Dilation B, in [1.05, 64] (default 2)");
  tc->add_option("--lmax", t->lmax, "Band limit, 1..63")->required();
  tc->add_option("--sizes", t->sizes, "Table sizes, e.g. 64,256,1024 (3..1048576; default 64,256,1024,4096,16384)");
  tc->add_flag("--gauss", t->gauss, "Gauss product cubatures at every level instead of the shipped designs");
  tc->add_option("--json", t->out, "Write the tables here (zhf-needlet-tables-1)");
  tc->callback([t, &action] { action = [t] { return run_needlet_tables(*t); }; });
  auto pr = std::make_shared<NeedletOptions>();
  CLI::App* pc = nc->add_subcommand("profile", "One level's needlet against the SH delta of its top band: energy and side lobes outside caps");
  pc->add_option("--B", pr->dilation, "Dilation B, in [1.05, 64] (default 2)");
  pc->add_option("--j", pr->j, "Level, 0..16 (default 1)");
  pc->add_option("--csv", pr->out, "Write both profiles against theta here (degrees, each divided by its peak)");
  pc->callback([pr, &action] { action = [pr] { return run_needlet_profile(*pr); }; });
  auto mk = std::make_shared<NeedletOptions>();
  CLI::App* mc = nc->add_subcommand("mask", "A signal cut around the equator: which SH and needlet coefficients the cut disturbs");
  mc->add_option("--B", mk->dilation, "Dilation B, in [1.05, 64] (default 2)");
  mc->add_option("--lmax", mk->lmax, "Band limit, 1..63")->required();
  mc->add_option("--cut", mk->cut, "Half-width of the cut band in degrees of latitude, 0.1..80 (default 10)");
  mc->add_option("--margin", mk->margin, "Beyond the cut by this many half-wavelengths of the top band (pi / lmax of a level, pi / L for SH), 0..64 (default 4)");
  mc->add_flag("--gauss", mk->gauss, "Gauss product cubatures instead of the shipped designs");
  mc->callback([mk, &action] { action = [mk] { return run_needlet_mask(*mk); }; });
  auto e = std::make_shared<NeedletOptions>();
  CLI::App* ec = nc->add_subcommand("emit", "Emit a needlet expansion's evaluator (kernel look-up tables) as C++, GLSL or HLSL");
  ec->add_option("--B", e->dilation, "Dilation B, in [1.05, 64] (default 2)");
  ec->add_option("--lmax", e->lmax, "Band limit, 1..63")->required();
  ec->add_option("--size", e->size, "Entries per kernel table, 3..1048576 (default 1024)");
  ec->add_option("--interpolation", e->interpolation, "linear (default) or quadratic");
  ec->add_option("--lang", e->lang, "cpp, glsl or hlsl")->required();
  ec->add_option("--prefix", e->prefix, "Prefix of every emitted name (default zhf_needlets)");
  ec->add_flag("--gauss", e->gauss, "Gauss product cubatures instead of the shipped designs");
  ec->add_option("--out", e->out, "The file to write")->required();
  ec->add_option("--data", e->data, "Also write the nodes, scales and tables as little-endian float32 (the shaders' storage buffer)");
  ec->callback([e, &action, command_line] { action = [e, command_line] { return run_needlet_emit(*e, command_line); }; });
  auto v = std::make_shared<NeedletOptions>();
  CLI::App* vc = nc->add_subcommand("verify", "Compile and run the emitted needlet evaluators against their CPU mirror and the exact expansion");
  vc->add_option("--B", v->dilation, "Dilation B, in [1.05, 64] (default 2)");
  vc->add_option("--lmax", v->lmax, "Band limit, 1..63")->required();
  vc->add_option("--size", v->size, "Entries per kernel table, 3..1048576 (default 1024)");
  vc->add_option("--interpolation", v->interpolation, "linear (default) or quadratic");
  vc->add_option("--langs", v->langs, "Languages, e.g. cpp,glsl (default cpp,glsl,hlsl)");
  vc->add_option("--compiler", v->compiler, "C++ compiler and leading arguments (default $CXX, else c++)");
  vc->add_flag("--gauss", v->gauss, "Gauss product cubatures instead of the shipped designs");
  vc->add_option("--json", v->out, "Write the results here (zhf-needlet-verify-1)");
  vc->callback([v, &action] { action = [v] { return run_needlet_verify(*v); }; });
}

}  // namespace zhf::cli
