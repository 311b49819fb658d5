#include "zhf/frames/needlet_studies.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "zhf/runtime/rotation.h"
#include "zhf/runtime/sh_eval.h"

namespace zhf::frames {
namespace {

constexpr Interpolation kInterpolations[] = {Interpolation::kLinear, Interpolation::kQuadratic};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

TableStudy needlet_table_study(const NeedletFrame& frame, const std::vector<int>& sizes, const std::function<void()>& poll) {
  TableStudy study;
  const int levels = static_cast<int>(frame.levels().size());
  std::vector<double> f(runtime::coefficient_count(frame.band_limit() + 1));
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = std::sin(1.0 + 0.7 * double(i)) / std::sqrt(double(f.size()) / 2);
  const std::vector<double> beta = frame.analyze(f);
  const runtime::Matrix3 r = runtime::rotation_from_zyz(0.3, 1.1, -0.7);
  auto start = std::chrono::steady_clock::now();
  const std::vector<double> exact = frame.rotate_exact(beta, r);
  study.exact_seconds = seconds_since(start);
  for (int size : sizes) {
    TableSizeErrors row;
    row.size = size;
    for (int k = 0; k < 2; ++k) {
      for (int a = 1; a < levels; ++a) {
        const auto kernel = [&](double t) { return frame.kernel(a, t); };
        row.kernel[k] = std::max(row.kernel[k], table_error(UniformTable(kernel, size), kernel, kInterpolations[k]));
      }
      const TabulatedNeedletRotation rotation(frame, size, kInterpolations[k]);
      start = std::chrono::steady_clock::now();
      const std::vector<double> turned = rotation.rotate(beta, r);
      row.rotation_seconds[k] = seconds_since(start);
      for (std::size_t i = 0; i < turned.size(); ++i) row.rotation[k] = std::max(row.rotation[k], std::abs(turned[i] - exact[i]));
      poll();
    }
    study.sizes.push_back(row);
  }
  return study;
}

WindowFrameBounds window_frame_bounds(const Window& w, int lmax) {
  WindowFrameBounds bounds{INFINITY, 0};
  for (int l = 1; l <= lmax; ++l) {
    const double sum = window_square_sum(w, l);
    bounds.least = std::min(bounds.least, sum);
    bounds.greatest = std::max(bounds.greatest, sum);
  }
  return bounds;
}

std::vector<double> kernel_energy_outside_caps(const Window& w, int j, const std::vector<double>& ks) {
  std::vector<double> outside;
  for (double k : ks) outside.push_back(kernel_energy_outside(w, j, std::min(runtime::kPi, k / std::pow(w.dilation, j))));
  return outside;
}

NeedletProfile needlet_profile(double dilation, int j) {
  NeedletProfile p;
  p.top_band = needlet_top_band(dilation, j);
  p.first_band = static_cast<int>(std::floor(std::pow(dilation, j - 1))) + 1;
  const std::function<double(double)> needlet = needlet_kernel(dilation, j);
  const auto delta = [&](double t) { return sh_delta_kernel(p.top_band, t); };
  for (double waves : {1.0, 2.0, 4.0}) {
    const double cap = waves * runtime::kPi / p.top_band;
    p.caps.push_back({cap, localisation(needlet, p.top_band, cap), localisation(delta, p.top_band, cap)});
  }
  const double needlet_peak = needlet(1), delta_peak = delta(1);
  constexpr int kSteps = 720;
  for (int i = 0; i <= kSteps; ++i) {
    const double theta = runtime::kPi * i / kSteps, t = std::cos(theta);
    p.samples.push_back({theta, needlet(t) / needlet_peak, delta(t) / delta_peak});
  }
  return p;
}

}  // namespace zhf::frames
