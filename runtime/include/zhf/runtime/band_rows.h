// Band rows: the zxzxz rotation of one float vector of order 4..8 with every band across the
// lanes of AVX2 registers, for builds that target AVX2 and FMA (kBandRowsBuilt). zhf_kernels.h
// picks it for float where it was measured faster than the generated scalar kernels
// (docs/design.md, "Which path a Rotator takes"), and Rotator::from_table and
// Rotator::zxzxz take it for float at its orders.
//
// The factorisation is ZxzxzRotation's (zxzxz_rotation.h): D(R) = Z(a + pi) X Z(b + pi) X Z(g),
// X = D(Rx(90 deg)) per band, the angles' multiples from R's entries by zyz_multiples' steps, in
// float, the three angles side by side in one register, except that the first multiples of a and
// g are not multiplied by the reciprocal of sin b but divided by it (order 4) or scaled by a power
// of two near it and the rows scaled back (orders 5..8): shorter chains (1.1x, then 1.03x at 5).
//
// Layout: band l is two rows of 8 lanes, lane m of the cosine row holding the coefficient of
// cos(m phi) and lane m of the sine row that of sin(m phi) (lane 0 zero). A turn Z(t) is then
// elementwise with the same factor rows (cos m t, sin m t) for every band: two multiplies and two
// fused multiply-adds per row pair. X sends each input to one row only: its coefficient at
// (|m| + l) even goes to the cosine row, odd to the sine row (X keeps the parity under x -> -x and
// carries y -> -y to z -> -z), so X is one fused multiply-add per input, that input broadcast
// across the lanes of its target row's column. Bands 2 and 3 share one register pair (band 3 in
// lanes 0..3, band 2 in lanes 4..7, so one in-lane broadcast serves both); band 2 is held with its
// rows exchanged and its sines negated there, which gives its inputs the targets of band 3's at
// the same lanes and leaves the turns unchanged. Bands 0 and 1 take one register of their own
// (avx2_fma.h's rotate_bands01), which is the whole rotation at order 2 (bands01_kernels: the
// fastest float path, from_table's and zxzxz's there). Z(pi)'s signs (-1)^m are folded into X's
// columns, so one table serves both X.
//
// Convention as Rotator (rotator.h): out = coefficients of f(R^T w), R row-major, in and out
// N^2 floats each, not overlapping. Accuracy: X rounded to float once; the rounding of two block
// products and three turns, within tolerance::kFloatRotation on random unit inputs (tested at
// every order with extreme rotations). Cost per call, order 6: 3 x 3 turns of a register pair,
// 2 x 28 broadcasts and fused multiply-adds for X, ~60 instructions for the angles' multiples,
// one square root and one division; no allocation (the tables are built once, on first use).
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "zhf/runtime/avx2_fma.h"
#include "zhf/runtime/band_recurrence.h"
#include "zhf/runtime/kernel_set.h"
#include "zhf/runtime/tolerances.h"

namespace zhf::runtime {

// Whether this build has the band-rows kernels (AVX2 and FMA targeted, GCC or Clang).
inline constexpr bool kBandRowsBuilt = ZHF_RUNTIME_AVX2_FMA;
inline constexpr int kBandRowsMinOrder = 4, kBandRowsMaxOrder = 8;

// The band-rows kernels of order N (kBandRowsMinOrder..kBandRowsMaxOrder) for a Rotator; defined
// where kBandRowsBuilt. Build the order's tables on the first call.
template <int N>
KernelSet<float> band_rows_kernels();
// Order 2 on the same terms (path "bands01"): bands 0 and 1 in one register; defined where
// kBandRowsBuilt.
KernelSet<float> bands01_kernels();
// Whether this header has kernels for an order known at run time (order 2 and the band rows'), and
// those kernels; defined where kBandRowsBuilt.
inline constexpr bool band_rows_hold(int order) {
  return order == 2 || (order >= kBandRowsMinOrder && order <= kBandRowsMaxOrder);
}
KernelSet<float> band_rows_kernels(int order);

#if ZHF_RUNTIME_AVX2_FMA

template <int N>
class BandRows {
  static_assert(N >= kBandRowsMinOrder && N <= kBandRowsMaxOrder, "band rows hold orders 4..8");

