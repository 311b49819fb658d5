// The tight-frame rotation (frames/tight_frame_rotation.h) against the Ivanic-Ruedenberg band
// matrices, on designs and on Gauss product nodes, at every order the shipped designs reach.
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "zhf/frames/tight_frame_rotation.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"
#include "test_tolerances.h"

namespace zhf::frames {
namespace {

using zhf::tolerance::kFloatRotation;
using zhf::tolerance::kTightFrameRotation;

template <class T>
double worst_error(const TightFrameRotator<T>& rotator, const sh::RotationMatrix& r, std::mt19937_64& rng) {
  const int order = rotator.order(), n = order * order;
  sh::Normal<> normal(0, 1.0 / order);
  Eigen::VectorXd f(n);
  for (int i = 0; i < n; ++i) f[i] = normal(rng);
  f.normalize();
  std::vector<T> in(n), out(n), rt(9);
  for (int i = 0; i < n; ++i) in[i] = T(f[i]);
  for (int i = 0; i < 9; ++i) rt[i] = T(r(i / 3, i % 3));
  rotator.rotate(rt.data(), in.data(), out.data());
  const Eigen::VectorXd expected = sh::apply_band_matrices(sh::ivanic_ruedenberg(r, order), f);
  double worst = 0;
  for (int i = 0; i < n; ++i) worst = std::max(worst, std::abs(double(out[i]) - expected[i]));
  return worst;
}

TEST(TightFrameRotation, MatchesTheReferenceAtEveryOrderOnDesignsAndGaussNodes) {
  std::mt19937_64 rng(21);
  const std::string designs = std::string(ZHF_SOURCE_DIR) + "/generated/designs";
  for (int order = 2; order <= 16; ++order) {
    for (bool gauss : {false, true}) {
      const Cubature nodes = gauss ? gauss_product_cubature(2 * (order - 1)) : design_cubature(designs, 2 * (order - 1));
      const TightFrameRotator<double> d(order, nodes);
      const TightFrameRotator<float> f(order, nodes);
      std::vector<std::pair<std::string, sh::RotationMatrix>> turns = sh::extreme_rotations({});
      for (int i = 0; i < 4; ++i) turns.push_back({"random " + std::to_string(i), sh::random_rotation(rng)});
      for (const auto& [name, r] : turns) {
        EXPECT_LT(worst_error(d, r, rng), kTightFrameRotation) << "order " << order << ", " << nodes.name << ", " << name;
        EXPECT_LT(worst_error(f, r, rng), kFloatRotation) << "order " << order << ", " << nodes.name << ", " << name << ", float";
      }
    }
  }
  EXPECT_THROW(TightFrameRotator<float>(5, gauss_product_cubature(7)), std::invalid_argument);
}

}  // namespace
}  // namespace zhf::frames
