#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "options.h"
#include "progress.h"
#include "zhf/frames/cubature.h"
#include "zhf/frames/limits.h"
#include "zhf/frames/projection.h"
#include "zhf/healpix/limits.h"
#include "zhf/healpix/maps.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/hdr.h"
#include "zhf/io/signals.h"
#include "zhf/pipeline/data_root.h"

namespace zhf::cli {
namespace {

struct ProjectOptions {
  std::string order = "3", image, healpix, mask, iterations = "3", function, nodes = "design", degree, out, csv, threads = "0";
  bool compare = false, quiet = false, verbose = false;
};

nlohmann::ordered_json coefficient_json(const std::vector<std::vector<double>>& channels) {
  if (channels.size() == 1) return nlohmann::ordered_json::array({channels[0]});
  nlohmann::ordered_json vector = nlohmann::ordered_json::array();
  for (const std::vector<double>& c : channels) vector.push_back(c);
  return nlohmann::ordered_json::array({vector});
}

frames::Cubature nodes_of(const std::string& kind, int degree) {
  if (kind == "design") return frames::design_cubature(pipeline::data_root().designs(), degree);
  if (kind == "gauss") return frames::gauss_product_cubature(degree);
  if (kind == "grid") return frames::equirectangular_nodes(2 * (degree + 1), degree + 1);
  throw UsageError("--nodes: '" + io::excerpt(kind) + "' is not design, gauss or grid");
}

// Error per sample count of designs, Gauss product rules and equal-angle grids, on the test
// functions, at one order.
int run_compare(const ProjectOptions& o, int order, int threads) {
  std::unique_ptr<io::PendingFile> csv;
  if (!o.csv.empty()) csv = std::make_unique<io::PendingFile>(o.csv);
  std::string text = "# zhf project --compare: nodes, samples, max error (band-limited), max error (30-degree cap)\n";
  std::printf("order %d: max coefficient error on a function of bands 0..7 and on a 30-degree cap\n", order);
  std::printf("%-22s %8s %16s %16s\n", "nodes", "samples", "bands 0..7", "cap");
  const std::string designs = pipeline::data_root().designs();
  std::vector<frames::Cubature> sets;
  for (int t : {2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 25, 31}) {
    frames::Cubature c = frames::design_cubature(designs, t);
    if (c.name.rfind("design", 0) == 0) sets.push_back(std::move(c));
  }
  for (int d : {2, 4, 6, 8, 10, 14, 20, 30, 40, 60, 80}) sets.push_back(frames::gauss_product_cubature(d));
  for (int h : {2, 4, 8, 16, 32, 64, 128, 256}) sets.push_back(frames::equirectangular_nodes(2 * h, h));
  Progress progress("project", o.quiet, o.verbose);
  for (std::size_t s = 0; s < sets.size(); ++s) {
    const frames::Cubature& c = sets[s];
    progress.update(double(s), double(sets.size()), "node sets");
    const frames::ProjectionError e = frames::projection_error(c, order, threads);
    std::printf("%-22s %8d %16.3e %16.3e\n", e.nodes.c_str(), e.samples, e.band_limited, e.cap);
    char line[128];
    std::snprintf(line, sizeof line, "%s,%d,%.6e,%.6e\n", e.nodes.substr(0, e.nodes.find(' ')).c_str(), e.samples, e.band_limited, e.cap);
    text += line;
    io::throw_if_interrupted();
  }
  progress.done();
  if (csv) {
    csv->write(text);
    csv->commit();
  }
  return kExitOk;
}

int run_project(const ProjectOptions& o) {
  const int order = static_cast<int>(integer_option("--order", o.order, 1, frames::kMaxProjectionOrder));
  const int threads = threads_option(o.threads);
  if (o.compare) {
    if (!o.image.empty() || !o.function.empty() || !o.out.empty()) throw UsageError("--compare: takes no --image, --function or --out");
    return run_compare(o, order, threads);
  }
  if (o.image.empty() + o.healpix.empty() + o.function.empty() != 2) throw UsageError("--image, --healpix or --function: give exactly one");
  if (!o.mask.empty() && o.healpix.empty()) throw UsageError("--mask: only with --healpix");
  const int iterations = static_cast<int>(integer_option("--iterations", o.iterations, 0, healpix::kMaxHealpixIterations));
  if (o.out.empty()) throw UsageError("--out: required");
  io::PendingFile out(o.out);  // refuse an unwritable output before the work
  std::vector<std::vector<double>> coefficients;
  Progress progress("project", o.quiet, o.verbose);
  const auto samples_done = [&progress](std::size_t done, std::size_t samples) {
    io::throw_if_interrupted();
    progress.update(double(done), double(samples), "samples");
  };
  if (!o.healpix.empty()) {
    const healpix::MaskedSignal signal = healpix::read_masked_signal(o.healpix, o.mask);
    if (order - 1 > healpix::max_analysis_band(signal.nside))
      throw UsageError("--order: band " + std::to_string(order - 1) + " is above 4 Nside = " + std::to_string(healpix::max_analysis_band(signal.nside)) + ", the most " +
                       io::excerpt(o.healpix) + "'s pixels resolve");
    int pass = 0;  // a quadrature, then a synthesis and an analysis per Jacobi step
    coefficients = {healpix::analyze_map(signal.nside, signal.ring, order, iterations, [&] {
      io::throw_if_interrupted();
      progress.update(pass++, 1 + 2 * iterations, "passes over the map");
    })};
    progress.done();
    std::printf("%s: Nside %lld (%zu pixels), sky fraction %.4f, projected to order %d with %d Jacobi steps\n", o.healpix.c_str(),
                static_cast<long long>(signal.nside), signal.ring.size(), signal.sky_fraction, order, iterations);
  } else if (!o.image.empty()) {
    const io::HdrImage image = io::read_hdr(o.image);
    const frames::Cubature nodes = frames::equirectangular_nodes(image.width, image.height);
    coefficients = frames::project_samples(nodes, std::vector<double>(image.rgb.begin(), image.rgb.end()), 3, order, threads, samples_done);
    progress.done();
    std::printf("%s: %d x %d pixels projected to order %d (RGB)\n", o.image.c_str(), image.width, image.height, order);
  } else {
    frames::TestFunction f;
    if (o.function == "band-limited") f = frames::TestFunction::kBandLimited;
    else if (o.function == "cap") f = frames::TestFunction::kCap;
    else throw UsageError("--function: '" + io::excerpt(o.function) + "' is not band-limited or cap");
    const int degree = o.degree.empty() ? 7 + order - 1 : static_cast<int>(integer_option("--degree", o.degree, 0, frames::kMaxCubatureDegree));
    const frames::Cubature nodes = nodes_of(o.nodes, degree);
    std::vector<double> values;
    for (const frames::Point& p : nodes.points) values.push_back(frames::test_function(f, p));
    coefficients = frames::project_samples(nodes, values, 1, order, threads, samples_done);
    const std::vector<double> exact = frames::test_function_coefficients(f, order);
    double worst = 0;
    for (std::size_t i = 0; i < exact.size(); ++i) worst = std::max(worst, std::abs(coefficients[0][i] - exact[i]));
    progress.done();
    std::printf("%s on %s (%zu samples), order %d: max error %.3e against the closed form\n", o.function.c_str(), nodes.name.c_str(),
                nodes.points.size(), order, worst);
  }
  out.write(io::json_text(coefficient_json(coefficients)));
  out.commit();
  return kExitOk;
}

}  // namespace

void add_project_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<ProjectOptions>();
  CLI::App* c = app.add_subcommand("project", "Project samples into SH: an equirectangular Radiance .hdr image, a HEALPix map, or a test function on chosen nodes");
  c->add_option("--order", o->order, "Order N of the coefficients, 1.." + std::to_string(frames::kMaxProjectionOrder) + " (default 3)");
  c->add_option("--image", o->image, "A Radiance .hdr equirectangular image (row 0 at +z, phi from +x towards +y): RGB coefficients");
  c->add_option("--healpix", o->healpix, "A HEALPix map (FITS, RING or NESTED; healpy's layout): its first column's coefficients");
  c->add_option("--mask", o->mask, "With --healpix: a HEALPix mask of the same Nside, values in [0, 1], multiplied into the map (UNSEEN pixels need 0)");
  c->add_option("--iterations", o->iterations, "With --healpix: Jacobi steps after the pixel quadrature, 0.." + std::to_string(healpix::kMaxHealpixIterations) + " (default 3, as healpy's iter)");
  c->add_option("--function", o->function, "A test function with known coefficients: band-limited (bands 0..7) or cap (30 degrees)");
  c->add_option("--nodes", o->nodes, "With --function: design (default), gauss or grid");
  c->add_option("--degree", o->degree, "With --function: the nodes' degree, 0.." + std::to_string(frames::kMaxCubatureDegree) + " (default 7 + N - 1, exact for the band-limited function)");
  c->add_flag("--compare", o->compare, "Print the error per sample count of designs, Gauss rules and equal-angle grids on both test functions");
  c->add_option("--csv", o->csv, "With --compare: write the table here");
  c->add_option("--out", o->out, "Write the coefficients here (JSON, as zhf rotate reads them)");
  add_threads_option(c, o->threads);
  add_progress_flags(c, o->quiet, o->verbose);
  c->callback([o, &action] { action = [o] { return run_project(*o); }; });
}

}  // namespace zhf::cli