 public:
  // The one instance of the order (its tables are made on the first call).
  static const BandRows& instance() {
    static const BandRows rows;
    return rows;
  }

  // channels vectors in[c N^2 + i] to out[c N^2 + i] under one R; in and out must not overlap.
  void rotate(const float r[9], const float* in, float* out, int channels) const {
    Turns turns;
    angle_rows(r, turns);
    for (int c = 0; c < channels; ++c, in += N * N, out += N * N) rotate_one(r, turns, in, out);
  }

 private:
  // Register pair u: u = 0 holds bands 3 and 2, u >= 1 band u + 3.
  static constexpr int kUnits = N - 3;
  static constexpr int band_of_unit(int u) { return u == 0 ? 3 : u + 3; }
  // The row (0 cosine, 1 sine) that input lane j of row h goes to, -1 if it holds nothing: by the
  // parity of |m| + l (for the shared pair the rule of band 3, which band 2's exchanged rows obey).
  static constexpr int target(int u, int h, int j) { return u > 0 && h == 1 && j == 0 ? -1 : (j + band_of_unit(u)) & 1; }
  // Inputs per row: lanes 0..3 of the pair (both bands at once), 0..l of a single band.
  static constexpr int inputs(int u) { return u == 0 ? 4 : band_of_unit(u) + 1; }

  struct Turns {
    __m256 c[3], s[3];  // lanes m: cos and sin of m a, m b, m g (a, b, g = 0, 1, 2)
  };

  // The coefficient held at lane `lane` of row h of unit u: its band, its place m + l in the
  // band and the sign it is held with; false where the lane holds nothing.
  static bool held(int u, int h, int lane, int& l, int& place, int& sign) {
    const bool pair = u == 0, exchanged = pair && lane >= 4;
    l = pair ? (lane < 4 ? 3 : 2) : band_of_unit(u);
    const int m = pair ? lane % 4 : lane;
    const bool cosine = exchanged ? h == 1 : h == 0;
    if (m > l || (!cosine && m == 0)) return false;
    place = cosine ? l + m : l - m;
    sign = exchanged && !cosine ? -1 : 1;
    return true;
  }

  BandRows() {
    const std::vector<std::vector<long double>> x = quarter_turn_bands<long double>(N);
    for (int u = 0; u < kUnits; ++u)
      for (int h = 0; h < 2; ++h)
        for (int j = 0; j < 8; ++j)
          for (int lane = 0; lane < 8; ++lane) {
            float& entry = columns_[u][h][j][lane];
            entry = 0;
            const int t = target(u, h, j);
            int l, place_out, sign_out, l_in, place_in, sign_in;
            if (t < 0 || j >= inputs(u) || !held(u, t, lane, l, place_out, sign_out)) continue;
            // In the pair, lane j's broadcast carries band 3's input j to lanes 0..3 and band 2's
            // (lane j + 4) to lanes 4..7.
            if (!held(u, h, u == 0 && lane >= 4 ? j + 4 : j, l_in, place_in, sign_in) || l_in != l) continue;
            const int m_out = place_out - l;
            const long double zpi = m_out % 2 ? -1 : 1;  // Z(pi) after X
            entry = float(zpi * sign_out * sign_in * x[l][place_out * (2 * l + 1) + place_in]);
          }
    for (int l = 4; l < N; ++l)
      for (int lane = 0; lane < 8; ++lane) {
        sine_in_[l][lane] = lane >= 1 && lane <= l ? l - lane : 7;
        sine_out_[l][lane] = lane < l ? l - lane : 0;
        cosine_mask_[l][lane] = lane <= l ? -1 : 0;
        sine_mask_[l][lane] = lane < l ? -1 : 0;
      }
  }

