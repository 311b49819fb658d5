// zhf needlets: the needlet frame's windows, kernel look-up tables, localisation experiments, and
// the emitted evaluators with their verification (frames/needlets.h, codegen/needlet_lut.h).
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "options.h"
#include "zhf/codegen/needlet_lut.h"
#include "zhf/frames/needlets.h"
#include "zhf/frames/prt.h"
#include "zhf/frames/windows.h"
#include "zhf/healpix/maps.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/hdr.h"
#include "zhf/io/signals.h"
#include "zhf/pipeline/project.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/runtime/tolerances.h"
#include "zhf/verify/needlets.h"

namespace zhf::cli {
namespace {

struct NeedletOptions {
  std::string dilation = "2", order, lmax, sizes = "64,256,1024,4096,16384";
  bool gauss = false;
  std::string size = "1024", interpolation = "linear", lang, langs = "cpp,glsl,hlsl,wgsl", prefix = "zhf_needlets", compiler;
  std::string set = "0", binding = "0";
  std::string out, data;
  std::string j = "1", cut = "10", margin = "4";
  std::string window = "standard", mexican_order = "1", level;
  std::string healpix, mask, iterations = "3", in, healpix_out, nside, ordering = "ring";
  std::string scene = "sphere", transfer = "diffuse", sky = "sun", side = "16", kept = "16,64,256,1024", csv, shading_csv;
};

// The top band L of a needlet command's signals, in [lo, hi]: --order N means bands 0..N-1 (as in
// every command), the old --lmax L bands 0..L.
const std::string kDilationHelp = "Dilation B, in [" + runtime::format_number(runtime::kMinDilation) + ", " +
                                  runtime::format_number(runtime::kMaxDilation) + "] (default 2)";
const std::string kTableSizeRange = std::to_string(runtime::kMinNeedletTableSize) + ".." + std::to_string(runtime::kMaxNeedletTableSize);
constexpr const char* kNeedletCoefficientsFormat = "zhf-needlet-coefficients-1";
const std::string kTableSizeHelp = "Entries per kernel table, " + kTableSizeRange + " (default 1024)";

// --order N (bands 0..N-1, N up to max_top_band + 1) and its old spelling --lmax L (bands 0..L).
void add_band_limit(CLI::App* command, NeedletOptions& o, int max_top_band) {
  CLI::Option* order = command->add_option("--order", o.order, "Bands 0..N-1, N in 1.." + std::to_string(max_top_band + 1));
  CLI::Option* lmax = command->add_option("--lmax", o.lmax, "old spelling: the top band, --order minus 1")->group("");
  old_spellings().push_back({"--lmax", lmax, order, "--order (minus 1)"});
}

int top_band(const NeedletOptions& o, int lo, int hi) {
  if (!o.lmax.empty()) return static_cast<int>(integer_option("--lmax", o.lmax, lo, hi));
  if (o.order.empty()) throw UsageError("--order: required (bands 0..N-1)");
  return static_cast<int>(integer_option("--order", o.order, lo + 1, hi + 1)) - 1;
}

double dilation_option(const std::string& text) {
  return number_option("--B", text, runtime::kMinDilation, runtime::kMaxDilation);
}

// Each level on the smallest shipped design exact for it, or on Gauss product nodes.
frames::NeedletFrame needlet_frame(double dilation, int lmax, bool gauss) {
  if (gauss) return frames::NeedletFrame(dilation, lmax);
  const std::string designs = pipeline::project().designs();
  return frames::NeedletFrame(dilation, lmax, [&](int degree) { return frames::design_cubature(designs, degree); });
}

codegen::NeedletLutOptions lut_options(const NeedletOptions& o, const std::string& command) {
  codegen::NeedletLutOptions lut;
  lut.table_size = static_cast<int>(integer_option("--size", o.size, runtime::kMinNeedletTableSize, runtime::kMaxNeedletTableSize));
  if (o.interpolation == "linear") lut.interpolation = frames::Interpolation::kLinear;
  else if (o.interpolation == "quadratic") lut.interpolation = frames::Interpolation::kQuadratic;
  else throw UsageError("--interpolation: '" + io::excerpt(o.interpolation) + "' is not linear or quadratic");
  std::string why;
  if (!codegen::valid_prefix(o.prefix, why)) throw UsageError("--prefix: " + why);
  lut.prefix = o.prefix;
  lut.storage_set = static_cast<int>(integer_option("--set", o.set, 0, runtime::kMaxStorageSet));
  lut.storage_binding = static_cast<int>(integer_option("--binding", o.binding, 0, runtime::kMaxStorageBinding));
  lut.command = command;
  return lut;
}

codegen::Language language_option(const std::string& option, const std::string& name) {
  codegen::Language language;
  const auto& known = codegen::needlet_lut_languages();
  if (codegen::parse_language(name, language) && std::find(known.begin(), known.end(), language) != known.end()) return language;
  std::string names;
  for (std::size_t i = 0; i < known.size(); ++i)
    names += (i == 0 ? "" : i + 1 == known.size() ? " or " : ", ") + std::string(codegen::language_name(known[i]));
  throw UsageError(option + ": '" + io::excerpt(name) + "' is not " + names);
}

int run_needlet_emit(const NeedletOptions& o, const std::string& command) {
  const double dilation = dilation_option(o.dilation);
  const int lmax = top_band(o, 1, runtime::kMaxNeedletFrameBand);
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
  const int lmax = top_band(o, 1, runtime::kMaxNeedletFrameBand);
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
  v.naga_wasm = pipeline::project().naga_wasm();
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
  if (std::pow(dilation, j + 1) > runtime::kMaxProfileBand + 1)
    throw UsageError("--j: level " + o.j + " of B = " + o.dilation + " reaches past band " + std::to_string(runtime::kMaxProfileBand));
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
  const int lmax = top_band(o, 1, runtime::kMaxNeedletFrameBand);
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
  frames::Window w;
  w.dilation = dilation_option(o.dilation);
  if (!frames::parse_window_kind(o.window, w.kind)) throw UsageError("--window: '" + runtime::excerpt(o.window) + "' is not standard, spline or mexican");
  w.order = static_cast<int>(integer_option("--mexican-order", o.mexican_order, 1, runtime::kMaxMexicanOrder));
  const int lmax = top_band(o, 0, runtime::kMaxNeedletBand);
  std::unique_ptr<io::PendingFile> out;
  if (!o.out.empty()) out = std::make_unique<io::PendingFile>(o.out);
  nlohmann::ordered_json b = nlohmann::ordered_json::array();
  const std::vector<frames::WindowValue> windows = frames::window_values(w, lmax);
  for (std::size_t i = 0; i < windows.size(); ++i) {
    const frames::WindowValue& v = windows[i];
    b.push_back({v.j, v.l, v.value});
    if (i == 0 || windows[i - 1].j != v.j) std::printf("level %d: bands %d..", v.j, v.l);
    if (i + 1 == windows.size() || windows[i + 1].j != v.j) std::printf("%d\n", v.l);
  }
  std::printf("%zu windows\n", b.size());
  nlohmann::ordered_json report{{"format", "zhf-needlet-window-1"}, {"window", frames::window_kind_name(w.kind)}, {"B", w.dilation}, {"lmax", lmax}};
  if (w.kind == frames::WindowKind::kMexican) report["order"] = w.order;
  if (lmax >= 1) {
    // How far from tight: the squares' sum over the levels, least and greatest over the bands.
    double least = 1e300, most = 0;
    for (int l = 1; l <= lmax; ++l) {
      const double sum = frames::window_square_sum(w, l);
      least = std::min(least, sum);
      most = std::max(most, sum);
    }
    std::printf("sum over levels of b^2, bands 1..%d: %.17g .. %.17g, ratio %.6g (frame bounds; 1 .. 1 is a tight frame)\n", lmax, least,
                most, most / least);
    report["frame_bounds"] = {least, most};
  }
  if (!o.level.empty()) {
    // Localisation: level j's kernel energy outside caps of radius k / B^j, k = 1, 2, 4, 8.
    const int j = static_cast<int>(integer_option("--level", o.level, 0, 12));
    nlohmann::ordered_json caps = nlohmann::ordered_json::array();
    std::printf("level %d kernel, energy outside the cap of radius k / B^%d:", j, j);
    for (double k : {1.0, 2.0, 4.0, 8.0}) {
      const double radius = std::min(runtime::kPi, k / std::pow(w.dilation, j));
      const double outside = frames::kernel_energy_outside(w, j, radius);
      std::printf("  k=%g %.3e", k, outside);
      caps.push_back({k, outside});
    }
    std::printf("\n");
    report["localisation"] = {{"level", j}, {"outside", caps}};
  }
  report["b"] = b;
  if (out) {
    out->write(io::json_text(report));
    out->commit();
  }
  return kExitOk;
}

// The frame's levels, the kernel tables' error per size, and the tabulated rotation's error per
// size against the exact path; times on stdout only, so the JSON is the same on every run.
int run_needlet_tables(const NeedletOptions& o) {
  const double dilation = dilation_option(o.dilation);
  const int lmax = top_band(o, 1, runtime::kMaxNeedletFrameBand);
  const std::vector<int> sizes = orders_option("--sizes", o.sizes, runtime::kMinNeedletTableSize, runtime::kMaxNeedletTableSize);
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

// The needlet coefficients of a HEALPix map (masked: of the map times the mask): its SH to band L
// by the pixel quadrature and Jacobi steps, then the frame's analysis.
int run_needlet_analyze(const NeedletOptions& o) {
  const double dilation = dilation_option(o.dilation);
  const int lmax = top_band(o, 1, runtime::kMaxNeedletFrameBand);
  const int iterations = static_cast<int>(integer_option("--iterations", o.iterations, 0, runtime::kMaxHealpixIterations));
  if (o.healpix.empty()) throw UsageError("--healpix: required");
  if (o.out.empty()) throw UsageError("--out: required");
  io::PendingFile out(o.out);
  const healpix::MaskedSignal signal = healpix::read_masked_signal(o.healpix, o.mask);
  if (lmax + 1 - 1 > healpix::max_analysis_band(signal.nside))
    throw UsageError("--order: band " + std::to_string(lmax + 1 - 1) + " is above 4 Nside = " + std::to_string(healpix::max_analysis_band(signal.nside)) + ", the most " +
                     io::excerpt(o.healpix) + "'s pixels resolve");
  const std::vector<double> sh = healpix::analyze_map(signal.nside, signal.ring, lmax + 1, iterations, io::throw_if_interrupted);
  const frames::NeedletFrame frame = needlet_frame(dilation, lmax, o.gauss);
  const std::vector<double> beta = frame.analyze(sh);
  std::printf("%s: Nside %lld, sky fraction %.4f; B = %g, bands 0..%d, %d needlet coefficients\n", o.healpix.c_str(),
              static_cast<long long>(signal.nside), signal.sky_fraction, dilation, lmax, frame.size());
  std::printf("%6s %10s %10s %12s %14s\n", "level", "bands", "needlets", "masked", "energy");
  nlohmann::ordered_json levels = nlohmann::ordered_json::array();
  for (const frames::NeedletLevel& level : frame.levels()) {
    const int count = static_cast<int>(level.cubature.points.size());
    int masked = 0;  // centred on a pixel the mask drops
    double energy = 0;
    for (int k = 0; k < count; ++k) {
      energy += beta[level.offset + k] * beta[level.offset + k];
      if (!signal.weights.empty() && signal.weights[healpix::pixel_at(signal.nside, level.cubature.points[k])] == 0) ++masked;
    }
    std::printf("%6d %6d..%-3d %10d %12d %14.6e\n", level.j, level.lmin, level.lmax, count, masked, energy);
    levels.push_back({{"j", level.j}, {"lmin", level.lmin}, {"lmax", level.lmax}, {"offset", level.offset}, {"count", count}, {"masked", masked}});
  }
  out.write(io::json_text(nlohmann::ordered_json{{"format", kNeedletCoefficientsFormat},
                                                 {"B", dilation},
                                                 {"lmax", lmax},
                                                 {"nodes", o.gauss ? "gauss" : "design"},
                                                 {"levels", levels},
                                                 {"beta", beta}}));
  out.commit();
  return kExitOk;
}

// A HEALPix map from needlet coefficients (zhf needlets analyze's file): the frame's synthesis to
// SH, then the SH at every pixel centre.
int run_needlet_synthesize(const NeedletOptions& o) {
  if (o.in.empty()) throw UsageError("--in: required");
  if (o.healpix_out.empty()) throw UsageError("--healpix-out: required");
  if (o.nside.empty()) throw UsageError("--nside: required");
  const std::int64_t nside = integer_option("--nside", o.nside, 1, runtime::kMaxHealpixNside);
  healpix::HealpixOrdering ordering = healpix::HealpixOrdering::kRing;
  if (o.ordering == "nested") ordering = healpix::HealpixOrdering::kNested;
  else if (o.ordering != "ring") throw UsageError("--ordering: '" + io::excerpt(o.ordering) + "' is not ring or nested");
  if (ordering == healpix::HealpixOrdering::kNested && (nside & (nside - 1)) != 0)
    throw UsageError("--nside: " + std::to_string(nside) + " is not a power of two, as --ordering nested needs");
  io::PendingFile out(o.healpix_out);
  const runtime::json::Value root = io::read_json_file(o.in, runtime::kMaxCoefficientBytes);
  const runtime::json::Field top(root, o.in);
  top.allow_only({"format", "B", "lmax", "nodes", "levels", "beta"});
  const runtime::json::Field format = top.member("format");
  if (format.string() != kNeedletCoefficientsFormat) format.fail("'" + io::excerpt(format.string()) + "' is not " + kNeedletCoefficientsFormat);
  const double dilation = top.member("B").number(runtime::kMinDilation, runtime::kMaxDilation);
  const int lmax = top.member("lmax").integer(1, runtime::kMaxNeedletFrameBand);
  const bool gauss = top.member("nodes").one_of({"design", "gauss"}) == "gauss";
  const frames::NeedletFrame frame = needlet_frame(dilation, lmax, gauss);
  std::vector<double> beta;
  for (const runtime::json::Field& b : top.member("beta").items(frame.size())) beta.push_back(b.number());
  const std::vector<double> ring = healpix::synthesize_map(nside, frame.synthesize(beta), io::throw_if_interrupted);
  out.write(healpix::encode_healpix_map(healpix::map_from_ring(nside, ring, ordering)));
  out.commit();
  std::printf("%s: Nside %lld, %s, %zu pixels from %d needlet coefficients (B = %g, bands 0..%d)\n", o.healpix_out.c_str(),
              static_cast<long long>(nside), o.ordering.c_str(), ring.size(), frame.size(), dilation, lmax);
  return kExitOk;
}

// Shadowed transfer on a scene's ground, shaded by SH and by needlets at equal coefficient counts
// against the exact integral (frames/prt.h).
int run_needlet_prt(const NeedletOptions& o) {
  const double dilation = dilation_option(o.dilation);
  const int lmax = o.order.empty() && o.lmax.empty() ? 31 : top_band(o, 1, runtime::kMaxProjectionOrder - 1);
  frames::PrtScene scene;
  if (!frames::parse_prt_scene(o.scene, scene)) throw UsageError("--scene: '" + io::excerpt(o.scene) + "' is not sphere, corner or spheres");
  frames::PrtTransfer transfer;
  if (!frames::parse_prt_transfer(o.transfer, transfer)) throw UsageError("--transfer: '" + io::excerpt(o.transfer) + "' is not diffuse or glossy");
  const int side = static_cast<int>(integer_option("--side", o.side, 1, runtime::kMaxPrtSide));
  const int table_size = static_cast<int>(integer_option("--size", o.size, runtime::kMinNeedletTableSize, runtime::kMaxNeedletTableSize));
  const std::vector<int> kept = orders_option("--kept", o.kept, 1, 1 << 20);
  if (kept.size() > 16) throw UsageError("--kept: at most 16 counts (got " + std::to_string(kept.size()) + ")");
  std::unique_ptr<io::PendingFile> out, csv_out;
  if (!o.out.empty()) out = std::make_unique<io::PendingFile>(o.out);
  if (!o.csv.empty()) csv_out = std::make_unique<io::PendingFile>(o.csv);
  std::unique_ptr<io::PendingFile> shading_out;
  if (!o.shading_csv.empty()) shading_out = std::make_unique<io::PendingFile>(o.shading_csv);
  frames::Radiance sky = frames::sun_and_sky;
  if (o.sky != "sun") {
    // An equirectangular .hdr (row 0 at +z, phi from +x towards +y), its luminance at the
    // pixel holding the direction.
    auto image = std::make_shared<io::HdrImage>(io::read_hdr(o.sky));
    sky = [image](const frames::Point& w) {
      const double theta = std::acos(std::clamp(w[2], -1.0, 1.0)), phi = std::atan2(w[1], w[0]) + (w[1] < 0 ? 2 * runtime::kPi : 0.0);
      const int row = std::min(image->height - 1, static_cast<int>(theta / runtime::kPi * image->height));
      const int column = std::min(image->width - 1, static_cast<int>(phi / (2 * runtime::kPi) * image->width));
      const float* rgb = &image->rgb[3 * (static_cast<std::size_t>(row) * image->width + column)];
      return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
    };
  }
  const frames::NeedletFrame frame = needlet_frame(dilation, lmax, o.gauss);
  for (int k : kept)
    if (k > frame.size()) throw UsageError("--kept: " + std::to_string(k) + " is more than the frame's " + std::to_string(frame.size()) + " coefficients");
  const frames::PrtReport r = frames::prt_experiment(frame, scene, transfer, sky, side, kept, table_size, io::throw_if_interrupted);
  std::printf("%s scene, %s transfer, %s sky: %d vertices; SH bands 0..%d (%d coefficients), needlets B = %g (%d coefficients)\n", o.scene.c_str(),
              o.transfer.c_str(), o.sky == "sun" ? "sun and sky" : o.sky.c_str(), r.vertices, lmax, r.sh_coefficients, dilation, r.needlet_coefficients);
  std::printf("shading error against the exact integral (RMS / worst, relative to the exact RMS / largest); least value of the sky rebuilt (true: %.3g)\n", r.sky_min);
  std::printf("%8s %12s %12s %12s %12s %12s %12s\n", "K", "SH rms", "SH worst", "needlet rms", "needlet worst", "SH sky min", "needlet min");
  std::string csv = "# zhf needlets prt: K, SH rms, SH worst, needlet rms, needlet worst, SH sky min, needlet sky min\n";
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const frames::PrtRow& row : r.rows) {
    std::printf("%8d %12.3e %12.3e %12.3e %12.3e %12.3e %12.3e\n", row.kept, row.sh_rms, row.sh_worst, row.needlet_rms, row.needlet_worst, row.sh_sky_min,
                row.needlet_sky_min);
    char line[256];
    std::snprintf(line, sizeof line, "%d,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e\n", row.kept, row.sh_rms, row.sh_worst, row.needlet_rms, row.needlet_worst,
                  row.sh_sky_min, row.needlet_sky_min);
    csv += line;
    rows.push_back({{"kept", row.kept}, {"sh_rms", row.sh_rms}, {"sh_worst", row.sh_worst}, {"needlet_rms", row.needlet_rms},
                    {"needlet_worst", row.needlet_worst}, {"sh_sky_min", row.sh_sky_min}, {"needlet_sky_min", row.needlet_sky_min}});
  }
  std::printf("all coefficients: needlets - SH = %.2e of the exact RMS (Parseval)\n", r.parseval_gap);
  std::printf("sky turned through %d steps: largest change of a level's energy through tabulated rotation (%d entries):", 12, table_size);
  for (double c : r.level_energy_change) std::printf(" %.1e", c);
  std::printf("\nenergy held by the K largest needlet coefficients of the turned sky (SH bands: the same in every turn):\n");
  nlohmann::ordered_json held = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < kept.size(); ++i) {
    std::printf("  K = %d: %.6f .. %.6f\n", kept[i], r.kept_energy_least[i], r.kept_energy_greatest[i]);
    held.push_back({{"kept", kept[i]}, {"least", r.kept_energy_least[i]}, {"greatest", r.kept_energy_greatest[i]}});
  }
  if (csv_out) {
    csv_out->write(csv);
    csv_out->commit();
  }
  if (shading_out) {
    std::string text = "# zhf needlets prt: x, y, exact";
    for (const frames::PrtRow& row : r.rows) text += ", SH K=" + std::to_string(row.kept) + ", needlets K=" + std::to_string(row.kept);
    text += "\n";
    for (int v = 0; v < r.vertices; ++v) {
      char cell[64];
      std::snprintf(cell, sizeof cell, "%.6f,%.6f,%.6e", r.vertex_positions[v][0], r.vertex_positions[v][1], r.exact[v]);
      text += cell;
      for (const frames::PrtRow& row : r.rows) {
        std::snprintf(cell, sizeof cell, ",%.6e,%.6e", row.sh[v], row.needlet[v]);
        text += cell;
      }
      text += "\n";
    }
    shading_out->write(text);
    shading_out->commit();
  }
  if (out) {
    out->write(io::json_text(nlohmann::ordered_json{{"format", "zhf-needlet-prt-1"}, {"scene", o.scene}, {"transfer", o.transfer},
                                                    {"B", dilation}, {"lmax", lmax}, {"vertices", r.vertices},
                                                    {"sh_coefficients", r.sh_coefficients}, {"needlet_coefficients", r.needlet_coefficients},
                                                    {"exact_rms", r.exact_rms}, {"sky_min", r.sky_min}, {"parseval_gap", r.parseval_gap},
                                                    {"rows", rows}, {"level_energy_change", r.level_energy_change}, {"kept_energy", held}}));
    out->commit();
  }
  return kExitOk;
}

}  // namespace

