// HEALPix maps: the FITS reader and writer (bit-exact round trips, healpy's layout written here by
// cfitsio directly), the ring-by-ring analysis and synthesis against pixel-by-pixel sums, and the
// projection of a band-limited map.
#include <fitsio.h>
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <random>

#include "test_support.h"
#include "test_tolerances.h"
#include "zhf/healpix/fits.h"
#include "zhf/healpix/maps.h"
#include "zhf/io/errors.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"

namespace zhf::healpix {
namespace {

namespace tol = zhf::tolerance;

std::vector<double> random_values(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  sh::Normal<> normal;
  std::vector<double> v(n);
  for (double& x : v) x = normal(rng);
  return v;
}

// Coefficients of order N with power ~ 1 / (l + 1)^2.
std::vector<double> random_sh(int order, std::uint64_t seed) {
  std::vector<double> sh = random_values(static_cast<std::size_t>(order) * order, seed);
  for (int l = 0; l < order; ++l)
    for (int m = -l; m <= l; ++m) sh[runtime::index(l, m)] /= (l + 1);
  return sh;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(HealpixFits, WrittenMapsReadBackBitForBit) {
  for (const auto& [nside, ordering] : {std::pair{4, HealpixOrdering::kRing}, std::pair{16, HealpixOrdering::kNested}, std::pair{3, HealpixOrdering::kRing}}) {
    HealpixMap map;
    map.nside = nside;
    map.ordering = ordering;
    map.pixels = random_values(static_cast<std::size_t>(healpix_pixels(nside)), 7 + nside);
    map.pixels[0] = -0.0;
    map.pixels[1] = 4.9e-324;
    map.pixels[2] = 1.7976931348623157e308;
    const std::string bytes = encode_healpix_map(map);
    EXPECT_EQ(bytes.size() % 2880, 0u);
    const HealpixMap back = parse_healpix_map(bytes, "memory");
    EXPECT_EQ(back.nside, nside);
    EXPECT_EQ(back.ordering, ordering);
    ASSERT_EQ(back.pixels.size(), map.pixels.size());
    for (std::size_t p = 0; p < map.pixels.size(); ++p) ASSERT_TRUE(same_bits(back.pixels[p], map.pixels[p])) << "Nside " << nside << ", pixel " << p;
    EXPECT_EQ(back.unseen, 0);
    // The same through files, by zhf's writing rules.
    test::TempDir dir;
    const std::string path = dir.string() + "/map.fits";
    write_healpix_map(path, map);
    EXPECT_EQ(test::read_text(path), bytes);
    EXPECT_EQ(read_healpix_map(path).pixels.size(), map.pixels.size());
  }
}

// A map file as healpy writes it: float32 values 1024 to a row, more columns after the map,
// ORDERING NESTED, UNSEEN pixels; written here through cfitsio, not through zhf.
std::string healpy_style_file(const std::string& path, int nside, const std::vector<float>& values) {
  fitsfile* f = nullptr;
  int status = 0;
  const std::string name = "!" + path;
  fits_create_file(&f, name.c_str(), &status);
  fits_create_img(f, FLOAT_IMG, 0, nullptr, &status);
  char t1[] = "TEMPERATURE", t2[] = "HITS", f1[] = "1024E", f2[] = "1024J", u[] = "K";
  char* types[] = {t1, t2};
  char* forms[] = {f1, f2};
  char* units[] = {u, u};
  const long long rows = 12LL * nside * nside / 1024;
  fits_create_tbl(f, BINARY_TBL, rows, 2, types, forms, units, nullptr, &status);
  char healpix[] = "HEALPIX", nested[] = "NESTED";
  long long n = nside;
  fits_write_key(f, TSTRING, "PIXTYPE", healpix, nullptr, &status);
  fits_write_key(f, TSTRING, "ORDERING", nested, nullptr, &status);
  fits_write_key(f, TLONGLONG, "NSIDE", &n, nullptr, &status);
  fits_write_col(f, TFLOAT, 1, 1, 1, static_cast<long long>(values.size()), const_cast<float*>(values.data()), &status);
  std::vector<int> hits(values.size(), 3);
  fits_write_col(f, TINT, 2, 1, 1, static_cast<long long>(hits.size()), hits.data(), &status);
  fits_close_file(f, &status);
  EXPECT_EQ(status, 0);
  return path;
}

TEST(HealpixFits, ReadsHealpysLayoutOfFloatRowsAndMoreColumns) {
  test::TempDir dir;
  const int nside = 16;
  std::vector<float> values(static_cast<std::size_t>(healpix_pixels(nside)));
  for (std::size_t p = 0; p < values.size(); ++p) values[p] = static_cast<float>(p) * 0.25f - 100.0f;
  values[5] = static_cast<float>(kHealpixUnseen);
  values[9] = static_cast<float>(kHealpixUnseen);
  const HealpixMap map = read_healpix_map(healpy_style_file(dir.string() + "/healpy.fits", nside, values));
  EXPECT_EQ(map.ordering, HealpixOrdering::kNested);
  ASSERT_EQ(map.pixels.size(), values.size());
  for (std::size_t p = 0; p < values.size(); ++p) ASSERT_EQ(map.pixels[p], static_cast<double>(values[p])) << "pixel " << p;
  EXPECT_EQ(map.unseen, 2);
  EXPECT_EQ(map.first_unseen, 5);
  // NESTED to RING and back by the library's tables.
  const std::vector<double> ring = ring_pixels(map);
  const HealpixMap nested = map_from_ring(nside, ring, HealpixOrdering::kNested);
  EXPECT_EQ(nested.pixels, map.pixels);
  EXPECT_NE(ring, map.pixels);
}

TEST(HealpixFits, MalformedBytesAreRefusedNamingTheSource) {
  HealpixMap map;
  map.nside = 2;
  map.pixels.assign(48, 1.0);
  const std::string good = encode_healpix_map(map);
  auto refused = [](const std::string& bytes, const std::string& expected) {
    try {
      parse_healpix_map(bytes, "m.fits");
      ADD_FAILURE() << "accepted; expected: " << expected;
    } catch (const io::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("m.fits: "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  refused("", "empty");
  refused("SIMPLE  = nonsense", "the primary header has no END");
  refused(std::string(2880, ' '), "not a FITS file");
  refused(good.substr(0, good.size() - 2880), "truncated");
  refused(good + std::string(2880, '\0'), "bytes after the map's table");
  auto with_key = [&](const std::string& key, const std::string& value) {
    std::string bytes = good;
    const std::size_t at = bytes.find(key);
    EXPECT_NE(at, std::string::npos) << key;
    std::string card = key;
    card.resize(8, ' ');
    card += "= " + value;
    card.resize(80, ' ');
    bytes.replace(at, 80, card);
    return bytes;
  };
  refused(with_key("NAXIS", "99999999999999999999"), "NAXIS is not an integer");  // read ahead, checked
  refused(with_key("NAXIS", "1000"), "NAXIS 1000 is outside 0..999");
  refused(with_key("NSIDE", "3"), "column 1 holds 48 rows of 1 values, not 12 NSIDE^2 = 108");
  refused(with_key("NSIDE", "0"), "NSIDE 0 is outside 1..8192");
  refused(with_key("NSIDE", "'two'"), "NSIDE is not an integer");
  refused(with_key("ORDERING", "'SPIRAL'"), "ORDERING 'SPIRAL' is not RING or NESTED");
  refused(with_key("PIXTYPE", "'CAR'"), "PIXTYPE is not 'HEALPIX'");
  refused(with_key("INDXSCHM", "'EXPLICIT'"), "INDXSCHM 'EXPLICIT'");
  HealpixMap odd;
  odd.nside = 3;
  odd.ordering = HealpixOrdering::kRing;
  odd.pixels.assign(108, 0.0);
  std::string nested_three = encode_healpix_map(odd);
  nested_three.replace(nested_three.find("'RING    '"), 10, "'NESTED  '");
  refused(nested_three, "NSIDE 3 is not a power of two");
  HealpixMap bad = map;
  bad.pixels[7] = std::nan("");
  refused(encode_healpix_map(bad), "pixel 7 is NaN");
  bad.pixels[7] = INFINITY;
  refused(encode_healpix_map(bad), "pixel 7 is infinite");
}

TEST(HealpixMaps, SynthesisMatchesTheSeriesAtEveryPixelCentre) {
  for (const int nside : {1, 3, 8}) {
    const int order = 7;
    const std::vector<double> sh = random_sh(order, 11);
    const std::vector<double> map = synthesize_map(nside, sh);
    std::vector<double> y(sh.size());
    for (std::int64_t p = 0; p < healpix_pixels(nside); ++p) {
      const Point x = pixel_centre(nside, p);
      runtime::eval_sh(order, x.data(), y.data());
      double f = 0;
      for (std::size_t i = 0; i < sh.size(); ++i) f += sh[i] * y[i];
      ASSERT_NEAR(map[p], f, tol::kDouble) << "Nside " << nside << ", ring pixel " << p;
      ASSERT_EQ(pixel_at(nside, x), p);
    }
  }
}

TEST(HealpixMaps, AnalysisIsThePixelQuadratureWhateverTheThreadCount) {
  const int nside = 8, order = 9;
  const std::vector<double> values = random_values(static_cast<std::size_t>(healpix_pixels(nside)), 3);
  const std::vector<double> sh = analyze_map(nside, values, order, 0);
  std::vector<double> sum(sh.size(), 0.0), y(sh.size());
  for (std::int64_t p = 0; p < healpix_pixels(nside); ++p) {
    const Point x = pixel_centre(nside, p);
    runtime::eval_sh(order, x.data(), y.data());
    for (std::size_t i = 0; i < sh.size(); ++i) sum[i] += 4 * M_PI / static_cast<double>(healpix_pixels(nside)) * values[p] * y[i];
  }
  for (int l = 0; l < order; ++l)
    for (int m = -l; m <= l; ++m) ASSERT_NEAR(sh[runtime::index(l, m)], sum[runtime::index(l, m)], tol::kDouble) << "band " << l << ", m " << m;
  // libsharp's OpenMP threads never change the result.
  EXPECT_THROW(analyze_map(nside, values, 4 * nside + 2, 0), std::invalid_argument);  // beyond what the rings resolve
  for (const int iterations : {0, 3}) {
    omp_set_num_threads(1);
    const std::vector<double> one = analyze_map(nside, values, order, iterations);
    omp_set_num_threads(2);
    EXPECT_EQ(analyze_map(nside, values, order, iterations), one) << iterations << " iterations";
  }
}

TEST(HealpixMaps, ProjectionRecoversABandLimitedMapsCoefficients) {
  // Bands below Nside: the pixel quadrature is close to exact, and each Jacobi step closer.
  const int nside = 32, order = 17;
  const std::vector<double> sh = random_sh(order, 5);
  const std::vector<double> map = synthesize_map(nside, sh);
  double previous = INFINITY;
  for (const int iterations : {0, 1, 3}) {
    const std::vector<double> back = analyze_map(nside, map, order, iterations);
    double worst = 0;
    int worst_index = 0;
    for (std::size_t i = 0; i < sh.size(); ++i) {
      if (std::abs(back[i] - sh[i]) > worst) worst = std::abs(back[i] - sh[i]), worst_index = static_cast<int>(i);
    }
    EXPECT_LT(worst, previous) << iterations << " iterations, index " << worst_index;
    previous = worst;
    if (iterations == 3) {
      EXPECT_LE(worst, tol::kHealpixProjection) << "index " << worst_index;
    }
  }
}

}  // namespace
}  // namespace zhf::healpix
