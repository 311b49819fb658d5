// Projection into SH: the coefficients of f up to order N from samples,
//   f_lm = sum_k w_k f(x_k) y_l^m(x_k),
// exact when the nodes integrate every product f y exactly (a cubature of degree >= L_f + N - 1
// for f of bands <= L_f), and otherwise as good as the nodes' quadrature of f y.
//
// Equirectangular images, in zhf's axes: row 0 is the top (+z), row r covers theta in
// [r pi / H, (r + 1) pi / H]; column c covers phi in [c 2 pi / W, (c + 1) 2 pi / W], phi from +x
// towards +y. A pixel's node is its centre and its weight its exact solid angle,
// (2 pi / W) (cos theta_top - cos theta_bottom). Images in other axes: rotate the coefficients
// (zhf rotate). Cost: O(samples N^2).
#pragma once

#include <string>
#include <vector>

#include <cstddef>
#include <functional>

#include "zhf/frames/cubature.h"
#include "zhf/frames/limits.h"

namespace zhf::frames {


// values: channels per node, node-major (values[k * channels + c]). Returns channels vectors of
// N^2 coefficients. Throws std::invalid_argument for an order outside 1..frames::kMaxProjectionOrder or
// values of the wrong length. The samples are summed in fixed blocks on `threads` (0: all cores),
// each block in sample order and the blocks in block order: the result is the same on any thread
// count. checkpoint(samples done, samples) (which may throw) runs on the calling thread between
// rounds of blocks, a fraction of a second apart. Cost: one SH evaluation and channels N^2
// multiply-adds per sample.
std::vector<std::vector<double>> project_samples(const Cubature& nodes, const std::vector<double>& values, int channels, int order,
                                                 int threads = 1,
                                                 const std::function<void(std::size_t, std::size_t)>& checkpoint = {});

// The W x H equirectangular grid's pixel centres and solid angles (degree 0: not an exact rule).
Cubature equirectangular_nodes(int width, int height);

// Test functions with known coefficients, for checking and comparing node sets:
//  - kBandLimited: a fixed random function of bands 0..7 (power ~ 1/(l+1)^2);
//  - kCap: 1 inside the cap of 30 degrees about +z, 0 outside: not band-limited, its coefficients
//    zonal, f_l0 = 2 pi sqrt((2l+1)/(4 pi)) (P_{l-1}(c) - P_{l+1}(c)) / (2l+1), c = cos 30 deg.
enum class TestFunction { kBandLimited, kCap };
double test_function(TestFunction f, const Point& x);
std::vector<double> test_function_coefficients(TestFunction f, int order);

// Projection error of node sets on the test functions: max |f_lm - exact| over l < order.
struct ProjectionError {
  std::string nodes;
  int samples = 0;
  double band_limited = 0, cap = 0;
};
ProjectionError projection_error(const Cubature& nodes, int order, int threads = 1);

}  // namespace zhf::frames
