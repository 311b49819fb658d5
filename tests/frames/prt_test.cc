// Precomputed radiance transfer with SH and needlets: the Parseval identity that makes needlet
// shading equal SH shading with every coefficient kept, the scenes' visibility, and the errors'
// behaviour as coefficients are added.
#include <gtest/gtest.h>

#include "zhf/frames/prt.h"
#include "zhf/tolerances/tolerances.h"

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
      for (std::size_t i = 0; i < r.kept_energy_least.size(); ++i) EXPECT_LE(r.kept_energy_least[i], r.kept_energy_greatest[i]);
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

TEST(Prt, VisibilityOfEachScene) {
  const Point up{0, 0, 1}, low_west{-0.99, 0, 0.141}, low_east{0.99, 0, 0.141};
  EXPECT_EQ(prt_visibility(PrtScene::kSphere, {0, 0, 0}, up), 0);
  EXPECT_EQ(prt_visibility(PrtScene::kSphere, {1.4, 1.4, 0}, up), 1);
  EXPECT_EQ(prt_visibility(PrtScene::kSphere, {0, 0, 0}, low_east), 1);
  EXPECT_EQ(prt_visibility(PrtScene::kCorner, {0, 0, 0}, low_west), 0);  // meets the x wall below its top
  EXPECT_EQ(prt_visibility(PrtScene::kCorner, {0, 0, 0}, low_east), 1);
  EXPECT_EQ(prt_visibility(PrtScene::kCorner, {0, 0, 0}, up), 1);
  EXPECT_EQ(prt_visibility(PrtScene::kSpheres, {0.5, 0.4, 0}, up), 0);
  EXPECT_EQ(prt_transfer(PrtScene::kSphere, PrtTransfer::kDiffuse, {1.4, 1.4, 0}, {0, 0, -1}), 0);  // below the horizon
  EXPECT_THROW(prt_vertices(0), std::invalid_argument);
  EXPECT_THROW(prt_experiment(NeedletFrame(2.0, 4), PrtScene::kSphere, PrtTransfer::kDiffuse, sun_and_sky, 2, {100000}, 64), std::invalid_argument);
}

}  // namespace
}  // namespace zhf::frames
