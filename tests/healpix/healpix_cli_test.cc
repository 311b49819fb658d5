// zhf project --healpix, zhf needlets analyze / synthesize through the real binary: coefficients of
// a band-limited map, masks, the needlet round trip to a map file, and malformed maps refused.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "test_support.h"
#include "test_tolerances.h"
#include "zhf/healpix/fits.h"
#include "zhf/healpix/maps.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"

namespace zhf::healpix {
namespace {

namespace tol = zhf::tolerance;

// Bands 0..order-1 with fixed, uneven values.
std::vector<double> known_sh(int order) {
  std::vector<double> sh(static_cast<std::size_t>(order) * order);
  for (std::size_t i = 0; i < sh.size(); ++i) sh[i] = std::sin(1.0 + 2.7 * static_cast<double>(i)) / (1.0 + std::sqrt(static_cast<double>(i)));
  return sh;
}

void write_map(const std::string& path, std::int64_t nside, const std::vector<double>& ring, HealpixOrdering ordering) {
  write_healpix_map(path, map_from_ring(nside, ring, ordering));
}

TEST(HealpixCli, ProjectRecoversABandLimitedMapInEitherOrdering) {
  const test::TempDir dir;
  const int nside = 32, order = 9;
  const std::vector<double> sh = known_sh(order);
  const std::vector<double> ring = synthesize_map(nside, sh);
  for (const HealpixOrdering ordering : {HealpixOrdering::kRing, HealpixOrdering::kNested}) {
    const std::string map = (dir / "map.fits").string(), out = (dir / "c.json").string();
    write_map(map, nside, ring, ordering);
    const test::RunResult r = test::run_zhf({"project", "--healpix", map, "--order", std::to_string(order), "--out", out});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json c = test::read_json(out)[0];
    ASSERT_EQ(c.size(), sh.size());
    for (int l = 0; l < order; ++l)
      for (int m = -l; m <= l; ++m)
        EXPECT_NEAR(c[runtime::index(l, m)].get<double>(), sh[runtime::index(l, m)], tol::kHealpixProjection) << "band " << l << ", m " << m;
  }
}

TEST(HealpixCli, MaskedNeedletsRoundTripToAMapFile) {
  const test::TempDir dir;
  const int nside = 16, order = 9;
  const std::vector<double> ring = synthesize_map(nside, known_sh(order));
  // The full map's needlets synthesise the map back (a tight frame on bands < order).
  const std::string map = (dir / "map.fits").string(), beta = (dir / "beta.json").string(), back = (dir / "back.fits").string();
  write_map(map, nside, ring, HealpixOrdering::kRing);
  test::RunResult r = test::run_zhf({"needlets", "analyze", "--healpix", map, "--order", std::to_string(order), "--out", beta});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // --healpix-out: the old spelling of --out.
  r = test::run_zhf({"needlets", "synthesize", "--in", beta, "--healpix-out", back, "--nside", std::to_string(nside), "--ordering", "nested"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const HealpixMap written = read_healpix_map(back);
  EXPECT_EQ(written.ordering, HealpixOrdering::kNested);
  const std::vector<double> again = ring_pixels(written);
  for (std::size_t p = 0; p < ring.size(); ++p) ASSERT_NEAR(again[p], ring[p], tol::kHealpixProjection * 10) << "ring pixel " << p;

  // A galactic-cut mask: UNSEEN under it is accepted, and the needlets centred there are counted.
  std::vector<double> cut = ring, mask(ring.size(), 1.0);
  for (std::size_t p = 0; p < ring.size(); ++p)
    if (std::abs(pixel_centre(nside, static_cast<std::int64_t>(p))[2]) < std::sin(20 * M_PI / 180)) cut[p] = kHealpixUnseen, mask[p] = 0;
  const std::string cut_path = (dir / "cut.fits").string(), mask_path = (dir / "mask.fits").string();
  write_map(cut_path, nside, cut, HealpixOrdering::kRing);
  write_map(mask_path, nside, mask, HealpixOrdering::kNested);
  r = test::run_zhf({"needlets", "analyze", "--healpix", cut_path, "--mask", mask_path, "--order", std::to_string(order), "--out", beta});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int masked = 0;
  const nlohmann::json report = test::read_json(beta);
  for (const nlohmann::json& level : report["levels"]) masked += level["masked"].get<int>();
  EXPECT_GT(masked, 0) << r.out;
  EXPECT_NE(r.out.find("sky fraction 0.6"), std::string::npos) << r.out;
}

TEST(HealpixCli, MalformedMapsAreRefusedInOneLineAndNothingIsWritten) {
  const test::TempDir dir;
  const std::string good = (dir / "good.fits").string(), out = (dir / "out.json").string();
  HealpixMap map;
  map.nside = 4;
  map.pixels.assign(static_cast<std::size_t>(healpix_pixels(4)), 0.5);
  write_healpix_map(good, map);
  const std::string bytes = test::read_text(good);
  auto file = [&](const std::string& name, const std::string& content) {
    const std::string path = (dir / name).string();
    test::write_text(path, content);
    return path;
  };
  std::string wrong_nside = bytes;
  const std::size_t at = wrong_nside.find("NSIDE   =");
  wrong_nside.replace(at + 10, 20, "                   8");
  HealpixMap nan = map, unseen = map, other = map;
  nan.pixels[9] = std::nan("");
  unseen.pixels[4] = kHealpixUnseen;
  other.nside = 2;
  other.pixels.assign(48, 1.0);
  write_healpix_map((dir / "nan.fits").string(), nan);
  write_healpix_map((dir / "unseen.fits").string(), unseen);
  write_healpix_map((dir / "two.fits").string(), other);
  HealpixMap half = map;
  half.pixels.assign(half.pixels.size(), 1.5);
  write_healpix_map((dir / "half.fits").string(), half);
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::string d = dir.string() + "/";
  const std::vector<Case> cases = {
      {{"--healpix", file("truncated.fits", bytes.substr(0, bytes.size() - 100))}, "truncated.fits: truncated"},
      {{"--healpix", file("empty.fits", "")}, "empty.fits: empty"},
      {{"--healpix", file("text.fits", "hello")}, "text.fits: not a FITS file"},
      {{"--healpix", file("nside.fits", wrong_nside)}, "nside.fits: column 1 holds"},
      {{"--healpix", d + "nan.fits"}, "nan.fits: pixel 9 is NaN"},
      {{"--healpix", d + "unseen.fits"}, "unseen.fits: 1 UNSEEN pixels (the first: pixel 4) and no mask"},
      {{"--healpix", d + "unseen.fits", "--mask", d + "two.fits"}, "two.fits: NSIDE 2 is not the map's 4"},
      {{"--healpix", d + "unseen.fits", "--mask", d + "half.fits"}, "half.fits: pixel 0 (RING) is 1.5, outside [0, 1]"},
      {{"--healpix", d + "missing.fits"}, "missing.fits: cannot be read"},
  };
  for (const Case& c : cases) {
    for (const bool needlets : {false, true}) {
      std::vector<std::string> args = needlets ? std::vector<std::string>{"needlets", "analyze", "--order", "5"} : std::vector<std::string>{"project", "--order", "3"};
      args.insert(args.end(), c.args.begin(), c.args.end());
      args.insert(args.end(), {"--out", out});
      const test::RunResult r = test::run_zhf(args);
      EXPECT_EQ(r.exit_code, 3) << c.message << ": " << r.err;
      EXPECT_EQ(test::line_count(r.err), 1) << r.err;
      EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
      EXPECT_FALSE(std::filesystem::exists(out)) << c.message;
    }
  }
  // Options.
  const std::string beta = (dir / "beta.json").string();
  ASSERT_EQ(test::run_zhf({"needlets", "analyze", "--healpix", good, "--order", "5", "--out", beta}).exit_code, 0);
  for (const auto& [args, message] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"project", "--healpix", good, "--iterations", "21", "--out", out}, "--iterations"},
           {{"project", "--healpix", good, "--order", "20", "--out", out}, "--order: band 19 is above 4 Nside = 16"},
           {{"needlets", "analyze", "--healpix", good, "--order", "18", "--out", out}, "--order: band 17 is above 4 Nside = 16"},
           {{"project", "--image", good, "--healpix", good, "--out", out}, "give exactly one"},
           {{"project", "--function", "cap", "--mask", good, "--out", out}, "--mask: only with --healpix"},
           {{"needlets", "synthesize", "--in", beta, "--out", out, "--nside", "3", "--ordering", "nested"}, "--nside: 3 is not a power of two"},
           {{"needlets", "synthesize", "--in", beta, "--out", out, "--nside", "8193"}, "--nside"},
           {{"needlets", "synthesize", "--in", beta, "--out", out, "--nside", "4", "--ordering", "spiral"}, "--ordering: 'spiral'"},
       }) {
    const test::RunResult r = test::run_zhf(args);
    EXPECT_EQ(r.exit_code, 2) << message << ": " << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << message;
  }
  // Coefficients that do not fit the frame they name.
  const std::string short_beta = file("short.json", R"({"format": "zhf-needlet-coefficients-1", "B": 2, "lmax": 4, "nodes": "design", "levels": [], "beta": [1, 2]})");
  const test::RunResult r = test::run_zhf({"needlets", "synthesize", "--in", short_beta, "--out", out, "--nside", "4"});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("short.json"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace zhf::healpix
