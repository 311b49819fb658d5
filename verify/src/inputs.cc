#include "inputs.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include <Eigen/Core>

#include "zhf/io/limits.h"
#include "zhf/runtime/product.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"

namespace zhf::verify {

std::vector<double> Inputs::rotation_stream() const {
  std::vector<double> stream;
  for (int v = 0; v < count; ++v) {
    stream.insert(stream.end(), rotations.begin() + 9 * v, rotations.begin() + 9 * v + 9);
    stream.insert(stream.end(), axes.begin() + 3 * v, axes.begin() + 3 * v + 3);
  }
  return stream;
}

int dense_size(int order) { return codegen::dense_matrix_offset(order); }

Inputs make_inputs(int order, int random_count, const runtime::LobeTable& table, const std::vector<int>& zero_bands) {
  Inputs in;
  in.order = order;
  in.live.assign(order, true);
  for (int l : zero_bands)
    if (l >= 0 && l < order) in.live[l] = false;
  std::vector<Eigen::Vector3d> lobes;
  for (const runtime::TableLobe& lobe : table.lobes) lobes.emplace_back(lobe.xyz[0], lobe.xyz[1], lobe.xyz[2]);
  std::vector<std::pair<std::string, sh::RotationMatrix>> rotations = sh::extreme_rotations(lobes);
  std::mt19937_64 rng(20261122 + order);
  for (int k = 0; k < random_count; ++k) rotations.push_back({"random", sh::random_rotation(rng)});
  sh::Normal<> normal;
  for (const auto& [name, r] : rotations) {
    for (int i = 0; i < 9; ++i) in.rotations.push_back(r(i / 3, i % 3));
    Eigen::VectorXd f(order * order);
    for (int i = 0; i < f.size(); ++i) f[i] = in.live[runtime::band_of(i)] ? normal(rng) : 0.0;
    f.normalize();
    in.coeffs.insert(in.coeffs.end(), f.data(), f.data() + f.size());
    // The first zonal axis is +z (zonal coefficients then equal the weights); the rest random.
    Eigen::Vector3d a = in.names.empty() ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    in.axes.insert(in.axes.end(), a.data(), a.data() + 3);
    in.names.push_back(name);
  }
  in.count = static_cast<int>(rotations.size());
  return in;
}

namespace {

double zonal_weight(const Inputs& in, int v, int c, int l) {
  const int n = in.order * in.order;
  return in.live[l] ? in.coeffs[size_t(n) * ((v + c) % in.count) + l] : 0.0;
}

}  // namespace

std::vector<std::vector<double>> reference_outputs(const Inputs& in, const runtime::LobeTable& table,
                                                   const std::vector<Mode>& modes) {
  using codegen::KernelKind;
  const int n = in.order * in.order;
  const size_t block = size_t(kMaxChannels) * n;
  std::vector<std::vector<double>> ref(modes.size(), std::vector<double>(block * in.count, 0.0));
  const bool products = std::any_of(modes.begin(), modes.end(), [](const Mode& m) {
    return m.kind == KernelKind::kProduct || m.kind == KernelKind::kSquare;
  });
  const runtime::ShProduct product(products ? in.order : 1);
  for (int v = 0; v < in.count; ++v) {
    sh::RotationMatrix r;
    for (int i = 0; i < 9; ++i) r(i / 3, i % 3) = in.rotations[9 * v + i];
    const sh::BandMatrices bands = sh::ivanic_ruedenberg(r, in.order);
    std::vector<Eigen::VectorXd> rotated(kMaxChannels), zonal(kMaxChannels);
    std::vector<double> y(n);
    runtime::eval_sh(in.order, &in.axes[3 * v], y.data());
    for (int c = 0; c < kMaxChannels; ++c) {
      const Eigen::Map<const Eigen::VectorXd> f(&in.coeffs[size_t(n) * ((v + c) % in.count)], n);
      rotated[c] = sh::apply_band_matrices(bands, f);
      // The zonal function's coefficients in the unrotated frame, then the reference rotation.
      Eigen::VectorXd z(n);
      for (int i = 0; i < n; ++i) {
        const int l = runtime::band_of(i);
        z[i] = std::sqrt(4 * runtime::kPi / (2 * l + 1)) * zonal_weight(in, v, c, l) * y[i];
      }
      zonal[c] = sh::apply_band_matrices(bands, z);
    }
    const double* f = &in.coeffs[size_t(n) * v];
    for (size_t k = 0; k < modes.size(); ++k) {
      double* out = &ref[k][block * v];
      const Mode& m = modes[k];
      switch (m.kind) {
        case KernelKind::kRotate:
        case KernelKind::kSignalTailored:
        case KernelKind::kBatch:
        case KernelKind::kApplyMatrices:
        case KernelKind::kRotationMatrices:
          for (int c = 0; c < m.channels; ++c)
            for (int i = 0; i < n; ++i) out[c * n + i] = rotated[c][i];
          break;
        case KernelKind::kZonal:
          for (int c = 0; c < m.channels; ++c)
            for (int i = 0; i < n; ++i) out[c * n + i] = zonal[c][i];
          break;
        case KernelKind::kProduct:  // channel 1 is the next input's coefficients
          product.product(f, &in.coeffs[size_t(n) * ((v + 1) % in.count)], out);
          break;
        case KernelKind::kSquare:
          product.square(f, out);
          break;
        case KernelKind::kShade:
        case KernelKind::kShadeLobes: {  // the transfer vector is the next input's coefficients
          const double* t = &in.coeffs[size_t(n) * ((v + 1) % in.count)];
          for (int i = 0; i < n; ++i) out[0] += rotated[0][i] * t[i];
          break;
        }
        case KernelKind::kShEval:
          runtime::eval_sh(in.order, &in.rotations[9 * v], out);  // the first row of R is a unit direction
          break;
        case KernelKind::kLobeWeights:
        case KernelKind::kFromSamples:
          for (int i = 0; i < std::min(n, 4); ++i) out[i] = f[i];
          for (const runtime::TableBand& band : table.bands) {
            const int size = 2 * band.l + 1, b0 = band.l * band.l;
            for (int i = 0; i < size; ++i)
              for (int j = 0; j < size; ++j)
                out[b0 + i] += (m.kind == KernelKind::kLobeWeights ? band.inverse(j, i) : band.inverse(i, j)) * f[b0 + j];
          }
          break;
      }
    }
  }
  return ref;
}

}  // namespace zhf::verify
