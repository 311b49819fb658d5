// The zonal fast path (runtime/zonal.h) against the reference rotation of the same function's full
// coefficients.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "zhf/runtime/sh_eval.h"
#include "zhf/runtime/tolerances.h"
#include "zhf/runtime/zonal.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"

namespace zhf {
namespace {

TEST(Zonal, RuntimeFastPathMatchesTheReferenceRotation) {
  std::mt19937_64 rng(8);
  sh::Normal<> normal;
  for (int order : {1, 2, 5, 8, 16}) {
    const runtime::ZonalRotator<double> zonal(order);
    const int n = order * order;
    double worst = 0;
    int worst_index = 0;
    for (int trial = 0; trial < 50; ++trial) {
      const Eigen::Vector3d axis = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
      std::vector<double> weights(order);
      for (double& w : weights) w = normal(rng);
      std::vector<double> f(n), got(n);
      zonal.project(axis.data(), weights.data(), f.data());
      const sh::RotationMatrix r = sh::random_rotation(rng);
      const Eigen::VectorXd expected =
          sh::apply_band_matrices(sh::ivanic_ruedenberg(r, order), Eigen::Map<Eigen::VectorXd>(f.data(), n));
      zonal.rotate(r.data(), axis.data(), weights.data(), got.data());
      for (int i = 0; i < n; ++i)
        if (std::abs(got[i] - expected[i]) > worst) worst = std::abs(got[i] - expected[i]), worst_index = i;
    }
    EXPECT_LE(worst, runtime::tolerance::kDouble) << "order " << order << ", band " << runtime::band_of(worst_index) << ", index " << worst_index;
  }
}

TEST(Zonal, OrdersOutsideTheRangeAreRefused) {
  for (int order : {-3, 0, 65}) EXPECT_THROW(runtime::ZonalRotator<float>{order}, std::invalid_argument) << order;
}

}  // namespace
}  // namespace zhf
