// The signal-tailored rotation arranged lobe-parallel, for SIMD CPUs: loops over the lobes
// (rotate each by R^T; evaluate the SH there and dot each band with f) whose bodies are the
// same straight-line code for every lobe, so the compiler runs them across SIMD lanes; then
// f' = A_l s per band as a dense multiply of SIMD columns. Orders 3..8.
//
// It uses its own lobe tables (generated zhf_lanes_orderN.h): continuous directions chosen for
// the least float error amplification, not the sparse tables' SH zeros, since a dense SIMD A_l s
// costs less here than the sparse scalar one. With them each step runs in float where the
// float error model allows (LanesTables<N>::kLobeStage), which halves the work per lane.
// The fast choice for one vector per rotation where the build targets AVX2 or wider; zhf_kernels.h
// picks it where benchmarks/path_bench.cc measured it faster (generated/paths/).
// Where the build targets AVX2 and FMA (avx2_fma.h) and an order's 2N - 1 lobes fit one register
// of 8 floats (orders 3 and 4) with its lobe stage in float, the float kernel is written out in
// intrinsics instead: one register holds the lobes, the SH at them come from the generated
// sh_eval run on packs, each band's samples are 2l + 1 fused multiply-adds, and A_l s is one
// in-lane broadcast and one fused multiply-add per lobe and output register. No square root, no
// division and no trigonometry: the whole call is one short dependency chain (order 4: about 75
// vector instructions, 21 ns against the band rows' 31 ns, benchmarks/NOTES.md).
// Accuracy: within 1e-6 of the reference on random unit inputs at the default stage (tested).
#pragma once

#include <cstddef>
#include <cstring>
#include <type_traits>
#include <utility>

#include "zhf/runtime/avx2_fma.h"
#include "zhf/runtime/lobe_stage.h"
#include "zhf/runtime/pack.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/rotator.h"

namespace zhf::gen {
// The lobe directions and dense inverses of one order, specialised in zhf_lanes_orderN.h:
// kLobeStage (the cheapest LobeStage the float error model allows), kLobes[2N-1][3] and
// kInverse[N-2][2N-1][2N-1].
template <int N>
struct LanesTables;
}  // namespace zhf::gen

