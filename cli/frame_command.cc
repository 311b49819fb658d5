// zhf frame: frame bounds of the zonal lobes at a point set or a lobe table's lobes
// (frames/frame.h).
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "options.h"
#include "zhf/frames/designs.h"
#include "zhf/frames/frame.h"
#include "zhf/frames/limits.h"
#include "zhf/io/files.h"
#include "zhf/io/signals.h"
#include "zhf/runtime/table_io.h"

namespace zhf::cli {
namespace {

struct FrameOptions {
  std::string directions, table, bands;
  std::string out;
};

int run_frame(const FrameOptions& o) {
  if (o.directions.empty() == o.table.empty()) throw UsageError("--directions or --table: give exactly one");
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
  if (!o.directions.empty()) {
    if (o.bands.empty()) throw UsageError("--bands: required with --directions");
    jobs.push_back({frames::read_points(o.directions), lmin, lmax});
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


}  // namespace

void add_frame_command(CLI::App& app, Action& action) {
  auto f = std::make_shared<FrameOptions>();
  CLI::App* fc = app.add_subcommand("frame", "Frame bounds of the zonal lobes at a set of directions, for a band range");
  keep_old_spelling(fc, fc->add_option("--directions", f->directions, "Directions: a JSON array of [x, y, z] or a design file"), "--points",
                    f->directions);
  fc->add_option("--table", f->table, "A lobe table's lobes (without --bands: each band on its own lobes)");
  fc->add_option("--bands", f->bands, "Bands L0..L1 (0.." + std::to_string(frames::kMaxFrameBand) + ")");
  keep_old_spelling(fc, fc->add_option("--out", f->out, "Write the bounds here (zhf-frame-1)"), "--json", f->out);
  fc->callback([f, &action] { action = [f] { return run_frame(*f); }; });
}

}  // namespace zhf::cli
