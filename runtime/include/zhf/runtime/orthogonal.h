// Orthogonal transforms of SH vectors: rotations and reflections (det -1) alike, in zhf's
// convention (docs/conventions.md): Q maps v to Q v and the result holds the coefficients of
// f(Q^T w).
//
// - A reflection Q is -R with R = -Q a rotation. Inversion w -> -w multiplies band l by (-1)^l,
//   so f(Q^T w) = f(-(R^T w)) is the rotation by R with the odd bands negated. Cost: a rotation
//   plus N^2 / 2 negations; accuracy: the rotation's.
// - The 16 axis maps that keep the z axis up to sign (sign flips of x, y and z, the swap of x and
//   y, and their products) move every coefficient to one place with a sign: no arithmetic, so the
//   result is bit-exact. Other signed permutations (those that move z, such as y-up to z-up) mix
//   the coefficients of a band with irrational weights and go through the rotation.
//
// Derivation of the exact map: with such a Q, Q^T sends (x, y, z) to (x', y', s z) where
// x' + i y' = u (x + i c y), u in {1, i, -1, -i}, c = +-1. Writing C_m + i S_m = (x + i y)^m,
// (x' + i y')^m = u^m (C_m + i c S_m), and the normalised Legendre factor of y_l^m obeys
// Q_l^m(-z) = (-1)^(l+m) Q_l^m(z). So y_l^m(Q^T w) is +-y_l^m(w) or +-y_l^-m(w).
#pragma once

#include <cmath>
#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "zhf/runtime/rotation.h"
#include "zhf/runtime/rotator.h"
#include "zhf/runtime/sh_eval.h"

namespace zhf::runtime {

// out[i] = sign[i] * in[source[i]]: a signed permutation of N^2 coefficients.
struct CoefficientMap {
  std::vector<int> source;
  std::vector<int> sign;  // +1 or -1

  template <class T>
  void apply(const T* in, T* out) const {
    for (std::size_t i = 0; i < source.size(); ++i) out[i] = sign[i] > 0 ? in[source[i]] : -in[source[i]];
  }
};

// The exact map of q when it is one of the 16 z-keeping axis maps (entries exactly 0 and +-1);
// nothing otherwise.
template <class T>
std::optional<CoefficientMap> exact_coefficient_map(const T q[9], int order) {
  for (int i = 0; i < 9; ++i)
    if (q[i] != 0 && q[i] != 1 && q[i] != -1) return std::nullopt;
  if (q[2] != 0 || q[5] != 0 || q[6] != 0 || q[7] != 0 || q[8] == 0) return std::nullopt;
  // (x', y') = the xy block of Q^T applied to (x, y): x' = q[0] x + q[3] y, y' = q[1] x + q[4] y.
  int quarter_turns, c;  // u = i^quarter_turns
  if (q[3] == 0 && q[1] == 0 && q[0] != 0 && q[4] != 0) {
    const int a = q[0] > 0 ? 1 : -1, b = q[4] > 0 ? 1 : -1;  // x' = a x, y' = b y
    quarter_turns = a > 0 ? 0 : 2;
    c = a * b;
  } else if (q[0] == 0 && q[4] == 0 && q[3] != 0 && q[1] != 0) {
    const int a = q[3] > 0 ? 1 : -1, b = q[1] > 0 ? 1 : -1;  // x' = a y, y' = b x
    quarter_turns = b > 0 ? 1 : 3;
    c = -a * b;
  } else {
    return std::nullopt;
  }
  const int z_sign = q[8] > 0 ? 1 : -1;
  CoefficientMap map;
  map.source.resize(std::size_t(order) * order);
  map.sign.resize(map.source.size());
  for (int l = 0; l < order; ++l) {
    map.source[index(l, 0)] = index(l, 0);
    map.sign[index(l, 0)] = (z_sign < 0 && l % 2) ? -1 : 1;
    for (int m = 1; m <= l; ++m) {
      const int q_sign = (z_sign < 0 && (l + m) % 2) ? -1 : 1;
      // f(Q^T w) = sum f_i y_i(Q^T w); y_l^m(Q^T w) = q_sign sqrt2 Q C'_m, y_l^-m(Q^T w) = q_sign sqrt2 Q S'_m,
      // C' + i S' = i^k (C + i c S):
      //   k = 0: C' = C,     S' = c S      k = 1: C' = -c S, S' = C
      //   k = 2: C' = -C,    S' = -c S     k = 3: C' = c S,  S' = -C
      const int cos_i = index(l, m), sin_i = index(l, -m);
      int cos_target, cos_sign, sin_target, sin_sign;  // where f's cos / sin coefficient lands, and its sign
      switch ((quarter_turns * m) % 4) {
        case 0: cos_target = cos_i, cos_sign = 1, sin_target = sin_i, sin_sign = c; break;
        case 1: cos_target = sin_i, cos_sign = -c, sin_target = cos_i, sin_sign = 1; break;
        case 2: cos_target = cos_i, cos_sign = -1, sin_target = sin_i, sin_sign = -c; break;
        default: cos_target = sin_i, cos_sign = c, sin_target = cos_i, sin_sign = -1; break;
      }
      map.source[cos_target] = cos_i;
      map.sign[cos_target] = q_sign * cos_sign;
      map.source[sin_target] = sin_i;
      map.sign[sin_target] = q_sign * sin_sign;
    }
  }
  return map;
}

// One orthogonal transform, prepared once for any number of vectors of the rotator's order.
template <class T>
class OrthogonalTransform {
 public:
  // q must be orthogonal (validate_rotation with Handedness::kEither); the rotator is used unless
  // the map is exact, and must outlive this.
  OrthogonalTransform(const Rotator<T>& rotator, const T q[9]) : rotator_(&rotator) {
    exact_ = exact_coefficient_map(q, rotator.order());
    invert_ = determinant(q) < 0;
    for (int i = 0; i < 9; ++i) rotation_[i] = invert_ ? -q[i] : q[i];
  }
  bool exact() const { return exact_.has_value(); }
  bool reflection() const { return invert_; }

