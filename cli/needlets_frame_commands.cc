// zhf needlets window, tables, profile and mask: the frame's windows, kernel tables and
// localisation, reported from frames/needlet_studies.h and frames/needlets.h.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "needlets.h"
#include "options.h"
#include "progress.h"
#include "zhf/frames/limits.h"
#include "zhf/frames/needlet_studies.h"
#include "zhf/frames/windows.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/signals.h"
#include "zhf/runtime/sh_eval.h"

namespace zhf::cli {

int run_needlet_window(const NeedletOptions& o) {
  frames::Window w;
  w.dilation = dilation_option(o.dilation);
  if (!frames::parse_window_kind(o.window, w.kind)) throw UsageError("--window: '" + runtime::excerpt(o.window) + "' is not standard, spline or mexican");
  w.order = static_cast<int>(integer_option("--mexican-order", o.mexican_order, 1, frames::kMaxMexicanOrder));
  const int lmax = top_band(o, 0, frames::kMaxNeedletBand);
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
    const frames::WindowFrameBounds bounds = frames::window_frame_bounds(w, lmax);
    std::printf("sum over levels of b^2, bands 1..%d: %.17g .. %.17g, ratio %.6g (frame bounds; 1 .. 1 is a tight frame)\n", lmax,
                bounds.least, bounds.greatest, bounds.greatest / bounds.least);
    report["frame_bounds"] = {bounds.least, bounds.greatest};
  }
  if (!o.level.empty()) {
    // Localisation: level j's kernel energy outside caps of radius k / B^j, k = 1, 2, 4, 8.
    const int j = static_cast<int>(integer_option("--level", o.level, 0, frames::kMaxLocalisationLevel));
    nlohmann::ordered_json caps = nlohmann::ordered_json::array();
    std::printf("level %d kernel, energy outside the cap of radius k / B^%d:", j, j);
    const std::vector<double> ks = {1, 2, 4, 8};
    const std::vector<double> outside = frames::kernel_energy_outside_caps(w, j, ks);
    for (std::size_t i = 0; i < ks.size(); ++i) {
      std::printf("  k=%g %.3e", ks[i], outside[i]);
      caps.push_back({ks[i], outside[i]});
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
  const int lmax = top_band(o, 1, frames::kMaxNeedletFrameBand);
  const std::vector<int> sizes = orders_option("--sizes", o.sizes, frames::kMinNeedletTableSize, frames::kMaxNeedletTableSize);
  if (sizes.size() > frames::kMaxNeedletTableSizes)
    throw UsageError("--sizes: at most " + std::to_string(frames::kMaxNeedletTableSizes) + " sizes (got " + std::to_string(sizes.size()) + ")");
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
  const char* const how_names[] = {"linear", "quadratic"};
  Progress progress("needlets tables", o.quiet, o.verbose);
  std::size_t rotations = 0;  // two a size: linear and quadratic
  const frames::TableStudy study = frames::needlet_table_study(frame, sizes, [&] {
    io::throw_if_interrupted();
    progress.update(double(++rotations), 2.0 * double(sizes.size()), "tabulated rotations");
  });
  progress.done();

  // Kernel tables: the worst level's error relative to its peak.
  nlohmann::ordered_json kernel_rows = nlohmann::ordered_json::array();
  std::printf("\nkernel table (max error / peak, worst level)\n%8s %12s %12s\n", "size", "linear", "quadratic");
  for (const frames::TableSizeErrors& s : study.sizes) {
    std::printf("%8d %12.3e %12.3e\n", s.size, s.kernel[0], s.kernel[1]);
    kernel_rows.push_back({{"size", s.size}, {how_names[0], s.kernel[0]}, {how_names[1], s.kernel[1]}});
  }

  // Rotation of a fixed unit-norm signal by a fixed turn: max coefficient error against the exact path.
  nlohmann::ordered_json rotation_rows = nlohmann::ordered_json::array();
  std::printf("\nrotation of %d coefficients (max error against the exact path; exact path %.3g ms)\n%8s %12s %12s %12s %12s\n",
              frame.size(), study.exact_seconds * 1e3, "size", "linear", "ms", "quadratic", "ms");
  for (const frames::TableSizeErrors& s : study.sizes) {
    std::printf("%8d %12.3e %12.3g %12.3e %12.3g\n", s.size, s.rotation[0], s.rotation_seconds[0] * 1e3, s.rotation[1],
                s.rotation_seconds[1] * 1e3);
    rotation_rows.push_back({{"size", s.size}, {how_names[0], s.rotation[0]}, {how_names[1], s.rotation[1]}});
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
// One level's needlet against the SH delta of the same top band: localisation, and the profiles.
int run_needlet_profile(const NeedletOptions& o) {
  const double dilation = dilation_option(o.dilation);
  const std::string& level = o.level.empty() ? std::string("1") : o.level;
  const int j = static_cast<int>(integer_option("--level", level, 0, frames::kMaxProfileLevel));
  if (std::pow(dilation, j + 1) > frames::kMaxProfileBand + 1)
    throw UsageError("--level: level " + level + " of B = " + o.dilation + " reaches past band " + std::to_string(frames::kMaxProfileBand));
  std::unique_ptr<io::PendingFile> out;
  if (!o.out.empty()) out = std::make_unique<io::PendingFile>(o.out);
  const frames::NeedletProfile p = frames::needlet_profile(dilation, j);
  std::printf("B = %g, level %d: bands %d..%d (SH delta: bands 0..%d)\n", dilation, j, p.first_band, p.top_band, p.top_band);
  std::printf("%12s %22s %22s %16s %16s\n", "cap (deg)", "needlet outside", "SH delta outside", "needlet lobe", "SH delta lobe");
  for (const frames::ProfileCap& c : p.caps)
    std::printf("%12.2f %22.3e %22.3e %16.3e %16.3e\n", c.cap * 180 / runtime::kPi, c.needlet.outside_energy, c.delta.outside_energy,
                c.needlet.sidelobe, c.delta.sidelobe);
  if (out) {
    std::string csv = "# zhf needlets profile: theta in degrees, needlet / its peak, SH delta / its peak\n";
    for (const frames::ProfileSample& s : p.samples) {
      char line[96];
      std::snprintf(line, sizeof line, "%.4f,%.9g,%.9g\n", s.theta * 180 / runtime::kPi, s.needlet, s.delta);
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
  const int lmax = top_band(o, 1, frames::kMaxNeedletFrameBand);
  const double cut = number_option("--cut", o.cut, frames::kMinMaskCut, frames::kMaxMaskCut) * runtime::kPi / 180;
  const double margin = number_option("--margin", o.margin, 0, frames::kMaxMaskMargin);
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

}  // namespace zhf::cli
