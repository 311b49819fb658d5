// ZxzxzRotation: the zxzxz factorisation for any order to kMaxZxzxzOrder, the run-time path for
// orders where it beats the lobe table (Rotator::from_table picks it by order, Rotator::zxzxz for
// any order; docs/performance.md gives the measurements). With zyz Euler angles
// R = Rz(a) Ry(b) Rz(g), Ry(b) = Rx(-90) Rz(b) Rx(+90) and X^T = Z(pi) X Z(pi) (a half turn about z
// carries x onto -x),
//   D(R) f = Z(a) X^T Z(b) X Z(g) f = Z(a + pi) X Z(b + pi) X Z(g) f,
// where Z(t) turns each (cos m phi, sin m phi) pair by m t and X = D(Rx(+90 deg)) is fixed per band,
// made once by the recurrence (band_recurrence.h: no lobe table) in long double, whose rounding
// grows with l (x86-64's 80-bit long double: 2.6e-10 at order 128; where long double is double,
// ~5e-7 there, below float's tolerance still).
//
// Layout: X commutes with the mirror x -> -x, which keeps cos(m phi) for even m and sin(m phi) for
// odd m (class E) and flips the others (class O). Band l is held as E_m = f_{l,m} (m even) or
// f_{l,-m} (m odd) and O_m = f_{l,-m} (m even; O_0 = 0) or f_{l,m} (m odd), m = 0..l, so X is two
// dense (l+1)^2 blocks, applied as packs of rows (pack.h), and a turn is elementwise:
// E' = c E + s' O, O' = c O - s' E with s' = (-1)^(m+1) sin(m t).
//
// The angles are never formed: (cos a, sin a) is R's last column in xy normalised (a = 0 at
// gimbal lock, where any a works), Rz(-a) R = Ry(b) Rz(g) gives g's from its middle row and b's
// are (R_22, |column in xy|); their multiples by doubling and angle addition, in double.
//
// A call gathers a group of bands into class form in a local stage (one pass over the input),
// rotates band by band there, with the block products unrolled over a band's packs at orders to
// 32, and scatters the group back.
//
// Convention as Rotator. Accuracy: X to ~1e-15 (the recurrence), T's rounding over two band
// products and three turns: float below 1e-6 on unit inputs at order 32 (tested). Cost per call:
// 2 sum_l (l+1) ceil((l+1)/lanes) pack multiply-adds, ~12 N^2 lane operations for the turns, one
// square root; no allocation.
#pragma once

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "zhf/runtime/band_recurrence.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/pack.h"
#include "zhf/runtime/tolerances.h"

namespace zhf::runtime {

// cos(m t) and sin(m t) for m < order of the zyz Euler angles of r, without forming them
// (see above): c_a[m], s_a[m], and so on. Even m by doubling m/2, odd m by adding t to m - 1:
// error ~m eps at every angle. The emitted kernels build the same steps into their graph
// (codegen/src/kernels.cc, euler_turns), in the kernel's type.
inline void zyz_multiples(const double r[9], int order, double* c_a, double* s_a, double* c_b, double* s_b, double* c_g,
                          double* s_g) {
  const double column2 = r[2] * r[2] + r[5] * r[5];
  const bool locked = !(column2 > tolerance::kGimbalLockSine2);
  const double inverse = locked ? 1.0 : 1 / std::sqrt(column2);
  const double ca = locked ? 1.0 : r[2] * inverse, sa = locked ? 0.0 : r[5] * inverse;
  const double first[3][2] = {{ca, sa}, {r[8], column2 * inverse}, {ca * r[4] - sa * r[1], ca * r[3] - sa * r[0]}};
  double* c[3] = {c_a, c_b, c_g};
  double* s[3] = {s_a, s_b, s_g};
  for (int k = 0; k < 3; ++k) {
    c[k][0] = 1, s[k][0] = 0;
    if (order > 1) c[k][1] = first[k][0], s[k][1] = first[k][1];
    for (int m = 2; m < order; ++m) {
      if (m % 2 == 0) {
        const double ch = c[k][m / 2], sh = s[k][m / 2];
        c[k][m] = (ch - sh) * (ch + sh);
        s[k][m] = 2 * ch * sh;
      } else {
        c[k][m] = c[k][m - 1] * first[k][0] - s[k][m - 1] * first[k][1];
        s[k][m] = s[k][m - 1] * first[k][0] + c[k][m - 1] * first[k][1];
      }
    }
  }
}

template <class T>
class ZxzxzRotation {
 public:
  using P = Pack<T>;
  static constexpr int kLanes = P::kLanes;

