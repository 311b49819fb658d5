// 10^6 successive small random rotations (0.01 rad about random axes) of one unit vector through
// the generated kernel, against one reference rotation by the product of the steps composed in
// double. Prints max error and norm drift at checkpoints (README, "Numerical limits").
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "zhf/runtime/rotator.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"
#include "zhf_kernels.h"

namespace {

template <class T>
void chain(int order, long steps) {
  const auto rotator = zhf::runtime::Rotator<T>::with(zhf::gen::scalar_kernels<T>(order));
  std::mt19937_64 rng(11);
  zhf::sh::Normal<> normal;
  const int n = order * order;
  Eigen::VectorXd f(n);
  for (int i = 0; i < n; ++i) f[i] = normal(rng);
  f.normalize();
  std::vector<T> v(f.data(), f.data() + n), next(n), r(9);
  zhf::sh::RotationMatrix total = zhf::sh::RotationMatrix::Identity();
  long checkpoint = 1000;
  for (long k = 1; k <= steps; ++k) {
    const zhf::sh::RotationMatrix step = zhf::sh::rotation_about_axis(zhf::sh::random_direction(rng), 0.01);
    total = step * total;
    for (int i = 0; i < 9; ++i) r[i] = static_cast<T>(step(i / 3, i % 3));
    rotator.rotate(r.data(), v.data(), next.data());
    v.swap(next);
    if (k == checkpoint) {
      // The composed matrix drifts from orthonormal by ~k eps_d; re-project before comparing.
      const zhf::runtime::Matrix3 composed = zhf::sh::to_array(total);
      zhf::runtime::Matrix3 projected{};
      zhf::runtime::nearest_rotation(composed.data(), projected.data());
      const Eigen::VectorXd expected =
          zhf::sh::apply_band_matrices(zhf::sh::ivanic_ruedenberg(zhf::sh::to_eigen(projected), order), f);
      double error = 0, norm = 0;
      for (int i = 0; i < n; ++i) {
        error = std::max(error, std::abs(double(v[i]) - expected[i]));
        norm += double(v[i]) * double(v[i]);
      }
      std::printf("| %d | %s | %ld | %.2e | %.2e |\n", order, sizeof(T) == 4 ? "float" : "double", k, error,
                  std::sqrt(norm) - 1.0);
      std::fflush(stdout);
      checkpoint *= 10;
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  const long steps = argc > 1 ? std::atol(argv[1]) : 1000000;
  std::printf("| order | precision | steps | max error | norm - 1 |\n| --- | --- | --- | --- | --- |\n");
  for (int order : {4, 8}) {
    chain<float>(order, steps);
    chain<double>(order, steps);
  }
}
