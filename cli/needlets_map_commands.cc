// zhf needlets analyze and synthesize: needlet coefficients of a HEALPix map, and a map from them.
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "needlets.h"
#include "options.h"
#include "zhf/frames/limits.h"
#include "zhf/healpix/limits.h"
#include "zhf/healpix/maps.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/limits.h"
#include "zhf/io/signals.h"
#include "zhf/io/json.h"

namespace zhf::cli {

// The needlet coefficients of a HEALPix map (masked: of the map times the mask): its SH to band L
// by the pixel quadrature and Jacobi steps, then the frame's analysis.
int run_needlet_analyze(const NeedletOptions& o) {
  const double dilation = dilation_option(o.dilation);
  const int lmax = top_band(o, 1, frames::kMaxNeedletFrameBand);
  const int iterations = static_cast<int>(integer_option("--iterations", o.iterations, 0, healpix::kMaxHealpixIterations));
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
  if (o.out.empty()) throw UsageError("--out: required");
  if (o.nside.empty()) throw UsageError("--nside: required");
  const std::int64_t nside = integer_option("--nside", o.nside, 1, healpix::kMaxHealpixNside);
  healpix::HealpixOrdering ordering = healpix::HealpixOrdering::kRing;
  if (o.ordering == "nested") ordering = healpix::HealpixOrdering::kNested;
  else if (o.ordering != "ring") throw UsageError("--ordering: '" + io::excerpt(o.ordering) + "' is not ring or nested");
  if (ordering == healpix::HealpixOrdering::kNested && (nside & (nside - 1)) != 0)
    throw UsageError("--nside: " + std::to_string(nside) + " is not a power of two, as --ordering nested needs");
  io::PendingFile out(o.out);
  const io::json::Json root = io::json::read_file(o.in, io::kMaxCoefficientBytes);
  const io::json::Field top(root, o.in);
  top.allow_only({"format", "B", "lmax", "nodes", "levels", "beta"});
  const io::json::Field format = top.member("format");
  if (format.string() != kNeedletCoefficientsFormat) format.fail("'" + io::excerpt(format.string()) + "' is not " + kNeedletCoefficientsFormat);
  const double dilation = top.member("B").number(frames::kMinDilation, frames::kMaxDilation);
  const int lmax = top.member("lmax").integer(1, frames::kMaxNeedletFrameBand);
  const bool gauss = top.member("nodes").one_of({"design", "gauss"}) == "gauss";
  const frames::NeedletFrame frame = needlet_frame(dilation, lmax, gauss);
  std::vector<double> beta;
  for (const io::json::Field& b : top.member("beta").items(frame.size())) beta.push_back(b.number());
  const std::vector<double> ring = healpix::synthesize_map(nside, frame.synthesize(beta), io::throw_if_interrupted);
  out.write(healpix::encode_healpix_map(healpix::map_from_ring(nside, ring, ordering)));
  out.commit();
  std::printf("%s: Nside %lld, %s, %zu pixels from %d needlet coefficients (B = %g, bands 0..%d)\n", o.out.c_str(),
              static_cast<long long>(nside), o.ordering.c_str(), ring.size(), frame.size(), dilation, lmax);
  return kExitOk;
}

}  // namespace zhf::cli