namespace zhf::runtime {

namespace lanes_detail {

// Lobes per loop, padded to a multiple of 8 (AVX float lanes) with copies of lobe 0; also the
// rows of the padded columns of A_l.
constexpr int padded_lobes(int order) { return (2 * order - 1 + 7) / 8 * 8; }

template <int N, class W>
struct LobeColumns {
  alignas(64) W x[padded_lobes(N)];
  alignas(64) W y[padded_lobes(N)];
  alignas(64) W z[padded_lobes(N)];
};

template <int N, class W>
constexpr LobeColumns<N, W> lobe_columns() {
  LobeColumns<N, W> c{};
  for (int d = 0; d < padded_lobes(N); ++d) {
    const int lobe = d < 2 * N - 1 ? d : 0;
    c.x[d] = W(gen::LanesTables<N>::kLobes[lobe][0]);
    c.y[d] = W(gen::LanesTables<N>::kLobes[lobe][1]);
    c.z[d] = W(gen::LanesTables<N>::kLobes[lobe][2]);
  }
  return c;
}

// sum_m f_{l,m} y_{l,m}: a fixed trip count, so it unrolls into the loop body; two partial sums
// halve the dependency chain.
template <int L, class W>
inline W band_dot(const W* f, const W* y) {
  W even = 0, odd = 0;
  for (int m = 0; m < 2 * L; m += 2) {
    even += f[L * L + m] * y[L * L + m];
    odd += f[L * L + m + 1] * y[L * L + m + 1];
  }
  return (even + f[L * L + 2 * L] * y[L * L + 2 * L]) + odd;
}

// columns[l - 2][d]: column d of A_l, zero beyond its 2l + 1 rows.
template <int N, class T>
struct DenseColumns {
  alignas(64) T columns[N - 2][2 * N - 1][padded_lobes(N)];
};

template <int N, class T>
constexpr DenseColumns<N, T> dense_columns() {
  DenseColumns<N, T> c{};
  for (int b = 0; b < N - 2; ++b)
    for (int d = 0; d < 2 * N - 1; ++d)
      for (int row = 0; row < 2 * N - 1; ++row) c.columns[b][d][row] = T(gen::LanesTables<N>::kInverse[b][row][d]);
  return c;
}

// out[band L] = A_L s: a sum of whole padded columns scaled by the samples.
template <int N, int L, class T, class W>
inline void band_multiply(const T (&columns)[2 * N - 1][padded_lobes(N)], const W* s, T* out) {
  constexpr int kRows = padded_lobes(N);
#if defined(__GNUC__) && !defined(ZHF_LANES_PLAIN_LOOPS)
  // GCC vectorises the plain loops below across d, with transposes; vector types keep the
  // columns whole.
  typedef T Column __attribute__((vector_size(kRows * sizeof(T))));
  Column even = {}, odd = {};
  for (int d = 0; d < 2 * L + 1; ++d) {
    Column column;
    std::memcpy(&column, columns[d], sizeof column);
    (d % 2 == 0 ? even : odd) += column * T(s[d]);
  }
  const Column sum = even + odd;
  T rows[kRows];
  std::memcpy(rows, &sum, sizeof rows);
#else
  T rows[kRows] = {};
  for (int d = 0; d < 2 * L + 1; ++d)
    for (int row = 0; row < kRows; ++row) rows[row] += columns[d][row] * T(s[d]);
#endif
  for (int m = 0; m < 2 * L + 1; ++m) out[L * L + m] = rows[m];
}

template <int N, class T, class W, int... L>
inline void multiply_bands(const DenseColumns<N, T>& a, const W (*s)[padded_lobes(N)], T* out,
                           std::integer_sequence<int, L...>) {
  (band_multiply<N, L + 2>(a.columns[L], s[L], out), ...);
}

template <int N, class W, int... L>
inline void band_samples(const W* f, const W* y, W (*s)[padded_lobes(N)], int d, std::integer_sequence<int, L...>) {
  ((s[L][d] = band_dot<L + 2>(f, y)), ...);
}

#if ZHF_RUNTIME_AVX2_FMA && !defined(ZHF_LANES_PLAIN_LOOPS)
#define ZHF_LANES_ONE_REGISTER 1
#else
#define ZHF_LANES_ONE_REGISTER 0
#endif

// Whether rotate_lanes<N, T, kStage> is the kernel held in one register of lobes (header comment):
// float, lobes fitting 8 lanes, lobe stage float, in builds that have it.
template <int N, class T, int kStage>
inline constexpr bool kOneRegister = ZHF_LANES_ONE_REGISTER && std::is_same_v<T, float> && 2 * N - 1 <= 8 &&
                                     kStage == int(LobeStage::kFloat);

#if ZHF_LANES_ONE_REGISTER
// Bands 2..N-1 of the output, out[4 .. N^2), as consecutive registers of 8 lanes; band l's
// outputs start at index l^2 - 4 of that run.
template <int N>
struct OneRegisterTables {
  static constexpr int kOutputs = N * N - 4;
  static constexpr int kRegisters = (kOutputs + 7) / 8;
  // column[l][d][k]: column d of A_l placed at band l's lanes of output register k, zero elsewhere.
  alignas(32) float column[N][8][kRegisters][8];
};

template <int N>
constexpr OneRegisterTables<N> one_register_tables() {
  OneRegisterTables<N> t{};
  for (int l = 2; l < N; ++l)
    for (int d = 0; d <= 2 * l; ++d)
      for (int m = 0; m <= 2 * l; ++m) {
        const int at = l * l + m - 4;
        t.column[l][d][at / 8][at % 8] = float(gen::LanesTables<N>::kInverse[l - 2][m][d]);
      }
  return t;
}

inline __m256 m256(const Pack<float>& p) { return (__m256)p.v; }

// Lane D of a register in every lane, from its low and high halves each held twice: one in-lane
// shuffle.
template <int D>
inline __m256 lane_broadcast(__m256 low_twice, __m256 high_twice) {
  return _mm256_permute_ps(D < 4 ? low_twice : high_twice, (D % 4) * 0x55);
}

// Band L's samples s_d = sum_m f_{L,m} y_L^m(R^T w_d), two partial sums.
template <int L, int... M>
inline __m256 band_samples(const float* f, const Pack<float>* y, std::integer_sequence<int, M...>) {
  auto term = [&](int m) { return _mm256_broadcast_ss(f + L * L + m); };
  __m256 sum[2] = {_mm256_mul_ps(term(0), m256(y[L * L])), _mm256_mul_ps(term(1), m256(y[L * L + 1]))};
  ((sum[M % 2] = _mm256_fmadd_ps(term(M + 2), m256(y[L * L + M + 2]), sum[M % 2])), ...);
  return _mm256_add_ps(sum[0], sum[1]);
}

// The output registers band l reaches, and the band whose lobes 0 and 1 start register k's sums.
constexpr int first_register_of_band(int l) { return (l * l - 4) / 8; }
constexpr int last_register_of_band(int l) { return ((l + 1) * (l + 1) - 5) / 8; }
constexpr int first_band_of_register(int k) {
  int l = 2;
  while (last_register_of_band(l) < k) ++l;
  return l;
}

// Adds A_L s to the output registers band L reaches, two partial sums each (even lobes to the first).
template <int N, int L, int... D, int... K>
inline void add_band(const OneRegisterTables<N>& t, __m256 s, __m256 (*acc)[2], std::integer_sequence<int, D...>,
                     std::integer_sequence<int, K...>) {
  const __m256 low_twice = _mm256_permute2f128_ps(s, s, 0x00), high_twice = _mm256_permute2f128_ps(s, s, 0x11);
  auto add_lobe = [&](auto d) {
    constexpr int kD = decltype(d)::value;
    const __m256 b = lane_broadcast<kD>(low_twice, high_twice);
    auto add_to = [&](auto k) {
      constexpr int kK = decltype(k)::value;
      if constexpr (kK >= first_register_of_band(L) && kK <= last_register_of_band(L)) {
        const __m256 column = _mm256_load_ps(t.column[L][kD][kK]);
        if constexpr (L == first_band_of_register(kK) && kD < 2)
          acc[kK][kD] = _mm256_mul_ps(b, column);
        else
          acc[kK][kD % 2] = _mm256_fmadd_ps(b, column, acc[kK][kD % 2]);
      }
    };
    (add_to(std::integral_constant<int, K>{}), ...);
  };
  (add_lobe(std::integral_constant<int, D>{}), ...);
}

template <int N, int... L>
inline void add_bands(const OneRegisterTables<N>& t, const float* f, const Pack<float>* y, __m256 (*acc)[2],
                      std::integer_sequence<int, L...>) {
  (add_band<N, L + 2>(t, band_samples<L + 2>(f, y, std::make_integer_sequence<int, 2 * L + 3>()), acc,
                      std::make_integer_sequence<int, 2 * L + 5>(),
                      std::make_integer_sequence<int, OneRegisterTables<N>::kRegisters>()),
   ...);
}

// out[4 .. N^2) from the output registers' two sums, nothing past N^2.
template <int N, int... K>
inline void store_outputs(const __m256 (*acc)[2], float* out, std::integer_sequence<int, K...>) {
  constexpr int kOutputs = OneRegisterTables<N>::kOutputs;
  (avx2::store_first<(kOutputs - 8 * K < 8 ? kOutputs - 8 * K : 8)>(out + 4 + 8 * K, _mm256_add_ps(acc[K][0], acc[K][1])), ...);
}

// channels vectors of N^2 floats, one after another (1, or 3 for RGB: the lobes and their SH once).
template <int N>
inline void rotate_one_register(const float R[9], const float* coeffs, float* rotated, int channels) {
  using T = OneRegisterTables<N>;
  static_assert(padded_lobes(N) == 8);
  static constexpr T kTables = one_register_tables<N>();
  static constexpr LobeColumns<N, float> kLobes = lobe_columns<N, float>();
  Pack<float> dir[3];  // R^T w_d
  for (int j = 0; j < 3; ++j)
    dir[j].v = (Pack<float>::Vector)_mm256_fmadd_ps(
        _mm256_broadcast_ss(R + 6 + j), _mm256_load_ps(kLobes.z),
        _mm256_fmadd_ps(_mm256_broadcast_ss(R + 3 + j), _mm256_load_ps(kLobes.y),
                        _mm256_mul_ps(_mm256_broadcast_ss(R + j), _mm256_load_ps(kLobes.x))));
  Pack<float> y[N * N];
  gen::Kernels<N>::template sh_eval<Pack<float>>(dir, y);
  for (int c = 0; c < channels; ++c) {
    const float* f = coeffs + c * N * N;
    float* out = rotated + c * N * N;
    __m256 acc[T::kRegisters][2];
    add_bands<N>(kTables, f, y, acc, std::make_integer_sequence<int, N - 2>());
    store_outputs<N>(acc, out, std::make_integer_sequence<int, T::kRegisters>());
    avx2::rotate_bands01(R, f, out);
  }
}
#endif

}  // namespace lanes_detail

// rotated = coefficients of f(R^T w), R row-major mapping v to R v; orders 3..8 (include
// zhf_orderN.h and zhf_lanes_orderN.h). Flattened so the SH evaluation is inlined into the lobe
// loop at every order (the loop body must be straight-line code to vectorize).
// kStage is a LobeStage; the default is the table's (zhf_lanes_orderN.h, from the error model
// against the 1e-6 target). A s runs in T.
template <int N, class T, int kStage = gen::LanesTables<N>::kLobeStage>
[[gnu::flatten]] inline void rotate_lanes(const T R[9], const T coeffs[N * N], T rotated[N * N]) {
  using namespace lanes_detail;
#if ZHF_LANES_ONE_REGISTER
  if constexpr (kOneRegister<N, T, kStage>) return rotate_one_register<N>(R, coeffs, rotated, 1);
#endif
  constexpr bool kRotationInDouble = kStage >= int(LobeStage::kDoubleRotation);
  constexpr bool kAllInDouble = kStage == int(LobeStage::kDouble);
  using W = std::conditional_t<kAllInDouble, std::common_type_t<T, double>, T>;
  using Rotated = std::conditional_t<kRotationInDouble, std::common_type_t<T, double>, T>;
  constexpr int kLanes = padded_lobes(N);
  static constexpr LobeColumns<N, Rotated> kColumns = lobe_columns<N, Rotated>();
  static constexpr DenseColumns<N, T> kInverse = dense_columns<N, T>();
  Rotated q[9];
  if constexpr (kAllInDouble) {
    polar_step(R, q);
  } else {
    for (int i = 0; i < 9; ++i) q[i] = R[i];
  }
  W f[N * N];
  for (int i = 0; i < N * N; ++i) f[i] = W(coeffs[i]);
  // The lobes rotated in a loop of their own: fused with the evaluation, a double rotation
  // feeding float lanes vectorises worse.
  alignas(64) W rx[kLanes], ry[kLanes], rz[kLanes];
  for (int d = 0; d < kLanes; ++d) {
    rx[d] = W(q[0] * kColumns.x[d] + q[3] * kColumns.y[d] + q[6] * kColumns.z[d]);
    ry[d] = W(q[1] * kColumns.x[d] + q[4] * kColumns.y[d] + q[7] * kColumns.z[d]);
    rz[d] = W(q[2] * kColumns.x[d] + q[5] * kColumns.y[d] + q[8] * kColumns.z[d]);
  }
  alignas(64) W samples[N - 2][kLanes];  // band l + 2's function at R^T w_d
  for (int d = 0; d < kLanes; ++d) {
    const W dir[3] = {rx[d], ry[d], rz[d]};
    W y[N * N];
    gen::Kernels<N>::template sh_eval<W>(dir, y);
    band_samples<N>(f, y, samples, d, std::make_integer_sequence<int, N - 2>());
  }
  multiply_bands<N>(kInverse, samples, rotated, std::make_integer_sequence<int, N - 2>());
  rotated[0] = coeffs[0];
  rotate_band1(R, coeffs + 1, rotated + 1);
}

// The lanes kernel of order N for a Rotator; stage as in rotate_lanes. Its RGB entry point is
// the scalar kernel's, which shares the per-rotation work across channels, except where the kernel
// is held in one register of lobes (the lobes and their SH once for three channels).
template <int N, class T, int kStage = gen::LanesTables<N>::kLobeStage>
KernelSet<T> lanes_kernels() {
  KernelSet<T> k = scalar_kernels<N, T>();
  k.path = "lanes";
  k.rotate = &rotate_lanes<N, T, kStage>;
  k.rotate_batch = &rotate_each<T, N, &rotate_lanes<N, T, kStage>>;
#if ZHF_LANES_ONE_REGISTER
  if constexpr (lanes_detail::kOneRegister<N, T, kStage>)
    k.rotate_rgb = [](const float* r, const float* in, float* out) { lanes_detail::rotate_one_register<N>(r, in, out, 3); };
#endif
  return k;
}

#undef ZHF_LANES_ONE_REGISTER

}  // namespace zhf::runtime
