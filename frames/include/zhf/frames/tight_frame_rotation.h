// Rotation through a tight frame: the lobes sit at the M nodes xi_k of a cubature exact to degree
// 2 (N - 1) (a t-design: weights lambda_k = 4 pi / M), where sum_k lambda_k y(xi_k) y(xi_k)^T is
// the identity on every band below N (frame.h). So band l of f needs no inverse at all:
//   f_l = sum_k lambda_k f_l(xi_k) y_l(xi_k)   and   g_l = sum_k lambda_k f_l(xi_k) y_l(R xi_k)
// for g(w) = f(R^T w). The condition number is exactly 1 at every order; the price is M ~ 2 N^2
// lobes for every band, against the sparse tables' 2l + 1 per band.
//
// Accuracy: float rounding of sums of M terms, ~eps sqrt(M) |f|, at any order. Cost per rotation:
// M (N^2 multiply-adds for the lobe values, an SH evaluation at R xi_k, N^2 multiply-adds out):
// O(N^4). No allocation after construction.
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "zhf/frames/cubature.h"
#include "zhf/frames/limits.h"
#include "zhf/runtime/sh_eval.h"

namespace zhf::frames {


template <class T>
class TightFrameRotator {
 public:
  // `nodes` must be exact to degree 2 (order - 1); throws std::invalid_argument otherwise.
  TightFrameRotator(int order, const Cubature& nodes)
      : order_(order), n_(order * order), points_(static_cast<int>(nodes.points.size())), legendre_(order) {
    if (order < 2 || order > frames::kMaxTightFrameOrder)
      throw std::invalid_argument("tight-frame rotation: order " + std::to_string(order) + " outside 2.." +
                                  std::to_string(frames::kMaxTightFrameOrder));
    if (nodes.degree < 2 * (order - 1) || nodes.points.empty() || nodes.points.size() != nodes.weights.size())
      throw std::invalid_argument("tight-frame rotation: order " + std::to_string(order) + " needs nodes exact to degree " +
                                  std::to_string(2 * (order - 1)) + " ('" + nodes.name + "' is exact to " + std::to_string(nodes.degree) + ")");
    std::vector<double> y(n_);
    for (int k = 0; k < points_; ++k) {
      const Point& p = nodes.points[k];
      directions_.insert(directions_.end(), {T(p[0]), T(p[1]), T(p[2])});
      runtime::eval_sh(order, p.data(), y.data(), legendre_);
      for (double v : y) lobes_.push_back(T(v * nodes.weights[k]));  // lambda_k folded into the analysis
    }
  }

  int order() const { return order_; }
  int lobes() const { return points_; }

  // out = the coefficients of f(R^T w); r row-major. in and out must not overlap.
  void rotate(const T r[9], const T* in, T* out) const {
    std::array<T, frames::kMaxTightFrameOrder> value{};
    std::array<T, frames::kMaxTightFrameOrder * frames::kMaxTightFrameOrder> y{};
    out[0] = in[0];
    for (int i = 1; i < n_; ++i) out[i] = T(0);
    for (int k = 0; k < points_; ++k) {
      const T* at = &lobes_[std::size_t(k) * n_];
      for (int l = 1; l < order_; ++l) {
        T sum = 0;
        for (int i = l * l; i < (l + 1) * (l + 1); ++i) sum += in[i] * at[i];
        value[l] = sum;
      }
      const T* d = &directions_[3 * std::size_t(k)];
      const T turned[3] = {r[0] * d[0] + r[1] * d[1] + r[2] * d[2], r[3] * d[0] + r[4] * d[1] + r[5] * d[2],
                           r[6] * d[0] + r[7] * d[1] + r[8] * d[2]};
      runtime::eval_sh(order_, turned, y.data(), legendre_);
      for (int l = 1; l < order_; ++l)
        for (int i = l * l; i < (l + 1) * (l + 1); ++i) out[i] += value[l] * y[i];
    }
  }

 private:
  int order_, n_, points_;
  runtime::TabulatedLegendreCoefficients legendre_;
  std::vector<T> directions_;  // 3 per point
  std::vector<T> lobes_;       // lambda_k y(xi_k), N^2 per point
};

}  // namespace zhf::frames
