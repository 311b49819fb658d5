// Precomputed radiance transfer with SH and needlets: the Parseval identity that makes needlet
// shading equal SH shading with every coefficient kept, the scenes' visibility, and the errors'
// behaviour as coefficients are added.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "zhf/frames/prt.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"
#include "test_tolerances.h"

namespace zhf::frames {
namespace {

namespace tol = zhf::tolerance;

TEST(Prt, NeedletShadingWithEveryCoefficientIsTheShSum) {
  const NeedletFrame frame(2.0, 12);
  for (const PrtScene scene : {PrtScene::kSphere, PrtScene::kCorner, PrtScene::kSpheres}) {
    for (const PrtTransfer transfer : {PrtTransfer::kDiffuse, PrtTransfer::kGlossy}) {
      const PrtReport r = prt_experiment(frame, scene, transfer, sun_and_sky, 3, {9, 49}, 256);
      EXPECT_LE(r.parseval_gap, tol::kParsevalShading) << "scene " << static_cast<int>(scene) << ", transfer " << static_cast<int>(transfer);
      ASSERT_EQ(r.rows.size(), 3u);
      const PrtRow& all = r.rows.back();
      EXPECT_EQ(all.kept, frame.size());
      EXPECT_NEAR(all.needlet_rms, all.sh_rms, tol::kParsevalShading);
      // More coefficients, less error (SH from 9 to all 169; needlets from 9 to all).
      EXPECT_LT(all.sh_rms, r.rows[0].sh_rms);
      EXPECT_LT(all.needlet_rms, r.rows[0].needlet_rms);
      // Exact rotation keeps each level's energy; the tabulated one only nearly (256 entries).
      for (double change : r.level_energy_change) EXPECT_LT(change, 0.1);
      // At every turn the 49 largest hold at least what the 9 largest hold, and no more than all.
      ASSERT_EQ(r.kept_energy_least.size(), 2u);
      EXPECT_GE(r.kept_energy_least[1], r.kept_energy_least[0]);
      EXPECT_GE(r.kept_energy_greatest[1], r.kept_energy_greatest[0]);
      EXPECT_LE(r.kept_energy_greatest[1], 1 + tol::kParsevalShading);
      // The best-K SH control with every SH coefficient kept is the band sum.
      EXPECT_NEAR(all.sh_best_rms, all.sh_rms, tol::kParsevalShading);
      EXPECT_EQ(all.sh_bytes, 4 * 169);
      EXPECT_EQ(all.needlet_bytes, frame.size() * 6);  // a 2-byte index beside each 4-byte value
    }
  }
}

// The same report on one thread as on three, and a checkpoint that sees every vertex counted.
TEST(Prt, TheReportDoesNotDependOnTheThreads) {
  const NeedletFrame frame(2.0, 6);
  int last_done = -1, calls = 0;
  const auto watch = [&](int done, int total) {
    EXPECT_EQ(total, 9);
    EXPECT_GE(done, last_done);
    last_done = done, ++calls;
  };
  const PrtReport one = prt_experiment(frame, PrtScene::kCorner, PrtTransfer::kGlossy, sun_and_sky, 3, {9, 25}, 64, watch, 1);
  EXPECT_EQ(last_done, 9);
  EXPECT_GE(calls, 9);  // a vertex at a time on one thread, then the later stages
  const PrtReport three = prt_experiment(frame, PrtScene::kCorner, PrtTransfer::kGlossy, sun_and_sky, 3, {9, 25}, 64, {}, 3);
  EXPECT_EQ(one.exact, three.exact);
  ASSERT_EQ(one.rows.size(), three.rows.size());
  for (std::size_t i = 0; i < one.rows.size(); ++i) {
    EXPECT_EQ(one.rows[i].sh, three.rows[i].sh) << "K = " << one.rows[i].kept;
    EXPECT_EQ(one.rows[i].needlet, three.rows[i].needlet) << "K = " << one.rows[i].kept;
  }
  EXPECT_EQ(one.level_energy_change, three.level_energy_change);
  EXPECT_EQ(one.kept_energy_least, three.kept_energy_least);
}

double constant_sky(const Point&) { return 1; }
double linear_sky(const Point& w) { return 0.25 + 0.75 * w[2]; }

// The exact reference against closed forms. Diffuse: int_visible L w_z / pi.
TEST(PrtExact, AnUnoccludedDiffuseVertexIsTheClosedForm) {
  for (const Point& p : {Point{0, 0, 0}, Point{1.2, -0.7, 0}}) {
    EXPECT_NEAR(prt_exact_shading(PrtScene::kOpen, PrtTransfer::kDiffuse, constant_sky, p), 1.0, tol::kPrtExactReference);
    // (1 / pi) int (0.25 + 0.75 w_z) w_z over the hemisphere = 0.25 + 0.75 (2 / 3).
    EXPECT_NEAR(prt_exact_shading(PrtScene::kOpen, PrtTransfer::kDiffuse, linear_sky, p), 0.75, tol::kPrtExactReference);
  }
  // Glossy, constant sky: over the whole hemisphere of the lobe's axis r, (e + 2) / (2 pi) int
  // (w . r)^e w_z = r_z (the part of w_z across r integrates to zero), and the ground's transfer
  // drops only the lobe's tail below the horizon, where w_z < 0 and (w . r)^e <= 2^(-e/2) = 1e-3:
  // the open ground's value sits just above r_z.
  const double r_z = 1 / std::sqrt(2.0);
  const double glossy = prt_exact_shading(PrtScene::kOpen, PrtTransfer::kGlossy, constant_sky, {0, 0, 0});
  EXPECT_GT(glossy, r_z);
  EXPECT_LT(glossy, r_z + 1e-4);
}

// Straight under the sphere the hidden cap is centred on the normal, half-angle a = asin(r / d):
// (1 / pi) int over theta in [a, pi / 2] of L w_z = cos^2 a for L = 1 and 0.25 cos^2 a + 0.5 cos^3 a
// for the linear sky. The quadrature reference this replaced erred by 1.2 % here.
TEST(PrtExact, UnderTheSphereIsTheClosedForm) {
  const double sin_a = 0.5 / 0.8, cos2 = 1 - sin_a * sin_a, cos_a = std::sqrt(cos2);
  EXPECT_NEAR(prt_exact_shading(PrtScene::kSphere, PrtTransfer::kDiffuse, constant_sky, {0, 0, 0}), cos2, tol::kPrtExactReference);
  EXPECT_NEAR(prt_exact_shading(PrtScene::kSphere, PrtTransfer::kDiffuse, linear_sky, {0, 0, 0}), 0.25 * cos2 + 0.5 * cos2 * cos_a,
              tol::kPrtExactReference);
}

// The corner's walls are half-spaces: the visible sky is a spherical triangle (the horizon and one
// great circle per wall), whose irradiance vector is Lambert's (1/2) sum over its edges of the
// edge's arc times its plane's inward unit normal; a diffuse vertex under a constant sky shades to
// that vector's z / pi.
TEST(PrtExact, UnderTheCornerIsLambertsPolygonFormula) {
  const double wall = -1.6, height = 1.5;
  for (const Point& p : {Point{0, 0, 0}, Point{-1.4, 1.3, 0}, Point{1.45, -1.5, 0}}) {
    using V = std::array<double, 3>;
    auto unit = [](V v) {
      const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      return V{v[0] / n, v[1] / n, v[2] / n};
    };
    auto cross = [](V a, V b) { return V{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; };
    auto dot = [](V a, V b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
    // Inward normals of the visible region: the ground's +z, and each wall's visible side.
    const V inward[3] = {V{0, 0, 1}, unit({height, 0, p[0] - wall}), unit({0, height, p[1] - wall})};
    // The triangle's corners: where two circles meet, on the third's visible side.
    auto corner = [&](int i, int j, int k) {
      const V c = unit(cross(inward[i], inward[j]));
      return dot(c, inward[k]) >= 0 ? c : V{-c[0], -c[1], -c[2]};
    };
    const V c01 = corner(0, 1, 2), c02 = corner(0, 2, 1), c12 = corner(1, 2, 0);
    // Edge on circle i runs between the two corners on it.
    const double arc0 = std::acos(dot(c01, c02)), arc1 = std::acos(dot(c01, c12)), arc2 = std::acos(dot(c02, c12));
    const double z = 0.5 * (arc0 * inward[0][2] + arc1 * inward[1][2] + arc2 * inward[2][2]);
    EXPECT_NEAR(prt_exact_shading(PrtScene::kCorner, PrtTransfer::kDiffuse, constant_sky, p), z / runtime::kPi, tol::kPrtExactReference)
        << "vertex (" << p[0] << ", " << p[1] << ")";
  }
}

// The reference converges: halving the step changes no vertex of any scene and transfer by more
// than the reference's tolerance of the shading, under the sun and sky.
TEST(PrtExact, HalvingTheStepChangesNothing) {
  for (const PrtScene scene : {PrtScene::kSphere, PrtScene::kCorner, PrtScene::kSpheres})
    for (const PrtTransfer transfer : {PrtTransfer::kDiffuse, PrtTransfer::kGlossy})
      for (const Point& p : prt_vertices(3)) {
        const double coarse = prt_exact_shading(scene, transfer, sun_and_sky, p), fine = prt_exact_shading(scene, transfer, sun_and_sky, p, kPrtExactStep / 2);
        EXPECT_NEAR(coarse, fine, tol::kPrtExactReference * std::max(1.0, std::abs(fine)))
            << "scene " << static_cast<int>(scene) << ", transfer " << static_cast<int>(transfer) << ", vertex (" << p[0] << ", " << p[1] << ")";
      }
}

// The control keeps each vertex's largest |T_lm|, not its first ones. On the open ground the clamped
// cosine's largest coefficient is y_1^0's (sqrt(pi / 3) / pi against y_0^0's sqrt(pi) / (2 pi)),
// which a constant sky does not see: K = 1 shades nothing, where band 0 shades it all; K = 2 adds
// y_0^0 and is band 0's shading.
TEST(Prt, TheBestKShControlKeepsTheLargestCoefficients) {
  const PrtReport r = prt_experiment(NeedletFrame(2.0, 4), PrtScene::kOpen, PrtTransfer::kDiffuse, constant_sky, 1, {1, 2}, 16);
  ASSERT_EQ(r.rows.size(), 3u);
  EXPECT_NEAR(r.rows[0].sh_best[0], 0.0, tol::kParsevalShading);
  EXPECT_NEAR(r.exact[0], 1.0, tol::kPrtExactReference);  // what K = 1 misses
  EXPECT_NEAR(r.rows[1].sh_best[0], r.rows[1].sh[0], tol::kParsevalShading);
}

TEST(Prt, VisibilityOfEachScene) {
  const Point up{0, 0, 1}, low_west{-0.99, 0, 0.141}, low_east{0.99, 0, 0.141};
  EXPECT_EQ(prt_visibility(PrtScene::kOpen, {0, 0, 0}, low_west), 1);
  EXPECT_EQ(prt_visibility(PrtScene::kSphere, {0, 0, 0}, up), 0);
  EXPECT_EQ(prt_visibility(PrtScene::kSphere, {1.4, 1.4, 0}, up), 1);
  EXPECT_EQ(prt_visibility(PrtScene::kSphere, {0, 0, 0}, low_east), 1);
  EXPECT_EQ(prt_visibility(PrtScene::kCorner, {0, 0, 0}, low_west), 0);  // meets the x wall below its top
  EXPECT_EQ(prt_visibility(PrtScene::kCorner, {0, 0, 0}, low_east), 1);
  EXPECT_EQ(prt_visibility(PrtScene::kCorner, {0, 0, 0}, up), 1);
  EXPECT_EQ(prt_visibility(PrtScene::kSpheres, {0.5, 0.4, 0}, up), 0);
  EXPECT_EQ(prt_transfer(PrtScene::kSphere, PrtTransfer::kDiffuse, {1.4, 1.4, 0}, {0, 0, -1}), 0);  // below the horizon
  EXPECT_THROW(prt_vertices(0), std::invalid_argument);
  EXPECT_THROW(prt_exact_shading(PrtScene::kSphere, PrtTransfer::kDiffuse, sun_and_sky, {0, 0, 0.5}), std::invalid_argument);
  EXPECT_THROW(prt_exact_shading(PrtScene::kCorner, PrtTransfer::kDiffuse, sun_and_sky, {-1.7, 0, 0}), std::invalid_argument);
  EXPECT_THROW(prt_experiment(NeedletFrame(2.0, 4), PrtScene::kSphere, PrtTransfer::kDiffuse, sun_and_sky, 2, {100000}, 64), std::invalid_argument);
}

}  // namespace
}  // namespace zhf::frames