  // The three angles' multiples m = 0..7 (zero past the order): the zyz_multiples steps with the
  // angles in lanes a, b, g of one register, then transposed to one row per angle. The first
  // multiples of a and g come from their numerators (cos a, sin a, cos g, sin g) sin b, formed
  // while the square root runs. Order 4 divides them by sin b after the root. From order 5 no
  // division follows the root: they are scaled by p, a power of two near 1 / sin b read off
  // column2's exponent (exact), so the multiples come out times (p sin b)^m, and each row's lane m
  // is scaled back by q^m, q = 1 / (p sin b) from a division that runs beside the chain (1.03x at
  // order 5; at order 4, with half the multiples, 0.97x).
  static void angle_rows(const float r[9], Turns& turns) {
    constexpr bool kScaledBack = N > 4;
    const float column2 = r[2] * r[2] + r[5] * r[5];
    const bool locked = !(column2 > float(tolerance::kGimbalLockSine2));
    const float sine = std::sqrt(column2), scaled2 = locked ? 1.0f : column2;
    // scaled2 = 2^e x with 1 <= x < 2 (a normal float: above kGimbalLockSine2): p = 2^-floor(e / 2)
    // and 1 / p^2 = 2^(2 floor(e / 2)), made from its exponent in the vector unit (through the
    // integer registers it ran slower).
    const __m128i half_exponent = _mm_srai_epi32(
        _mm_sub_epi32(_mm_srli_epi32(_mm_castps_si128(_mm_set_ss(scaled2)), 23), _mm_set1_epi32(127)), 1);
    const __m128i bias = _mm_set1_epi32(127);
    const float p = with_biased_exponent(_mm_sub_epi32(bias, half_exponent));
    const float p_inverse2 = with_biased_exponent(_mm_add_epi32(bias, _mm_add_epi32(half_exponent, half_exponent)));
    // q^2 = 1 / (column2 p^2) and q = 1 / (p sin b), begun here so that they are ready by the end.
    const float q2 = (1.0f / scaled2) * p_inverse2, q = q2 * (p * (locked ? 1.0f : sine));
    const __m128 numerators = locked ? _mm_setr_ps(1.0f, 0.0f, r[4], r[3])
                                     : _mm_setr_ps(r[2], r[5], r[2] * r[4] - r[5] * r[1], r[2] * r[3] - r[5] * r[0]);
    const __m128 first = kScaledBack ? _mm_mul_ps(numerators, _mm_set1_ps(p))  // ca, sa, cg, sg times p sin b
                                     : _mm_div_ps(numerators, _mm_set1_ps(locked ? 1.0f : sine));  // ca, sa, cg, sg
    const __m128 c1 = _mm_blend_ps(first, _mm_setr_ps(0, r[8], 0, 0), 0xa);
    const __m128 s1 = _mm_blend_ps(_mm_permute_ps(first, _MM_SHUFFLE(2, 3, 0, 1)), _mm_setr_ps(0, sine, 0, 0), 0xa);
    __m128 c[8], s[8];
    c[0] = _mm_set1_ps(1.0f), s[0] = _mm_setzero_ps(), c[1] = c1, s[1] = s1;
    for (int m = 2; m < 8; ++m) {
      if (m >= N) {
        c[m] = s[m] = _mm_setzero_ps();
      } else if (m % 2 == 0) {  // doubling m / 2
        const __m128 ch = c[m / 2], sh = s[m / 2], p = _mm_mul_ps(ch, sh);
        c[m] = _mm_mul_ps(_mm_sub_ps(ch, sh), _mm_add_ps(ch, sh));
        s[m] = _mm_add_ps(p, p);
      } else {  // m - 1 plus one
        c[m] = _mm_fmsub_ps(c[m - 1], c1, _mm_mul_ps(s[m - 1], s1));
        s[m] = _mm_fmadd_ps(s[m - 1], c1, _mm_mul_ps(c[m - 1], s1));
      }
    }
    transpose_to_rows(c, turns.c);
    transpose_to_rows(s, turns.s);
    if constexpr (kScaledBack) {
      // Lane m of a's and g's rows times q^m (the bits of m: q^2, q^4, then q, which comes last).
      const __m256 one = _mm256_set1_ps(1.0f);
      const __m256 scale = _mm256_mul_ps(_mm256_mul_ps(_mm256_blend_ps(one, _mm256_set1_ps(q2), 0xcc),
                                                       _mm256_blend_ps(one, _mm256_set1_ps(q2 * q2), 0xf0)),
                                         _mm256_blend_ps(one, _mm256_set1_ps(q), 0xaa));
      for (int angle : {0, 2}) {
        turns.c[angle] = _mm256_mul_ps(turns.c[angle], scale);
        turns.s[angle] = _mm256_mul_ps(turns.s[angle], scale);
      }
    }
  }

