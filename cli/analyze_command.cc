#include <cstdio>
#include <memory>

#include <Eigen/Geometry>

#include "commands.h"
#include "options.h"
#include "zhf/codegen/limits.h"
#include "zhf/codegen/scene.h"
#include "zhf/io/coefficients.h"
#include "zhf/io/files.h"
#include "zhf/io/limits.h"
#include "zhf/io/signals.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/analysis.h"
#include "zhf/sh/limits.h"

namespace zhf::cli {
namespace {

struct AnalyzeOptions {
  std::string coeffs;
  std::string tolerance = runtime::format_number(sh::kDefaultZonalFit);
  int channels = 0;
  std::string json;
  std::string scene_out;
};

nlohmann::ordered_json vec3(const Eigen::Vector3d& v) { return {v[0], v[1], v[2]}; }

int run_analyze(const AnalyzeOptions& options) {
  struct {
    const std::string& coeffs;
    double tolerance;
    const std::string& json;
    const std::string& scene_out;
  } o{options.coeffs, number_option("--tolerance", options.tolerance, sh::kMinZonalTolerance, 1.0), options.json, options.scene_out};
  for (const std::string& out : {o.json, o.scene_out})
    if (!out.empty()) io::PendingFile check(out);  // refuse an unwritable output before the work
  const io::CoefficientFile file = io::read_coefficients(o.coeffs, options.channels);
  std::vector<Eigen::VectorXd> signals;
  for (const auto& s : file.signals) signals.push_back(Eigen::Map<const Eigen::VectorXd>(s.data(), Eigen::Index(s.size())));
  const sh::EnergyReport energy = sh::analyze_energy(signals, o.tolerance);

  // Zonal: every signal within the tolerance, about one common axis.
  int zonal_count = 0;
  double worst_residual = 0;
  bool common = true;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  bool have_axis = false;
  nlohmann::ordered_json fits = nlohmann::ordered_json::array();
  for (const Eigen::VectorXd& f : signals) {
    const sh::ZonalFit fit = sh::fit_zonal(f);
    worst_residual = std::max(worst_residual, fit.residual);
    if (fit.residual <= o.tolerance) ++zonal_count;
    if (!fit.constant) {
      if (!have_axis) {
        axis = fit.axis;
        have_axis = true;
      } else if (axis.cross(fit.axis).norm() > zhf::tolerance::kSameAxis) {
        common = false;
      }
    }
    fits.push_back({{"zonal", fit.residual <= o.tolerance}, {"residual", fit.residual}, {"axis", vec3(fit.axis)},
                    {"weights", fit.weights}});
  }
  const bool zonal = zonal_count == static_cast<int>(signals.size()) && common;

  double total = 0;
  for (double e : energy.band_energy) total += e;
  std::printf("%s: %zu vectors x %d channel%s, order %d (%d coefficients)\n", o.coeffs.c_str(),
              file.signals.size() / file.channels, file.channels, file.channels == 1 ? "" : "s", file.order,
              file.order * file.order);
  std::printf("band      energy   share   error if cut here (keep bands < N)\n");
  for (int l = 0; l < energy.order; ++l)
    std::printf("%4d  %10.3e  %5.1f%%   N=%-3d %.3e\n", l, energy.band_energy[l],
                total > 0 ? 100 * energy.band_energy[l] / total : 0.0, l + 1, energy.truncation_error[l]);
  std::printf("smallest order within relative L2 error %.3g: N = %d\n", o.tolerance, energy.smallest_order);
  if (energy.zero_bands.empty()) {
    std::printf("band-sparse: no (every band below N carries energy)\n");
  } else {
    std::printf("band-sparse: bands");
    for (int l : energy.zero_bands) std::printf(" %d", l);
    std::printf(" can be treated as zero\n");
  }
  if (zonal)
    std::printf("zonal: yes, about (%.12f, %.12f, %.12f) (worst residual %.2e)\n", axis[0], axis[1], axis[2], worst_residual);
  else
    std::printf("zonal: no (%d of %zu signals zonal%s; worst residual %.2e)\n", zonal_count, signals.size(),
                common ? "" : ", axes differ", worst_residual);

  // Both outputs are made before either is written: one refused is neither written.
  std::string json_text, scene_text;
  if (!o.json.empty()) {
    nlohmann::ordered_json j;
    j["format"] = "zhf-analysis-1";
    j["source"] = o.coeffs;
    j["tolerance"] = o.tolerance;
    j["order"] = file.order;
    j["channels"] = file.channels;
    j["vectors"] = file.signals.size() / file.channels;
    j["band_energy"] = energy.band_energy;
    j["truncation_error"] = energy.truncation_error;
    j["smallest_order"] = energy.smallest_order;
    j["zero_bands"] = energy.zero_bands;
    j["zonal"] = zonal;
    if (zonal) j["axis"] = vec3(axis);
    j["signals"] = fits;
    json_text = io::json_text(j);
  }
  if (!o.scene_out.empty()) {
    codegen::Scene scene;
    scene.targets = codegen::all_languages();
    codegen::SceneSignal signal;
    signal.name = "analyzed";
    signal.order = std::max(2, energy.smallest_order);
    signal.channels = file.channels == 2 ? 3 : file.channels;
    signal.variants = {zonal ? "zonal" : "standard"};
    for (int l : energy.zero_bands)
      if (l < signal.order) signal.zero_bands.push_back(l);
    if (signal.order > codegen::kMaxEmitOrder)
      throw UsageError("--scene-out: the data needs order " + std::to_string(signal.order) + ", zhf emits up to " +
                       std::to_string(codegen::kMaxEmitOrder));
    scene.signals.push_back(signal);
    scene_text = io::json_text(scene.to_json());
  }
  // The report and the scene spec are one result: both are written, or neither.
  io::PendingFiles outputs;
  if (!o.json.empty()) outputs.add(o.json).write(json_text);
  if (!o.scene_out.empty()) outputs.add(o.scene_out).write(scene_text);
  outputs.commit();
  if (!o.json.empty()) std::printf("wrote %s\n", o.json.c_str());
  if (!o.scene_out.empty())
    std::printf("wrote %s (a scene spec for zhf generate --scene; edit targets and variants to taste)\n", o.scene_out.c_str());
  return kExitOk;
}

}  // namespace

void add_analyze_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<AnalyzeOptions>();
  CLI::App* c = app.add_subcommand("analyze", "Per-band energy, the order the data needs, known-zero bands, zonal axis");
  c->add_option("--coeffs", o->coeffs, "SH coefficient vectors: JSON array or text, one vector per line")->required();
  c->add_option("--tolerance", o->tolerance, "Relative L2 error allowed, " + runtime::format_number(sh::kMinZonalTolerance) + "..1 (default " + runtime::format_number(sh::kDefaultZonalFit) + "); also the zonal residual bound");
  c->add_option("--channels", o->channels, "Channels per vector (text: numbers per line split evenly; JSON: checked)")
      ->check(CLI::Range(1, io::kMaxChannels));
  keep_old_spelling(c, c->add_option("--out", o->json, "Write the analysis as JSON here"), "--json", o->json);
  c->add_option("--scene-out", o->scene_out, "Write a scene spec (zhf-scene-1) for this data here");
  c->callback([o, &action] { action = [o] { return run_analyze(*o); }; });
}

}  // namespace zhf::cli