  ZxzxzRotation() = default;
  // Any order 1..kMaxZxzxzOrder; throws std::invalid_argument for any other.
  explicit ZxzxzRotation(int order) : order_(order) {
    if (order < 1 || order > kMaxZxzxzOrder)
      throw std::invalid_argument("ZxzxzRotation: order " + std::to_string(order) + " is outside 1.." +
                                  std::to_string(kMaxZxzxzOrder));
    const std::vector<std::vector<long double>> x = quarter_turn_bands<long double>(order);
    offset_.assign(order + 1, 0);
    for (int l = 0; l < order; ++l) offset_[l + 1] = offset_[l] + 2 * (l + 1) * packs(l);
    // Band l's class-k block, column j, row i at lanes[(offset_[l] + (k (l+1) + j) packs(l)) kLanes + i].
    std::vector<T> lanes(std::size_t(offset_[order]) * kLanes, T(0));
    for (int l = 1; l < order; ++l)
      for (int k = 0; k < 2; ++k)
        for (int j = 0; j <= l; ++j)
          for (int i = 0; i <= l; ++i) {
            const int row = position(l, k, i), col = position(l, k, j);
            if (row >= 0 && col >= 0)
              lanes[std::size_t(offset_[l] + (k * (l + 1) + j) * packs(l)) * kLanes + i] = T(x[l][row * (2 * l + 1) + col]);
          }
    blocks_.reserve(offset_[order]);
    for (int p = 0; p < offset_[order]; ++p) blocks_.push_back(P::load(&lanes[std::size_t(p) * kLanes]));
    // Band l's classes, padded to whole packs, at stage positions [class_begin_[l], class_begin_[l + 1]):
    // E then O, packs(l) kLanes values each; input i (band l, i >= 1) at class_slot_[i].
    class_begin_.assign(order + 1, 0);
    class_slot_.assign(std::size_t(order) * order, 0);
    for (int l = 1; l < order; ++l) {
      class_begin_[l + 1] = class_begin_[l] + 2 * packs(l) * kLanes;
      for (int k = 0; k < 2; ++k)
        for (int m = 0; m <= l; ++m)
          if (position(l, k, m) >= 0) class_slot_[l * l + position(l, k, m)] = class_begin_[l] + k * packs(l) * kLanes + m;
    }
  }

  int order() const { return order_; }

  // out[c N^2 + i] for channels c < channels, from in laid out the same way; in and out must not
  // overlap.
  void rotate(const T r[9], const T* in, T* out, int channels) const {
    double rd[9];
    for (int i = 0; i < 9; ++i) rd[i] = double(r[i]);
    // The turns in the order applied: g, then b + pi and a + pi (the signs (-1)^m), in class form
    // padded to whole packs.
    double c[3][kMaxZxzxzOrder], s[3][kMaxZxzxzOrder];
    zyz_multiples(rd, order_, c[2], s[2], c[1], s[1], c[0], s[0]);
    constexpr int kPacks = (kMaxZxzxzOrder + kLanes - 1) / kLanes;
    const int used = packs(order_ - 1);
    P cos_turn[3][kPacks], sin_turn[3][kPacks];
    for (int k = 0; k < 3; ++k) {
      T cs[kPacks * kLanes], sn[kPacks * kLanes];
      for (int m = 0; m < used * kLanes; ++m) {
        const double shift = k > 0 && m % 2 ? -1.0 : 1.0;
        cs[m] = m < order_ ? T(shift * c[k][m]) : T(0);
        sn[m] = m < order_ ? T((m % 2 ? shift : -shift) * s[k][m]) : T(0);
      }
      for (int p = 0; p < used; ++p) cos_turn[k][p] = P::load(cs + p * kLanes), sin_turn[k][p] = P::load(sn + p * kLanes);
    }
    const int n = order_ * order_;
    T stage[kStageValues];
    for (int ch = 0; ch < channels; ++ch) {
      const T* f = in + ch * n;
      T* o = out + ch * n;
      o[0] = f[0];
      // Bands in groups whose classes fit the stage: all of a group's inputs are gathered into
      // class order before its first band is loaded as packs (a pack loaded right after its lanes'
      // scalar stores waits for them), the bands rotated there, then scattered back.
      for (int first = 1, last = 1; first < order_; first = last) {
        while (last < order_ && class_begin_[last + 1] - class_begin_[first] <= kStageValues) ++last;
        const int begin = class_begin_[first], values = class_begin_[last] - begin;
        const int* slot = class_slot_.data();
        for (int i = 0; i < values; ++i) stage[i] = T(0);  // padding and O_0
        for (int i = first * first; i < last * last; ++i) stage[slot[i] - begin] = f[i];
        for (int l = first; l < last; ++l) {
          T* band = stage + class_begin_[l] - begin;
          switch (packs(l)) {
            case 1: rotate_band<1>(l, band, cos_turn, sin_turn); break;
            case 2: rotate_band<2>(l, band, cos_turn, sin_turn); break;
            case 3: rotate_band<3>(l, band, cos_turn, sin_turn); break;
            case 4: rotate_band<4>(l, band, cos_turn, sin_turn); break;
            default: rotate_band<0>(l, band, cos_turn, sin_turn); break;
          }
        }
        for (int i = first * first; i < last * last; ++i) o[i] = stage[slot[i] - begin];
      }
    }
  }