  // 2^(e - 127) for the biased exponent e in lane 0, 1 <= e <= 254.
  static float with_biased_exponent(__m128i e) { return _mm_cvtss_f32(_mm_castsi128_ps(_mm_slli_epi32(e, 23))); }

  // x[m] holds lanes (a, b, g, -); rows[k] gets lane m = x[m][k], k < 3. At order 4 only the
  // pair reads them: lanes 0..3, repeated in both halves.
  static void transpose_to_rows(const __m128 x[8], __m256 rows[3]) {
    constexpr int high = N > 4 ? 4 : 0;
    const __m256 r0 = _mm256_insertf128_ps(_mm256_castps128_ps256(x[0]), x[high], 1);
    const __m256 r1 = _mm256_insertf128_ps(_mm256_castps128_ps256(x[1]), x[high + 1], 1);
    const __m256 r2 = _mm256_insertf128_ps(_mm256_castps128_ps256(x[2]), x[high + 2], 1);
    const __m256 r3 = _mm256_insertf128_ps(_mm256_castps128_ps256(x[3]), x[high + 3], 1);
    const __m256 ab01 = _mm256_unpacklo_ps(r0, r1), g01 = _mm256_unpackhi_ps(r0, r1);
    const __m256 ab23 = _mm256_unpacklo_ps(r2, r3), g23 = _mm256_unpackhi_ps(r2, r3);
    rows[0] = _mm256_shuffle_ps(ab01, ab23, _MM_SHUFFLE(1, 0, 1, 0));
    rows[1] = _mm256_shuffle_ps(ab01, ab23, _MM_SHUFFLE(3, 2, 3, 2));
    rows[2] = _mm256_shuffle_ps(g01, g23, _MM_SHUFFLE(1, 0, 1, 0));
  }

  static void turn(__m256 v[2], __m256 c, __m256 s) {
    const __m256 cosine = _mm256_fmsub_ps(c, v[0], _mm256_mul_ps(s, v[1]));
    v[1] = _mm256_fmadd_ps(s, v[0], _mm256_mul_ps(c, v[1]));
    v[0] = cosine;
  }

  // Lane k of each 128-bit half, across that half.
  template <int K>
  static __m256 in_lane_broadcast(__m256 v) {
    return _mm256_permute_ps(v, K * 0x55);
  }

  // The first input of row h of unit u that goes to target row t, -1 if none.
  static constexpr int first_input(int u, int h, int t) {
    for (int j = 0; j < inputs(u); ++j)
      if (target(u, h, j) == t) return j;
    return -1;
  }

  // One input (row H, lane J) of unit U into its target row's accumulator (one per input row, so
  // the two chains run side by side).
  template <int U, int H, int J>
  void accumulate(const __m256 (&source)[2][2], __m256 (&sum)[2][2]) const {
    constexpr int t = target(U, H, J);
    if constexpr (t >= 0 && J < inputs(U)) {
      const __m256 input = in_lane_broadcast<J % 4>(source[H][J / 4]);
      if constexpr (J == first_input(U, H, t))  // a multiply, not a multiply-add onto zero: 1 cycle off the chain
        sum[t][H] = _mm256_mul_ps(_mm256_load_ps(columns_[U][H][J]), input);
      else
        sum[t][H] = _mm256_fmadd_ps(_mm256_load_ps(columns_[U][H][J]), input, sum[t][H]);
    }
  }