  // in and out must not overlap.
  void apply(const T* in, T* out) const {
    if (exact_) return exact_->apply(in, out);
    rotator_->rotate(rotation_, in, out);
    if (invert_) negate_odd_bands(rotator_->order(), out);
  }

  // The band matrices of the transform (the rotation's, odd bands negated for a reflection).
  DenseRotation<T> dense() const {
    const DenseRotation<T> d = rotator_->dense(rotation_);
    if (!invert_) return d;
    std::vector<std::vector<T>> bands = d.bands();
    for (std::size_t l = 1; l < bands.size(); l += 2)
      for (T& x : bands[l]) x = -x;
    return DenseRotation<T>(d.order(), std::move(bands));
  }

  // The transform prepared for count vectors: the exact map, the band matrices when they pay
  // (band_matrices_pay), else vector by vector. It refers to this transform, which must outlive it.
  class Prepared {
   public:
    void apply(const T* in, T* out) const {
      if (dense_) {
        dense_->apply(in, out);
      } else {
        transform_->apply(in, out);
      }
    }

   private:
    friend class OrthogonalTransform;
    const OrthogonalTransform* transform_ = nullptr;
    std::optional<DenseRotation<T>> dense_;
  };
  Prepared prepare(std::size_t count) const {
    Prepared p;
    p.transform_ = this;
    if (!exact_ && band_matrices_pay(count, rotator_->order())) p.dense_.emplace(dense());
    return p;
  }

  static void negate_odd_bands(int order, T* f) {
    for (int l = 1; l < order; l += 2)
      for (int i = l * l; i < (l + 1) * (l + 1); ++i) f[i] = -f[i];
  }

 private:
  const Rotator<T>* rotator_;
  std::optional<CoefficientMap> exact_;
  bool invert_ = false;
  T rotation_[9];
};

// count vectors, each under its own orthogonal q[9 v + k] (as OrthogonalTransform): runs of
// rotations whose entries are not all 0 and +-1 go to the rotator's per-item batch together
// (rotate_batch, in lanes where its kernels have them); reflections and the axis maps (exact)
// vector by vector. in and out must not overlap.
template <class T>
void transform_each(const Rotator<T>& rotator, std::size_t count, const T* q, const T* in, T* out) {
  const std::size_t n = static_cast<std::size_t>(rotator.coefficients());
  auto batched = [](const T* m) {
    for (int i = 0; i < 9; ++i)
      if (m[i] != 0 && m[i] != 1 && m[i] != -1) return determinant(m) > 0;
    return false;
  };
  for (std::size_t v = 0; v < count;) {
    std::size_t end = v;
    while (end < count && batched(q + 9 * end)) ++end;
    if (end > v) {
      rotator.rotate_batch(end - v, q + 9 * v, in + n * v, out + n * v, 1);
      v = end;
    } else {
      OrthogonalTransform<T>(rotator, q + 9 * v).apply(in + n * v, out + n * v);
      ++v;
    }
  }
}

}  // namespace zhf::runtime