 private:
  static int packs(int l) { return (l + 1 + kLanes - 1) / kLanes; }
  // Where class k's element m of band l sits in the band (m + l), or -1 for O_0.
  static int position(int l, int k, int m) {
    const bool cosine = (m % 2 == 0) == (k == 0);
    if (!cosine && m == 0) return -1;
    return cosine ? l + m : l - m;
  }
  // Stage for rotate's band groups, in values: the largest band's classes (2 x 16 packs at order
  // 128) and more; 16 KiB of floats.
  static constexpr int kStageValues = 4096;
  static_assert(kStageValues >= 2 * ((kMaxZxzxzOrder + kLanes - 1) / kLanes) * kLanes, "a band fits the stage");

  // One band in class form (E then O, count packs each) through the three turns and two quarter
  // turns; Count = packs(l) known to the compiler (1..4: orders to 32) or 0 (read at run time).
  template <int Count, class Turns>
  void rotate_band(int l, T* band, const Turns& cos_turn, const Turns& sin_turn) const {
    constexpr int kPacks = (kMaxZxzxzOrder + kLanes - 1) / kLanes;
    const int count = Count > 0 ? Count : packs(l);
    P e[Count > 0 ? Count : kPacks], q[Count > 0 ? Count : kPacks];
    for (int p = 0; p < count; ++p) e[p] = P::load(band + p * kLanes), q[p] = P::load(band + (count + p) * kLanes);
    turn(count, cos_turn[0], sin_turn[0], e, q);
    quarter_turn<Count>(l, band, e, 0);
    quarter_turn<Count>(l, band, q, 1);
    turn(count, cos_turn[1], sin_turn[1], e, q);
    quarter_turn<Count>(l, band, e, 0);
    quarter_turn<Count>(l, band, q, 1);
    turn(count, cos_turn[2], sin_turn[2], e, q);
    for (int p = 0; p < count; ++p) e[p].store(band + p * kLanes), q[p].store(band + (count + p) * kLanes);
  }
  static void turn(int count, const P* c, const P* s, P* e, P* q) {
    for (int p = 0; p < count; ++p) {
      const P x = e[p], y = q[p];
      e[p] = c[p] * x + s[p] * y;
      q[p] = c[p] * y - s[p] * x;
    }
  }
  // Class k of band l through its block, in place: out = sum_j column_j * in_j, the class's values
  // passing through scratch to be broadcast one by one. With Count packs known, each broadcast
  // serves all packs and Count x kChains independent sums (8 where registers allow) keep both
  // multiply-add pipes busy; otherwise four sums per pack.
  template <int Count>
  void quarter_turn(int l, T* scratch, P* packs_of_class, int k) const {
    const int count = Count > 0 ? Count : packs(l);
    for (int p = 0; p < count; ++p) packs_of_class[p].store(scratch + p * kLanes);
    const P* block = blocks_.data() + offset_[l] + k * (l + 1) * count;
    if constexpr (Count > 0) {
      constexpr int kChains = Count >= 4 ? 2 : 8 / Count;
      P sum[kChains][Count];
      for (int u = 0; u < kChains; ++u)
        for (int p = 0; p < Count; ++p) sum[u][p] = P(0.0);
      int j = 0;
      for (; j + kChains <= l + 1; j += kChains)
        for (int u = 0; u < kChains; ++u) {
          const P x = P::broadcast(scratch[j + u]);
          for (int p = 0; p < Count; ++p) sum[u][p] += block[(j + u) * Count + p] * x;
        }
      for (; j <= l; ++j) {
        const P x = P::broadcast(scratch[j]);
        for (int p = 0; p < Count; ++p) sum[0][p] += block[j * Count + p] * x;
      }
      for (int p = 0; p < Count; ++p) {
        P total = sum[0][p];
        for (int u = 1; u < kChains; ++u) total += sum[u][p];
        packs_of_class[p] = total;
      }
    } else {
      for (int p = 0; p < count; ++p) {
        const P* column = block + p;
        P s0(0.0), s1(0.0), s2(0.0), s3(0.0);
        int j = 0;
        for (; j + 3 <= l; j += 4) {
          s0 += column[j * count] * P::broadcast(scratch[j]);
          s1 += column[(j + 1) * count] * P::broadcast(scratch[j + 1]);
          s2 += column[(j + 2) * count] * P::broadcast(scratch[j + 2]);
          s3 += column[(j + 3) * count] * P::broadcast(scratch[j + 3]);
        }
        for (; j <= l; ++j) s0 += column[j * count] * P::broadcast(scratch[j]);
        packs_of_class[p] = (s0 + s1) + (s2 + s3);
      }
    }
  }

  int order_ = 0;
  std::vector<int> offset_;   // band l's blocks start at offset_[l] (packs)
  std::vector<P> blocks_;     // per band: class E then O, (l+1) columns of packs(l) packs each
  std::vector<int> class_begin_;  // band l's classes in a stage of all bands (values)
  std::vector<int> class_slot_;   // input i's place in that stage
};

}  // namespace zhf::runtime