  template <int U, int... J>
  void quarter_turn(__m256 v[2], std::integer_sequence<int, J...>) const {
    // The pair's inputs are in-lane already; a single band's lane j comes from half j / 4.
    __m256 source[2][2];
    for (int h = 0; h < 2; ++h) {
      source[h][0] = U == 0 ? v[h] : _mm256_permute2f128_ps(v[h], v[h], 0x00);
      source[h][1] = _mm256_permute2f128_ps(v[h], v[h], 0x11);
    }
    __m256 sum[2][2] = {{_mm256_setzero_ps(), _mm256_setzero_ps()}, {_mm256_setzero_ps(), _mm256_setzero_ps()}};
    (accumulate<U, 0, J>(source, sum), ...);
    (accumulate<U, 1, J>(source, sum), ...);
    v[0] = _mm256_add_ps(sum[0][0], sum[0][1]);
    v[1] = _mm256_add_ps(sum[1][0], sum[1][1]);
  }

  template <int... U>
  void quarter_turns(__m256 (&v)[kUnits][2], std::integer_sequence<int, U...>) const {
    (quarter_turn<U>(v[U], std::make_integer_sequence<int, 8>()), ...);
  }

  // Pairs reach lanes 0..3 of the factor rows only, repeated in both halves.
  static void turns_of_angle(__m256 (&v)[kUnits][2], const Turns& turns, int angle) {
    if constexpr (N == 4)
      turn(v[0], turns.c[angle], turns.s[angle]);
    else
      turn(v[0], _mm256_permute2f128_ps(turns.c[angle], turns.c[angle], 0x00),
           _mm256_permute2f128_ps(turns.s[angle], turns.s[angle], 0x00));
    for (int u = 1; u < kUnits; ++u) turn(v[u], turns.c[angle], turns.s[angle]);
  }

  // Band l >= 4 from in (cosine row: m = 0..l at l^2 + l + m; sine row: m = 1..l at l^2 + l - m).
  void load_band(int l, const float* in, __m256 v[2]) const {
    const float* band = in + l * l;
    v[0] = _mm256_maskload_ps(band + l, _mm256_load_si256(reinterpret_cast<const __m256i*>(cosine_mask_[l])));
    v[1] = _mm256_permutevar8x32_ps(_mm256_maskload_ps(band, _mm256_load_si256(reinterpret_cast<const __m256i*>(sine_mask_[l]))),
                                    _mm256_load_si256(reinterpret_cast<const __m256i*>(sine_in_[l])));
  }

  // Band L >= 4 to out: each store may run past the band into the next one, which is stored
  // after it; the last band's stores stop at N^2.
  template <int L>
  void store_band(const __m256 v[2], float* out) const {
    const __m256 sines = _mm256_permutevar8x32_ps(v[1], _mm256_load_si256(reinterpret_cast<const __m256i*>(sine_out_[L])));
    avx2::store_first<L * L + 8 <= N * N ? 8 : L>(out + L * L, sines);
    avx2::store_first<L * L + L + 8 <= N * N ? 8 : L + 1>(out + L * L + L, v[0]);
  }
  template <int... U>
  void store_bands(const __m256 (&v)[kUnits][2], [[maybe_unused]] float* out, std::integer_sequence<int, U...>) const {
    (store_band<U + 4>(v[U + 1], out), ...);
  }

