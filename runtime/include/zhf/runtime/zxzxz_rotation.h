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
// Layout: each band is held in four classes by its parities under the mirrors x -> -x and
// y -> -y (cos(m phi) and sin(m phi), each for even and for odd m, indexed by m). X keeps the
// first parity and carries the second to z -> -z, so it sends each class onto one class: four
// dense blocks of about (l/2 + 1)^2 (X's other entries, three quarters of them, are zero),
// applied as packs of rows (pack.h); a turn is elementwise on the (cos, sin) pairs of classes.
//
// The angles are never formed: (cos a, sin a) is R's last column in xy normalised (a = 0 at
// gimbal lock, where any a works), Rz(-a) R = Ry(b) Rz(g) gives g's from its middle row and b's
// are (R_22, |column in xy|); their multiples in double, made as the lanes' factors a quad at a
// time (packs, not one store per lane: those stores cost a tenth of an order-16 call).
//
// A call gathers a group of bands into quads in a local stage (one pass over the input), rotates
// band by band there, with the block products unrolled over a band's 1..8 packs (float to order
// 32, double to 16), and scatters the group back.
//
// Convention as Rotator. Accuracy: X to ~1e-15 (the recurrence), T's rounding over two band
// products and three turns: float within tolerance::zxzxz_float(order) (4 N eps_f), below 1e-6 on
// unit inputs at order 32 (tested). Cost per call:
// 2 sum_l h ceil(4h/lanes) pack multiply-adds (h = l/2 + 1 quads), 6 sum_l ceil(4h/lanes) pack
// operations for the turns, three quad angle additions per quad of the largest band for their
// factors, one square root; no allocation.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstring>
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
// (codegen/src/band_zxzxz.cc, euler_turns), in the kernel's type.
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
  static_assert(kLanes % 4 == 0, "a pack holds whole quads");

  ZxzxzRotation() = default;
  // Any order 1..kMaxZxzxzOrder; throws std::invalid_argument for any other.
  explicit ZxzxzRotation(int order) : order_(order) {
    if (order < 1 || order > kMaxZxzxzOrder)
      throw std::invalid_argument("ZxzxzRotation: order " + std::to_string(order) + " is outside 1.." +
                                  std::to_string(kMaxZxzxzOrder));
    const std::vector<std::vector<long double>> x = quarter_turn_bands<long double>(order);
    offset_.assign(order + 1, 0);
    for (int l = 0; l < order; ++l) offset_[l + 1] = offset_[l] + 2 * quads(l) * packs(l);
    // Band l's quarter turn `second` (0: from layout L, 1: back to it), column j (input quad j),
    // lane e (output quad e / 4, place e % 4) at lanes[(offset_[l] + (second quads(l) + j) packs(l))
    // kLanes + e]. Place q of the first's output holds class partner(l, kPlaceClass[q]), which comes
    // from the input's class at q; the second undoes that.
    std::vector<T> lanes(std::size_t(offset_[order]) * kLanes, T(0));
    for (int l = 1; l < order; ++l)
      for (int second = 0; second < 2; ++second)
        for (int j = 0; j < quads(l); ++j)
          for (int e = 0; e < 4 * quads(l); ++e) {
            const int k = kPlaceClass[e % 4], out_class = second ? k : partner(l, k), in_class = second ? partner(l, k) : k;
            const int row = position(l, out_class, e / 4), col = position(l, in_class, j);
            if (row >= 0 && col >= 0)
              lanes[std::size_t(offset_[l] + (second * quads(l) + j) * packs(l)) * kLanes + e] =
                  T(x[l][row * (2 * l + 1) + col]);
          }
    blocks_.reserve(offset_[order]);
    for (int p = 0; p < offset_[order]; ++p) blocks_.push_back(P::load(&lanes[std::size_t(p) * kLanes]));
    // Band l in layout L, padded to whole packs, at stage positions [band_begin_[l], band_begin_[l + 1]).
    band_begin_.assign(order + 1, 0);
    for (int l = 1; l < order; ++l) band_begin_[l + 1] = band_begin_[l] + packs(l) * kLanes;
  }

  int order() const { return order_; }

  // out[c N^2 + i] for channels c < channels, from in laid out the same way; in and out must not
  // overlap.
  void rotate(const T r[9], const T* in, T* out, int channels) const {
    double rd[9];
    for (int i = 0; i < 9; ++i) rd[i] = double(r[i]);
    // Each lane's factors: a turn by t holds cos(m t) at the lane and sin(m t), signed by the
    // lane's place, at the same lane of its second array; m = 2 (e / 4) + the place's parity
    // (layout L for g and a, L' for b), and b + pi, a + pi carry (-1)^m. Built in double a quad at
    // a time: the first from the first multiples, each next turned by a further 2 t (one angle
    // addition, so m's error stays ~m eps as zyz_multiples'). Odd l's b turn is even l's with the
    // halves of each quad swapped.
    alignas(64) Turns turns;
    double c[3][3], s[3][3];
    zyz_multiples(rd, 3, c[0], s[0], c[1], s[1], c[2], s[2]);
    const int packs_used = packs(order_ - 1);
    for (const int which : {kTurnG, kTurnBEven, kTurnA}) {
      const int angle = which == kTurnA ? 0 : which == kTurnG ? 2 : 1, layout = which == kTurnBEven;
      const double odd_sign = angle == 2 ? 1 : -1;
      const Quad odd = Quad::load(kPlaceOdd[layout]), signs = Quad::load(kPlaceSinSign[layout]);
      const Quad cos_step(c[angle][2]), sin_step(s[angle][2]);
      Quad cos_m = (Quad(1.0) - odd) + odd * Quad(odd_sign * c[angle][1]), sin_m = odd * Quad(odd_sign * s[angle][1]);
      for (int p = 0; p < packs_used; ++p) {
        Quad cos_quads[kLanes / 4], sin_quads[kLanes / 4];
        for (int g = 0; g < kLanes / 4; ++g) {
          if (p + g > 0) {
            const Quad next = cos_m * cos_step - sin_m * sin_step;
            sin_m = sin_m * cos_step + cos_m * sin_step;
            cos_m = next;
          }
          cos_quads[g] = cos_m, sin_quads[g] = sin_m * signs;
        }
        const P cos_lanes = P::from_quads(cos_quads), sin_lanes = P::from_quads(sin_quads);
        cos_lanes.store(turns.cos[which] + p * kLanes);
        sin_lanes.store(turns.sin[which] + p * kLanes);
        if (which == kTurnBEven) {
          cos_lanes.template flip4<2>().store(turns.cos[kTurnBOdd] + p * kLanes);
          sin_lanes.template flip4<2>().store(turns.sin[kTurnBOdd] + p * kLanes);
        }
      }
    }
    const int n = order_ * order_;
    T stage[kStageValues];
    for (int ch = 0; ch < channels; ++ch) {
      const T* f = in + ch * n;
      T* o = out + ch * n;
      o[0] = f[0];
      // Bands in groups that fit the stage: all of a group's inputs are gathered into layout L
      // before its first band is loaded as packs (a pack loaded right after its lanes' scalar
      // stores waits for them), the bands rotated there, then scattered back.
      for (int first = 1, last = 1; first < order_; first = last) {
        while (last < order_ && band_begin_[last + 1] - band_begin_[first] <= kStageValues) ++last;
        const int begin = band_begin_[first];
        for (int l = first; l < last; ++l) gather(l, f + l * l + l, stage + band_begin_[l] - begin);
        for (int l = first; l < last; ++l) {
          T* band = stage + band_begin_[l] - begin;
          switch (packs(l)) {
            case 1: rotate_band<1>(l, band, turns); break;
            case 2: rotate_band<2>(l, band, turns); break;
            case 3: rotate_band<3>(l, band, turns); break;
            case 4: rotate_band<4>(l, band, turns); break;
            case 5: rotate_band<5>(l, band, turns); break;
            case 6: rotate_band<6>(l, band, turns); break;
            case 7: rotate_band<7>(l, band, turns); break;
            case 8: rotate_band<8>(l, band, turns); break;
            default: rotate_band<0>(l, band, turns); break;
          }
        }
        for (int l = first; l < last; ++l) scatter(l, stage + band_begin_[l] - begin, o + l * l + l);
      }
    }
  }

 private:
  // The mirrors x -> -x and y -> -y split a band into four classes: 0 cos(m phi) and 1 sin(m phi)
  // for even m, 2 cos(m phi) and 3 sin(m phi) for odd m. Quad j holds m = 2j and 2j + 1, in
  // layout L as cos 2j, cos(2j + 1), sin(2j + 1), sin 2j (sin(0 phi) and m > l are zeros): two
  // runs of the input band each (f_{l,m} is at m + l), and what X mixes; a turn mixes the two
  // ends and the two middles.
  static int quads(int l) { return l / 2 + 1; }
  static int packs(int l) { return (4 * quads(l) + kLanes - 1) / kLanes; }
  // Quads and packs of the largest band, l = kMaxZxzxzOrder - 1: the sizes of the local arrays.
  static constexpr int kQuadCapacity = (kMaxZxzxzOrder - 1) / 2 + 1;
  static constexpr int kPackCapacity = (4 * kQuadCapacity + kLanes - 1) / kLanes;
  // Where class k's quad j of band l sits in the band (m + l), or -1 for sin(0 phi) and m > l.
  static int position(int l, int k, int j) {
    const int m = 2 * j + k / 2;
    const bool cosine = k % 2 == 0;
    if (m > l || (!cosine && m == 0)) return -1;
    return cosine ? l + m : l - m;
  }
  static constexpr int kPlaceClass[4] = {0, 2, 3, 1};
  // Band l (centre[m] = f_{l,m}) into layout L, zeros to the end of its packs: a pair of values per
  // copy; the last quad of an even l has m = l alone (reading m = l + 1 would leave the band).
  static void gather(int l, const T* centre, T* band) {
    const int pairs = (l + 1) / 2;
    for (int j = 0; j < pairs; ++j) {
      std::memcpy(band + 4 * j, centre + 2 * j, 2 * sizeof(T));
      std::memcpy(band + 4 * j + 2, centre - 2 * j - 1, 2 * sizeof(T));
    }
    band[3] = T(0);  // sin(0 phi): the copy brought f_{l,0}
    int end = 4 * pairs;
    if (l % 2 == 0) band[end] = centre[l], band[end + 1] = band[end + 2] = T(0), band[end + 3] = centre[-l], end += 4;
    for (int i = end; i < packs(l) * kLanes; ++i) band[i] = T(0);
  }
  // Back from layout L: each quad's sines first, so that f_{l,0} comes from its cosine's place.
  static void scatter(int l, const T* band, T* centre) {
    const int pairs = (l + 1) / 2;
    for (int j = 0; j < pairs; ++j) {
      std::memcpy(centre - 2 * j - 1, band + 4 * j + 2, 2 * sizeof(T));
      std::memcpy(centre + 2 * j, band + 4 * j, 2 * sizeof(T));
    }
    if (l % 2 == 0) centre[l] = band[4 * pairs], centre[-l] = band[4 * pairs + 3];
  }
  // X keeps a function's parity under x -> -x and carries its parity under y -> -y to z -> -z
  // (Rx(90) Sy Rx(90)^T = Sz); y_l^m's z-parity is (-1)^(l+m). So class k of X f comes from class
  // partner(l, k) of f alone, a swap of two classes fixed by l's parity; in the layout X leaves,
  // L' (place q holds class partner(l, kPlaceClass[q])), a class's turn partner is its neighbour.
  static int partner(int l, int k) {
    static constexpr int kEven[4] = {0, 2, 1, 3}, kOdd[4] = {3, 1, 2, 0};
    return l % 2 == 0 ? kEven[k] : kOdd[k];
  }
  // A turn's lane factors: out = cos * v + sin * (v with each class's partner swapped in).
  enum TurnIndex { kTurnG, kTurnBEven, kTurnBOdd, kTurnA, kTurns };
  struct Turns {
    T cos[kTurns][kPackCapacity * kLanes], sin[kTurns][kPackCapacity * kLanes];
  };
  // By place, in L (classes 0 2 3 1: cos 2j, cos(2j + 1), sin(2j + 1), sin 2j) and in L' for even
  // l (0 1 3 2: cos 2j, sin 2j, sin(2j + 1), cos(2j + 1)): 1 where m is odd, and the sign of the
  // sine factor (a cosine's lane takes -sin t times its partner, a sine's +sin t).
  using Quad = Pack<double>;
  static_assert(Quad::kLanes == 4, "a quad in double");
  static constexpr double kPlaceOdd[2][4] = {{0, 1, 1, 0}, {0, 0, 1, 1}};
  static constexpr double kPlaceSinSign[2][4] = {{-1, -1, 1, 1}, {-1, 1, 1, -1}};
  // Stage for rotate's band groups, in values: the largest band (64 quads, 256 values, at order
  // 128) and more; 16 KiB of floats.
  static constexpr int kStageValues = 4096;
  static_assert(kStageValues >= kPackCapacity * kLanes, "a band fits the stage");

  // One band in layout L (count packs) through the three turns and two quarter turns; Count =
  // packs(l) known to the compiler (1..8: float to order 32) or 0 (read at run time).
  template <int Count>
  void rotate_band(int l, T* band, const Turns& turns) const {
    const int count = Count > 0 ? Count : packs(l);
    P v[Count > 0 ? Count : kPackCapacity];
    for (int p = 0; p < count; ++p) v[p] = P::load(band + p * kLanes);
    turn<3>(count, turns, kTurnG, v);
    quarter_turn<Count>(l, band, v, 0);
    turn<1>(count, turns, l % 2 ? kTurnBOdd : kTurnBEven, v);
    quarter_turn<Count>(l, band, v, 1);
    turn<3>(count, turns, kTurnA, v);
    for (int p = 0; p < count; ++p) v[p].store(band + p * kLanes);
  }
  // (cos, sin) weights (x, y) -> (x cos mt - y sin mt, x sin mt + y cos mt): g(phi) = f(phi - t);
  // the partners at place q ^ kFlip (3 in layout L, 1 in L').
  template <int kFlip>
  static void turn(int count, const Turns& turns, int which, P* v) {
    for (int p = 0; p < count; ++p)
      v[p] = P::load(turns.cos[which] + p * kLanes) * v[p] + P::load(turns.sin[which] + p * kLanes) * v[p].template flip4<kFlip>();
  }
  // The band through X: out = sum_j column_j * quad j of the input, the input passing through
  // scratch so that each quad is broadcast to every group of four lanes. With Count packs known
  // each broadcast serves all packs, and interleaved halves of the columns add sums where
  // Count is small; otherwise four sums per pack.
  template <int Count>
  void quarter_turn(int l, T* scratch, P* v, int second) const {
    const int count = Count > 0 ? Count : packs(l), h = quads(l);
    for (int p = 0; p < count; ++p) v[p].store(scratch + p * kLanes);
    const P* block = blocks_.data() + offset_[l] + second * h * count;
    if constexpr (Count > 0) {
      constexpr int kSplit = Count <= 4 ? 2 : 1;
      P sum[kSplit][Count];
      for (auto& a : sum)
        for (P& x : a) x = P(0.0);
      int j = 0;
      for (; j + kSplit <= h; j += kSplit)
        for (int u = 0; u < kSplit; ++u) {
          const P x = P::broadcast4(scratch + 4 * (j + u));
          for (int p = 0; p < Count; ++p) sum[u][p] += block[(j + u) * Count + p] * x;
        }
      for (; j < h; ++j) {
        const P x = P::broadcast4(scratch + 4 * j);
        for (int p = 0; p < Count; ++p) sum[0][p] += block[j * Count + p] * x;
      }
      for (int p = 0; p < Count; ++p) {
        P total = sum[0][p];
        for (int u = 1; u < kSplit; ++u) total += sum[u][p];
        v[p] = total;
      }
    } else {
      for (int p = 0; p < count; ++p) {
        const P* column = block + p;
        P s0(0.0), s1(0.0), s2(0.0), s3(0.0);
        int j = 0;
        for (; j + 4 <= h; j += 4) {
          s0 += column[j * count] * P::broadcast4(scratch + 4 * j);
          s1 += column[(j + 1) * count] * P::broadcast4(scratch + 4 * (j + 1));
          s2 += column[(j + 2) * count] * P::broadcast4(scratch + 4 * (j + 2));
          s3 += column[(j + 3) * count] * P::broadcast4(scratch + 4 * (j + 3));
        }
        for (; j < h; ++j) s0 += column[j * count] * P::broadcast4(scratch + 4 * j);
        v[p] = (s0 + s1) + (s2 + s3);
      }
    }
  }

  int order_ = 0;
  std::vector<int> offset_;      // band l's blocks start at offset_[l] (packs)
  std::vector<P> blocks_;        // per band: the two quarter turns, quads(l) columns of packs(l) packs each
  std::vector<int> band_begin_;  // band l in a stage of all bands (values)
};

}  // namespace zhf::runtime
