#include "zhf/frames/projection.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "zhf/frames/limits.h"
#include "zhf/runtime/parallel.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/sh/random.h"

namespace zhf::frames {
namespace {

constexpr int kBandLimitedBands = 8;  // bands 0..7
// Samples summed as one block: the unit of a projection's threads (0.2 ms of work at order 3, a
// tenth of a second at 64).
constexpr std::size_t kProjectionBlock = 4096;
constexpr double kCapRadius = 30 * runtime::kPi / 180;

const std::vector<double>& band_limited_coefficients() {
  static const std::vector<double> f = [] {
    std::mt19937_64 rng(8);
    sh::Normal<> normal(0, 1);
    std::vector<double> c(runtime::coefficient_count(kBandLimitedBands));
    for (int l = 0; l < kBandLimitedBands; ++l)
      for (int m = -l; m <= l; ++m) c[runtime::index(l, m)] = normal(rng) / (l + 1);
    return c;
  }();
  return f;
}

// P_l(t) from the runtime's normalised Q_l^0 = sqrt((2l+1)/(4 pi)) P_l.
double legendre(int l, double t) { return runtime::legendre_q(l, 0, t) / (std::sqrt(2 * l + 1) * runtime::kInvSqrt4Pi); }

}  // namespace

std::vector<std::vector<double>> project_samples(const Cubature& nodes, const std::vector<double>& values, int channels, int order,
                                                 int threads, const std::function<void(std::size_t, std::size_t)>& checkpoint) {
  if (order < 1 || order > frames::kMaxProjectionOrder)
    throw std::invalid_argument("projection order must be 1.." + std::to_string(frames::kMaxProjectionOrder) + " (got " + std::to_string(order) + ")");
  if (channels < 1 || values.size() != nodes.points.size() * channels)
    throw std::invalid_argument("samples: " + std::to_string(values.size()) + " values for " + std::to_string(nodes.points.size()) +
                                " nodes and " + std::to_string(channels) + " channels");
  const std::size_t n = runtime::coefficient_count(order), samples = nodes.points.size();
  const std::size_t blocks = (samples + kProjectionBlock - 1) / kProjectionBlock;
  const int workers = runtime::worker_count(threads);
  const runtime::TabulatedLegendreCoefficients legendre_coefficients(order);
  // One round sums a block per worker into its own slot (channels N^2 doubles: a transfer projection
  // of thousands of channels holds one a worker); the slots are added in block order.
  std::vector<std::vector<double>> block_sums(std::min(blocks, std::size_t(workers)), std::vector<double>(channels * n));
  std::vector<std::vector<double>> out(channels, std::vector<double>(n, 0.0));
  for (std::size_t first = 0; first < blocks; first += block_sums.size()) {
    const std::size_t round = std::min(block_sums.size(), blocks - first);
    runtime::parallel_for(static_cast<int>(round), workers, [&](int b) {
      std::vector<double>& sum = block_sums[b];
      std::fill(sum.begin(), sum.end(), 0.0);
      std::vector<double> y(n);
      const std::size_t begin = (first + b) * kProjectionBlock, end = std::min(samples, begin + kProjectionBlock);
      for (std::size_t k = begin; k < end; ++k) {
        runtime::eval_sh(order, nodes.points[k].data(), y.data(), legendre_coefficients);
        for (int c = 0; c < channels; ++c) {
          const double weighted = nodes.weights[k] * values[k * channels + c];
          if (weighted == 0) continue;
          for (std::size_t i = 0; i < n; ++i) sum[c * n + i] += weighted * y[i];
        }
      }
    });
    for (std::size_t b = 0; b < round; ++b)
      for (int c = 0; c < channels; ++c)
        for (std::size_t i = 0; i < n; ++i) out[c][i] += block_sums[b][c * n + i];
    if (checkpoint) checkpoint(std::min(samples, (first + round) * kProjectionBlock), samples);
  }
  return out;
}

Cubature equirectangular_nodes(int width, int height) {
  if (width < 1 || height < 1) throw std::invalid_argument("an image needs at least one pixel");
  Cubature c;
  c.degree = 0;
  c.name = "grid " + std::to_string(width) + "x" + std::to_string(height);
  c.points.reserve(static_cast<std::size_t>(width) * height);
  for (int r = 0; r < height; ++r) {
    const double top = runtime::kPi * r / height, bottom = runtime::kPi * (r + 1) / height, theta = (top + bottom) / 2;
    const double solid = 2 * runtime::kPi / width * (std::cos(top) - std::cos(bottom));
    for (int col = 0; col < width; ++col) {
      const double phi = 2 * runtime::kPi * (col + 0.5) / width;
      c.points.push_back({std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)});
      c.weights.push_back(solid);
    }
  }
  return c;
}

double test_function(TestFunction f, const Point& x) {
  if (f == TestFunction::kCap) return x[2] > std::cos(kCapRadius) ? 1.0 : 0.0;
  const std::vector<double>& c = band_limited_coefficients();
  std::vector<double> y(c.size());
  runtime::eval_sh(kBandLimitedBands, x.data(), y.data());
  double sum = 0;
  for (std::size_t i = 0; i < c.size(); ++i) sum += c[i] * y[i];
  return sum;
}

std::vector<double> test_function_coefficients(TestFunction f, int order) {
  std::vector<double> out(runtime::coefficient_count(order), 0.0);
  if (f == TestFunction::kBandLimited) {
    const std::vector<double>& c = band_limited_coefficients();
    for (std::size_t i = 0; i < out.size() && i < c.size(); ++i) out[i] = c[i];
    return out;
  }
  const double t = std::cos(kCapRadius);
  for (int l = 0; l < order; ++l) {
    const double integral = l == 0 ? 1 - t : (legendre(l - 1, t) - legendre(l + 1, t)) / (2 * l + 1);  // int_t^1 P_l
    out[runtime::index(l, 0)] = 2 * runtime::kPi * std::sqrt((2 * l + 1) / (4 * runtime::kPi)) * integral;
  }
  return out;
}

ProjectionError projection_error(const Cubature& nodes, int order, int threads) {
  ProjectionError e;
  e.nodes = nodes.name;
  e.samples = static_cast<int>(nodes.points.size());
  for (TestFunction f : {TestFunction::kBandLimited, TestFunction::kCap}) {
    std::vector<double> values;
    for (const Point& p : nodes.points) values.push_back(test_function(f, p));
    const std::vector<double> got = project_samples(nodes, values, 1, order, threads)[0], exact = test_function_coefficients(f, order);
    double worst = 0;
    for (std::size_t i = 0; i < got.size(); ++i) worst = std::max(worst, std::abs(got[i] - exact[i]));
    (f == TestFunction::kCap ? e.cap : e.band_limited) = worst;
  }
  return e;
}

}  // namespace zhf::frames