  void rotate_one(const float r[9], const Turns& turns, const float* in, float* out) const {
    __m256 v[kUnits][2];
    {  // bands 3 and 2: [cos 0..3 | -sin 0..2, 0] and [sin 0..3 | cos 0..2, 0]
      const __m128 zero = _mm_setzero_ps();
      const __m128 cos3 = _mm_loadu_ps(in + 12);
      const __m128 sin3 = _mm_blend_ps(_mm_permute_ps(_mm_loadu_ps(in + 8), _MM_SHUFFLE(1, 2, 3, 0)), zero, 0x1);
      const __m128 neg_sin2 = _mm_blend_ps(_mm_sub_ps(zero, _mm_permute_ps(_mm_loadu_ps(in + 4), _MM_SHUFFLE(0, 0, 1, 0))), zero, 0x9);
      const __m128 cos2 = _mm_blend_ps(_mm_loadu_ps(in + 6), zero, 0x8);
      v[0][0] = _mm256_insertf128_ps(_mm256_castps128_ps256(cos3), neg_sin2, 1);
      v[0][1] = _mm256_insertf128_ps(_mm256_castps128_ps256(sin3), cos2, 1);
    }
    for (int u = 1; u < kUnits; ++u) load_band(band_of_unit(u), in, v[u]);
    // Stage by stage over all bands, so each stage's independent work sits side by side.
    turns_of_angle(v, turns, 2);
    quarter_turns(v, std::make_integer_sequence<int, kUnits>());
    turns_of_angle(v, turns, 1);
    quarter_turns(v, std::make_integer_sequence<int, kUnits>());
    turns_of_angle(v, turns, 0);
    avx2::rotate_bands01(r, in, out);
    {
      const __m128 cos3 = _mm256_castps256_ps128(v[0][0]), neg_sin2 = _mm256_extractf128_ps(v[0][0], 1);
      const __m128 sin3 = _mm256_castps256_ps128(v[0][1]), cos2 = _mm256_extractf128_ps(v[0][1], 1);
      const __m128 sin2 = _mm_sub_ps(_mm_setzero_ps(), neg_sin2);              // [0, sin 1, sin 2, 0]
      _mm_storeu_ps(out + 4, _mm_shuffle_ps(sin2, cos2, _MM_SHUFFLE(1, 0, 1, 2)));  // sin 2, sin 1, cos 0, cos 1
      _mm_storeu_ps(out + 6, cos2);                                            // cos 0..2; lane 3 stored over next
      _mm_storeu_ps(out + 9, _mm_permute_ps(sin3, _MM_SHUFFLE(0, 1, 2, 3)));  // sin 3..1; lane 3 stored over next
      _mm_storeu_ps(out + 12, cos3);
    }
    store_bands(v, out, std::make_integer_sequence<int, kUnits - 1>());
  }

  // columns_[u][h][j]: the column, over the lanes of its target row, of input lane j of row h.
  alignas(32) float columns_[kUnits][2][8][8];
  // For bands 4..N-1: sine rows from and to memory order, and the lanes a band fills.
  alignas(32) int sine_in_[N][8], sine_out_[N][8], cosine_mask_[N][8], sine_mask_[N][8];
};

template <int N>
KernelSet<float> band_rows_kernels() {
  BandRows<N>::instance();
  KernelSet<float> k;
  k.order = N;
  k.path = "band_rows";
  k.rotate = [](const float* r, const float* in, float* out) { BandRows<N>::instance().rotate(r, in, out, 1); };
  k.rotate_rgb = [](const float* r, const float* in, float* out) { BandRows<N>::instance().rotate(r, in, out, 3); };
  k.rotate_batch = [](std::size_t count, const float* r, const float* in, float* out) {
    const BandRows<N>& rows = BandRows<N>::instance();
    for (std::size_t v = 0; v < count; ++v) rows.rotate(r + 9 * v, in + N * N * v, out + N * N * v, 1);
  };
  return k;
}

inline KernelSet<float> bands01_kernels() {
  KernelSet<float> k;
  k.order = 2;
  k.path = "bands01";
  k.rotate = &avx2::rotate_bands01;
  k.rotate_batch = &rotate_each<float, 2, &avx2::rotate_bands01>;
  k.rotate_rgb = [](const float* r, const float* in, float* out) {
    for (int c = 0; c < 3; ++c) avx2::rotate_bands01(r, in + 4 * c, out + 4 * c);
  };
  return k;
}

// Throws std::invalid_argument where !band_rows_hold(order).
inline KernelSet<float> band_rows_kernels(int order) {
  switch (order) {
    case 2: return bands01_kernels();
    case 4: return band_rows_kernels<4>();
    case 5: return band_rows_kernels<5>();
    case 6: return band_rows_kernels<6>();
    case 7: return band_rows_kernels<7>();
    case 8: return band_rows_kernels<8>();
    default: break;
  }
  throw std::invalid_argument("band_rows_kernels: order " + std::to_string(order) + " is outside 2 and " +
                              std::to_string(kBandRowsMinOrder) + ".." + std::to_string(kBandRowsMaxOrder));
}

#endif

}  // namespace zhf::runtime

