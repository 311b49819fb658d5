// zhf needlets prt: shadowed transfer shaded with SH and with needlets (frames/prt.h).
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "needlets.h"
#include "options.h"
#include "progress.h"
#include "zhf/frames/limits.h"
#include "zhf/frames/prt.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/hdr.h"
#include "zhf/io/signals.h"

namespace zhf::cli {

// Shadowed transfer on a scene's ground, shaded by SH and by needlets at equal coefficient counts
// against the exact integral (frames/prt.h).
int run_needlet_prt(const NeedletOptions& o) {
  const double dilation = dilation_option(o.dilation);
  const int lmax = o.order.empty() && o.lmax.empty() ? 31 : top_band(o, 1, frames::kMaxProjectionOrder - 1);
  frames::PrtScene scene;
  if (!frames::parse_prt_scene(o.scene, scene)) throw UsageError("--scene: '" + io::excerpt(o.scene) + "' is not open, sphere, corner or spheres");
  frames::PrtTransfer transfer;
  if (!frames::parse_prt_transfer(o.transfer, transfer)) throw UsageError("--transfer: '" + io::excerpt(o.transfer) + "' is not diffuse or glossy");
  const int side = static_cast<int>(integer_option("--side", o.side, 1, frames::kMaxPrtSide));
  const int table_size = static_cast<int>(integer_option("--size", o.size, frames::kMinNeedletTableSize, frames::kMaxNeedletTableSize));
  const std::vector<int> kept = orders_option("--kept", o.kept, 1, (frames::kMaxNeedletFrameBand + 1) * (frames::kMaxNeedletFrameBand + 1));
  if (kept.size() > std::size_t(frames::kMaxPrtKeptCounts))
    throw UsageError("--kept: at most " + std::to_string(frames::kMaxPrtKeptCounts) + " counts (got " + std::to_string(kept.size()) + ")");
  std::unique_ptr<io::PendingFile> out, csv_out;
  if (!o.out.empty()) out = std::make_unique<io::PendingFile>(o.out);
  if (!o.csv.empty()) csv_out = std::make_unique<io::PendingFile>(o.csv);
  std::unique_ptr<io::PendingFile> shading_out;
  if (!o.shading_csv.empty()) shading_out = std::make_unique<io::PendingFile>(o.shading_csv);
  frames::Radiance sky = frames::sun_and_sky;
  const bool analytic_sky = o.image.empty() || o.image == "sun";  // "sun": the old --sky's name for it
  if (!analytic_sky) {
    io::HdrImage image = io::read_hdr(o.image);
    sky = frames::equirectangular_sky(image.width, image.height, std::make_shared<const std::vector<float>>(std::move(image.rgb)));
  }
  const frames::NeedletFrame frame = needlet_frame(dilation, lmax, o.gauss);
  for (int k : kept)
    if (k > frame.size()) throw UsageError("--kept: " + std::to_string(k) + " is more than the frame's " + std::to_string(frame.size()) + " coefficients");
  const int threads = threads_option(o.threads);
  Progress progress("needlets prt", o.quiet, o.verbose);
  const frames::PrtReport r = frames::prt_experiment(
      frame, scene, transfer, sky, side, kept, table_size,
      [&](int done, int total) {
        io::throw_if_interrupted();
        progress.update(done, total, "vertices shaded exactly");
      },
      threads);
  progress.done();
  std::printf("%s scene, %s transfer, %s sky: %d vertices; SH bands 0..%d (%d coefficients), needlets B = %g (%d coefficients)\n", o.scene.c_str(),
              o.transfer.c_str(), analytic_sky ? "sun and sky" : o.image.c_str(), r.vertices, lmax, r.sh_coefficients, dilation, r.needlet_coefficients);
  std::printf("shading error against the exact integral (RMS / worst, relative to the exact RMS / largest); least value of the sky rebuilt (true: %.3g)\n", r.sky_min);
  std::printf("%6s %10s %10s %10s %10s %10s %10s %9s %9s %9s %10s %10s\n", "K", "SH rms", "SH worst", "best rms", "best worst", "needl rms",
              "needl worst", "SH bytes", "best B", "needl B", "SH sky min", "needl min");
  std::string csv =
      "# zhf needlets prt: K, SH rms, SH worst, needlet rms, needlet worst, SH sky min, needlet sky min, SH best-K rms, SH best-K worst, "
      "SH bytes, SH best-K bytes, needlet bytes (per vertex, 4-byte values and the indices they need)\n";
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const frames::PrtRow& row : r.rows) {
    std::printf("%6d %10.3e %10.3e %10.3e %10.3e %10.3e %10.3e %9d %9d %9d %10.3e %10.3e\n", row.kept, row.sh_rms, row.sh_worst, row.sh_best_rms,
                row.sh_best_worst, row.needlet_rms, row.needlet_worst, row.sh_bytes, row.sh_best_bytes, row.needlet_bytes, row.sh_sky_min,
                row.needlet_sky_min);
    char line[320];
    std::snprintf(line, sizeof line, "%d,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e,%d,%d,%d\n", row.kept, row.sh_rms, row.sh_worst, row.needlet_rms,
                  row.needlet_worst, row.sh_sky_min, row.needlet_sky_min, row.sh_best_rms, row.sh_best_worst, row.sh_bytes, row.sh_best_bytes,
                  row.needlet_bytes);
    csv += line;
    rows.push_back({{"kept", row.kept}, {"sh_rms", row.sh_rms}, {"sh_worst", row.sh_worst}, {"sh_best_rms", row.sh_best_rms},
                    {"sh_best_worst", row.sh_best_worst}, {"needlet_rms", row.needlet_rms}, {"needlet_worst", row.needlet_worst},
                    {"sh_bytes", row.sh_bytes}, {"sh_best_bytes", row.sh_best_bytes}, {"needlet_bytes", row.needlet_bytes},
                    {"sh_sky_min", row.sh_sky_min}, {"needlet_sky_min", row.needlet_sky_min}});
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
    for (const frames::PrtRow& row : r.rows)
      text += ", SH K=" + std::to_string(row.kept) + ", needlets K=" + std::to_string(row.kept) + ", SH best K=" + std::to_string(row.kept);
    text += "\n";
    for (int v = 0; v < r.vertices; ++v) {
      char cell[64];
      std::snprintf(cell, sizeof cell, "%.6f,%.6f,%.6e", r.vertex_positions[v][0], r.vertex_positions[v][1], r.exact[v]);
      text += cell;
      for (const frames::PrtRow& row : r.rows) {
        std::snprintf(cell, sizeof cell, ",%.6e,%.6e,%.6e", row.sh[v], row.needlet[v], row.sh_best[v]);
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

}  // namespace zhf::cli
