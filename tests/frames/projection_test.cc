// Projection into SH (frames/projection.h): exact on designs and Gauss rules for band-limited
// functions, the cap's closed form against a 1D integration, equal-angle grids converging, and
// `zhf project --image` on a Radiance file.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"
#include "test_tolerances.h"
#include "zhf/frames/projection.h"
#include "zhf/io/hdr.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"

namespace zhf::frames {
namespace {

using zhf::tolerance::kExactProjection;

TEST(Projection, ExactCubaturesProjectBandLimitedFunctionsExactly) {
  const std::string designs = std::string(ZHF_SOURCE_DIR) + "/generated/designs";
  for (int order : {1, 4, 8, 12}) {
    const int degree = 7 + order - 1;
    for (const Cubature& nodes : {design_cubature(designs, degree), gauss_product_cubature(degree)}) {
      const ProjectionError e = projection_error(nodes, order);
      EXPECT_LT(e.band_limited, kExactProjection) << "order " << order << ", " << nodes.name;
    }
    // One degree short, the top band aliases.
    EXPECT_GT(projection_error(gauss_product_cubature(degree - 2), order).band_limited, 1e-6) << "order " << order;
  }
}

TEST(Projection, CapCoefficientsMatchAOneDimensionalIntegral) {
  const std::vector<double> exact = test_function_coefficients(TestFunction::kCap, 16);
  const double edge = std::cos(30 * runtime::kPi / 180);
  for (int l = 0; l < 16; ++l) {
    // 2 pi int_edge^1 y_l^0(t) dt by the midpoint rule on zhf's own Q_l^0.
    constexpr int kSteps = 100000;
    double sum = 0;
    for (int i = 0; i < kSteps; ++i) sum += runtime::legendre_q<double>(l, 0, edge + (1 - edge) * (i + 0.5) / kSteps);
    EXPECT_NEAR(exact[runtime::index(l, 0)], 2 * runtime::kPi * sum * (1 - edge) / kSteps, zhf::tolerance::kCapCoefficientMidpoint) << "band " << l;
    for (int m = 1; m <= l; ++m) EXPECT_EQ(exact[runtime::index(l, m)], 0.0) << "band " << l << ", m " << m;
  }
}

TEST(Projection, EqualAngleGridsHaveExactSolidAnglesAndConverge) {
  double previous = 1;
  for (int height : {8, 32, 128}) {
    const Cubature grid = equirectangular_nodes(2 * height, height);
    double total = 0;
    for (double w : grid.weights) total += w;
    EXPECT_NEAR(total, 4 * runtime::kPi, zhf::tolerance::kDouble) << "height " << height;
    const double error = projection_error(grid, 8).band_limited;
    EXPECT_LT(error, previous / 4) << "height " << height;  // midpoint in theta: ~h^2
    previous = error;
  }
  EXPECT_THROW(project_samples(equirectangular_nodes(4, 2), std::vector<double>(3), 1, 2), std::invalid_argument);
}

TEST(Projection, TheSumIsTheSameOnAnyThreadCountAndTheCheckpointSeesEverySample) {
  // 128 x 64 pixels: two blocks of samples; 7 threads: more workers than blocks.
  const Cubature grid = equirectangular_nodes(128, 64);
  std::vector<double> values;
  for (const Point& p : grid.points) values.insert(values.end(), {test_function(TestFunction::kBandLimited, p), p[2]});
  std::vector<std::size_t> seen;
  const auto one = project_samples(grid, values, 2, 8, 1, [&](std::size_t done, std::size_t samples) {
    EXPECT_EQ(samples, grid.points.size());
    seen.push_back(done);
  });
  EXPECT_EQ(seen, (std::vector<std::size_t>{4096, grid.points.size()})) << "one worker: a round a block";
  for (int threads : {2, 3, 7}) EXPECT_EQ(project_samples(grid, values, 2, 8, threads), one) << threads << " threads";
  // Against a plain sum over the samples: the blocks only regroup it.
  std::vector<double> y(64), plain(64, 0.0);
  for (std::size_t k = 0; k < grid.points.size(); ++k) {
    runtime::eval_sh(8, grid.points[k].data(), y.data());
    for (int i = 0; i < 64; ++i) plain[i] += grid.weights[k] * values[2 * k] * y[i];
  }
  for (int i = 0; i < 64; ++i) EXPECT_NEAR(one[0][i], plain[i], kExactProjection) << "index " << i;
}

TEST(Projection, ARadianceImageBecomesRgbCoefficients) {
  const test::TempDir dir;
  io::HdrImage image;
  image.width = 64;
  image.height = 32;
  for (int i = 0; i < image.width * image.height; ++i) image.rgb.insert(image.rgb.end(), {1.0f, 0.5f, 2.0f});  // exact in RGBE
  const std::string path = (dir / "sky.hdr").string(), out = (dir / "sky.json").string();
  test::write_text(path, io::encode_hdr(image));
  const test::RunResult r = test::run_zhf("project --image '" + path + "' --order 3 --out '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = test::read_json(out);
  ASSERT_EQ(j.size(), 1u);
  ASSERT_EQ(j[0].size(), 3u);
  const double scale[3] = {1.0, 0.5, 2.0};
  for (int c = 0; c < 3; ++c) {
    // A constant: only y_0^0, with weight 4 pi / sqrt(4 pi); odd bands and m != 0 vanish by symmetry.
    EXPECT_NEAR(j[0][c][0].get<double>(), scale[c] * std::sqrt(4 * runtime::kPi), zhf::tolerance::kFloatProjection) << "channel " << c;
    for (int i = 1; i < 9; ++i) {
      if (i == runtime::index(2, 0)) continue;  // the grid's midpoint rule in theta leaves y_2^0 a little
      EXPECT_NEAR(j[0][c][i].get<double>(), 0.0, zhf::tolerance::kFloatProjection) << "channel " << c << ", index " << i;
    }
  }
  // 256 x 128 pixels: 8 blocks of samples; the file is the same bytes on 1 and 3 threads.
  image.width = 256;
  image.height = 128;
  image.rgb.clear();
  for (int i = 0; i < image.width * image.height; ++i) image.rgb.insert(image.rgb.end(), {float(i % 7), 0.5f, float(i % 3)});
  test::write_text(path, io::encode_hdr(image));
  std::string bytes[2];
  for (int threads : {1, 3}) {
    const test::RunResult run = test::run_zhf("project --image '" + path + "' --order 6 --threads " + std::to_string(threads) + " --out '" + out + "'");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    bytes[threads == 3] = test::read_text(out);
  }
  EXPECT_EQ(bytes[0], bytes[1]);
  EXPECT_EQ(test::run_zhf("project --image '" + path + "' --threads 257 --out '" + out + "'").exit_code, 2);
  test::write_text(path, io::encode_hdr(image) + "x");
  const test::RunResult bad = test::run_zhf("project --image '" + path + "' --order 3 --out '" + out + "'");
  EXPECT_EQ(bad.exit_code, 3);
  EXPECT_NE(bad.err.find("1 bytes after the last scanline"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace zhf::frames