void add_needlets_command(CLI::App& app, Action& action, const std::string& command_line) {
  CLI::App* nc = app.add_subcommand("needlets", "Spherical needlets: windows, kernel tables, tabulated rotation, analysis and synthesis of HEALPix maps");
  nc->require_subcommand(1);
  auto w = std::make_shared<NeedletOptions>();
  CLI::App* wc = nc->add_subcommand("window", "The windows b(l / B^j), every non-zero one for bands 0..lmax, their frame bounds and (--level) localisation");
  wc->add_option("--B", w->dilation, kDilationHelp);
  wc->add_option("--window", w->window, "standard (the C-infinity bump), spline (cubic B-spline step) or mexican (x^(2p) exp(-x^2)); default standard");
  wc->add_option("--mexican-order", w->mexican_order, "p of the Mexican window, 1.." + std::to_string(runtime::kMaxMexicanOrder) + " (default 1)");
  wc->add_option("--level", w->level, "Also print level J's kernel energy outside caps of radius k / B^J, k = 1, 2, 4, 8 (J in 0..12)");
  add_band_limit(wc, *w, runtime::kMaxNeedletBand);
  keep_old_spelling(wc, wc->add_option("--out", w->out, "Write the windows here: {\"B\", \"lmax\", \"b\": [[j, l, value], ...]}"), "--json", w->out);
  wc->callback([w, &action] { action = [w] { return run_needlet_window(*w); }; });
  auto an = std::make_shared<NeedletOptions>();
  CLI::App* ac = nc->add_subcommand("analyze", "Needlet coefficients of a HEALPix map, optionally masked");
  ac->add_option("--healpix", an->healpix, "The map (FITS, RING or NESTED; healpy's layout)");
  ac->add_option("--mask", an->mask, "A mask of the same Nside, values in [0, 1], multiplied into the map (UNSEEN pixels need 0)");
  ac->add_option("--iterations", an->iterations, "Jacobi steps of the map's SH projection, 0.." + std::to_string(runtime::kMaxHealpixIterations) + " (default 3)");
  ac->add_option("--B", an->dilation, kDilationHelp);
  add_band_limit(ac, *an, runtime::kMaxNeedletFrameBand);
  ac->add_flag("--gauss", an->gauss, "Gauss product cubatures instead of the shipped designs");
  ac->add_option("--out", an->out, std::string("Write the coefficients here (") + kNeedletCoefficientsFormat + ")");
  ac->callback([an, &action] { action = [an] { return run_needlet_analyze(*an); }; });
  auto sy = std::make_shared<NeedletOptions>();
  CLI::App* sc = nc->add_subcommand("synthesize", "A HEALPix map from needlet coefficients (zhf needlets analyze's file)");
  sc->add_option("--in", sy->in, std::string("The coefficients (") + kNeedletCoefficientsFormat + ")");
  sc->add_option("--healpix-out", sy->healpix_out, "Write the map here (FITS, double values)");
  sc->add_option("--nside", sy->nside, "The map's Nside, 1.." + std::to_string(runtime::kMaxHealpixNside));
  sc->add_option("--ordering", sy->ordering, "ring (default) or nested");
  sc->callback([sy, &action] { action = [sy] { return run_needlet_synthesize(*sy); }; });
  auto pr_t = std::make_shared<NeedletOptions>();
  CLI::App* rc = nc->add_subcommand("prt", "Shadowed transfer shaded with SH and with needlets at equal coefficient counts, against the exact integral");
  rc->add_option("--scene", pr_t->scene, "sphere (default; one sphere over the ground), corner (two walls) or spheres (three)");
  rc->add_option("--transfer", pr_t->transfer, "diffuse (default) or glossy (Phong lobe, exponent 20)");
  rc->add_option("--sky", pr_t->sky, "sun (default: an analytic sun and sky) or an equirectangular Radiance .hdr");
  rc->add_option("--side", pr_t->side, "Vertices per side of the ground grid, 1.." + std::to_string(runtime::kMaxPrtSide) + " (default 16)");
  rc->add_option("--kept", pr_t->kept, "Coefficient counts K per vertex, e.g. 16,64,256,1024 (the default)");
  rc->add_option("--B", pr_t->dilation, kDilationHelp);
  add_band_limit(rc, *pr_t, runtime::kMaxProjectionOrder - 1);
  rc->add_option("--size", pr_t->size, kTableSizeHelp + " (the tabulated rotation of the sky)");
  rc->add_flag("--gauss", pr_t->gauss, "Gauss product cubatures instead of the shipped designs");
  rc->add_option("--out", pr_t->out, "Write the report here (zhf-needlet-prt-1)");
  rc->add_option("--shading-csv", pr_t->shading_csv, "Write each vertex's shading here (x, y, exact, then SH and needlets per K): the images");
  rc->add_option("--csv", pr_t->csv, "Write the error table here (K, SH rms, SH worst, needlet rms, needlet worst, both skies' least values)");
  rc->callback([pr_t, &action] { action = [pr_t] { return run_needlet_prt(*pr_t); }; });
  auto t = std::make_shared<NeedletOptions>();
  CLI::App* tc = nc->add_subcommand("tables", "The needlet frame of bands 0..lmax: levels, kernel look-up error and tabulated rotation error per table size");
  tc->add_option("--B", t->dilation, kDilationHelp);
  add_band_limit(tc, *t, runtime::kMaxNeedletFrameBand);
  tc->add_option("--sizes", t->sizes, "Table sizes, e.g. 64,256,1024 (" + kTableSizeRange + "; default 64,256,1024,4096,16384)");
  tc->add_flag("--gauss", t->gauss, "Gauss product cubatures at every level instead of the shipped designs");
  keep_old_spelling(tc, tc->add_option("--out", t->out, "Write the tables here (zhf-needlet-tables-1)"), "--json", t->out);
  tc->callback([t, &action] { action = [t] { return run_needlet_tables(*t); }; });
  auto pr = std::make_shared<NeedletOptions>();
  CLI::App* pc = nc->add_subcommand("profile", "One level's needlet against the SH delta of its top band: energy and side lobes outside caps");
  pc->add_option("--B", pr->dilation, kDilationHelp);
  pc->add_option("--j", pr->j, "Level, 0..16 (default 1)");
  keep_old_spelling(pc, pc->add_option("--out", pr->out, "Write both profiles against theta here as CSV (degrees, each divided by its peak)"), "--csv", pr->out);
  pc->callback([pr, &action] { action = [pr] { return run_needlet_profile(*pr); }; });
  auto mk = std::make_shared<NeedletOptions>();
  CLI::App* mc = nc->add_subcommand("mask", "A signal cut around the equator: which SH and needlet coefficients the cut disturbs");
  mc->add_option("--B", mk->dilation, kDilationHelp);
  add_band_limit(mc, *mk, runtime::kMaxNeedletFrameBand);
  mc->add_option("--cut", mk->cut, "Half-width of the cut band in degrees of latitude, 0.1..80 (default 10)");
  mc->add_option("--margin", mk->margin, "Beyond the cut by this many half-wavelengths of the top band (pi / lmax of a level, pi / L for SH), 0..64 (default 4)");
  mc->add_flag("--gauss", mk->gauss, "Gauss product cubatures instead of the shipped designs");
  mc->callback([mk, &action] { action = [mk] { return run_needlet_mask(*mk); }; });
  auto e = std::make_shared<NeedletOptions>();
  CLI::App* ec = nc->add_subcommand("emit", "Emit a needlet expansion's evaluator (kernel look-up tables) as C++, GLSL, HLSL or WGSL");
  ec->add_option("--B", e->dilation, kDilationHelp);
  add_band_limit(ec, *e, runtime::kMaxNeedletFrameBand);
  ec->add_option("--size", e->size, kTableSizeHelp);
  ec->add_option("--interpolation", e->interpolation, "linear (default) or quadratic");
  ec->add_option("--lang", e->lang, "cpp, glsl, hlsl or wgsl")->required();
  ec->add_option("--prefix", e->prefix, "Prefix of every emitted name (default zhf_needlets)");
  ec->add_option("--set", e->set, "Shaders' data buffer: descriptor set / WGSL group, 0.." + std::to_string(runtime::kMaxStorageSet) + " (default 0)");
  ec->add_option("--binding", e->binding, "Shaders' data buffer: binding, 0.." + std::to_string(runtime::kMaxStorageBinding) + " (default 0)");
  ec->add_flag("--gauss", e->gauss, "Gauss product cubatures instead of the shipped designs");
  ec->add_option("--out", e->out, "The file to write")->required();
  ec->add_option("--data", e->data, "Also write the nodes, scales and tables as little-endian float32 (the shaders' storage buffer)");
  ec->callback([e, &action, command_line] { action = [e, command_line] { return run_needlet_emit(*e, command_line); }; });
  auto v = std::make_shared<NeedletOptions>();
  CLI::App* vc = nc->add_subcommand("verify", "Compile and run the emitted needlet evaluators against their CPU mirror and the exact expansion");
  vc->add_option("--B", v->dilation, kDilationHelp);
  add_band_limit(vc, *v, runtime::kMaxNeedletFrameBand);
  vc->add_option("--size", v->size, kTableSizeHelp);
  vc->add_option("--interpolation", v->interpolation, "linear (default) or quadratic");
  vc->add_option("--langs", v->langs, "Languages, e.g. cpp,glsl (default cpp,glsl,hlsl,wgsl)");
  vc->add_option("--compiler", v->compiler, "C++ compiler and leading arguments (default $CXX, else c++)");
  vc->add_flag("--gauss", v->gauss, "Gauss product cubatures instead of the shipped designs");
  keep_old_spelling(vc, vc->add_option("--out", v->out, "Write the results here (zhf-needlet-verify-1)"), "--json", v->out);
  vc->callback([v, &action] { action = [v] { return run_needlet_verify(*v); }; });
}

}  // namespace zhf::cli
