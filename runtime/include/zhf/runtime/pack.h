// Pack<T>: a fixed group of T values (8 floats or 4 doubles: one 256-bit AVX2 register) with the
// arithmetic of a scalar, so scalar code templated on its number type (the generated kernels, the
// Legendre recurrence) runs across lanes unchanged: the lobe path evaluates 4 lobes per step
// (double), rotate_soa runs 8 rotations per step, DenseRotation applies packs of rows or items.
//
// With GCC or Clang it is a vector-extension type: one AVX2 instruction per operation where the
// build targets AVX2, two SSE2 instructions on baseline x86-64, the target's own vectors elsewhere.
// Other compilers get a plain array loop of the same meaning. Each lane runs the scalar code's
// operations in the same order (contraction into fused multiply-adds may differ), so a lane's
// accuracy is the scalar path's.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#if defined(__GNUC__) && defined(__SSE2__)
#include <immintrin.h>  // non-temporal stores
#endif

namespace zhf::runtime {

// The cache geometry the bulk layouts are arranged for (x86-64 cores' L1 data caches): a line, and
// the span after which addresses meet the same L1 set again (64 sets of a line each).
inline constexpr int kCacheLineBytes = 64;
inline constexpr int kCacheSetSpanBytes = 4096;

// The packs the bulk layouts work in (dense_rotation.h): one SIMD128 register in WebAssembly, where
// a 32-byte pack is a pair that the engine's 16 registers hold half as many of (order-4 splats:
// 34 ns a splat in one register, 47 in pairs, under Node 20); an AVX2 register elsewhere.
#if defined(__wasm_simd128__)
inline constexpr int kBulkPackBytes = 16;
#else
inline constexpr int kBulkPackBytes = 32;
#endif

template <class T, int kBytes = 32>
struct Pack {
  static constexpr int kLanes = kBytes / int(sizeof(T));
#if defined(__GNUC__)
  typedef T Vector __attribute__((vector_size(kBytes)));
  Vector v;
  Pack() = default;  // uninitialised, as a scalar; Pack(0.0) for zeros
  // c - 0 is c exactly (signed zeros too), so this folds to a plain broadcast.
  Pack(double c) : v(T(c) - Vector{}) {}  // NOLINT: broadcast, as a scalar literal would be
  explicit Pack(const Vector& x) : v(x) {}
  static Pack broadcast(T value) { return Pack(value - Vector{}); }
  T lane(int i) const { return v[i]; }
  friend Pack operator+(const Pack& a, const Pack& b) { return Pack(a.v + b.v); }
  friend Pack operator-(const Pack& a, const Pack& b) { return Pack(a.v - b.v); }
  friend Pack operator*(const Pack& a, const Pack& b) { return Pack(a.v * b.v); }
  friend Pack operator-(const Pack& a) { return Pack(-a.v); }
  // x > 0 ? if_positive : otherwise, lane by lane (the emitted kernels' select_positive).
  friend Pack select_positive(const Pack& x, const Pack& if_positive, const Pack& otherwise) {
    using Int = std::conditional_t<sizeof(T) == 4, std::int32_t, std::int64_t>;
    typedef Int Mask __attribute__((vector_size(kBytes)));
    const Mask positive = x.v > Vector{};  // all bits set where true
    return Pack(Vector((positive & Mask(if_positive.v)) | (~positive & Mask(otherwise.v))));
  }
#else
  T v[kLanes];
  Pack() = default;  // uninitialised, as a scalar; Pack(0.0) for zeros
  Pack(double c) {  // NOLINT: broadcast
    for (T& x : v) x = T(c);
  }
  T lane(int i) const { return v[i]; }
  static Pack broadcast(T value) { return Pack(double(value)); }
  template <class Op>
  static Pack zip(Pack a, Pack b, Op op) {
    Pack r;
    for (int i = 0; i < kLanes; ++i) r.v[i] = op(a.v[i], b.v[i]);
    return r;
  }
  friend Pack operator+(Pack a, Pack b) { return zip(a, b, [](T x, T y) { return x + y; }); }
  friend Pack operator-(Pack a, Pack b) { return zip(a, b, [](T x, T y) { return x - y; }); }
  friend Pack operator*(Pack a, Pack b) { return zip(a, b, [](T x, T y) { return x * y; }); }
  friend Pack operator-(Pack a) { return zip(a, a, [](T x, T) { return -x; }); }
  friend Pack select_positive(const Pack& x, const Pack& if_positive, const Pack& otherwise) {
    Pack r;
    for (int i = 0; i < kLanes; ++i) r.v[i] = x.v[i] > T(0) ? if_positive.v[i] : otherwise.v[i];
    return r;
  }
#endif
  // 1 / sqrt(x), lane by lane (the emitted kernels' reciprocal_sqrt). On x86 through the vector
  // square-root instruction, correctly rounded as std::sqrt is, so each lane equals the scalar
  // kernel's; the lane loop is not vectorised because std::sqrt may set errno.
  friend Pack reciprocal_sqrt(const Pack& x) {
    Pack r;
#if defined(__GNUC__) && defined(__AVX__)
    if constexpr (kBytes == 32 && std::is_same_v<T, float>) {
      r.v = T(1) / __builtin_ia32_sqrtps256(x.v);
      return r;
    } else if constexpr (kBytes == 32 && std::is_same_v<T, double>) {
      r.v = T(1) / __builtin_ia32_sqrtpd256(x.v);
      return r;
    }
#elif defined(__GNUC__) && defined(__SSE2__)
    if constexpr (kBytes % 16 == 0 && (std::is_same_v<T, float> || std::is_same_v<T, double>)) {
      typedef T Half __attribute__((vector_size(16)));
      for (int part = 0; part < kBytes / 16; ++part) {
        Half h;
        std::memcpy(&h, reinterpret_cast<const char*>(&x.v) + 16 * part, 16);
        if constexpr (std::is_same_v<T, float>) h = T(1) / __builtin_ia32_sqrtps(h);
        else h = T(1) / __builtin_ia32_sqrtpd(h);
        std::memcpy(reinterpret_cast<char*>(&r.v) + 16 * part, &h, 16);
      }
      return r;
    }
#endif
    for (int i = 0; i < kLanes; ++i) r.v[i] = T(1) / std::sqrt(x.v[i]);
    return r;
  }
  // Groups of four lanes, for layouts that keep four related values side by side (zxzxz's quads).
  // With AVX each is one instruction; without it a 32-byte pack is two SSE registers, and the
  // full-width shuffles would go lane by lane through memory, so each half is handled alone.
  // Every group holds p[0..3].
  static Pack broadcast4(const T* p) {
    static_assert(kLanes % 4 == 0, "whole groups of four");
    if constexpr (kLanes == 4) return load(p);
    Pack r;
#if defined(__GNUC__) && defined(__AVX__) && (defined(__clang__) || __GNUC__ >= 12)
    if constexpr (kLanes == 8) {
      typedef T Quad __attribute__((vector_size(4 * sizeof(T))));
      Quad q;
      std::memcpy(&q, p, sizeof q);
      r.v = __builtin_shufflevector(q, q, 0, 1, 2, 3, 0, 1, 2, 3);
      return r;
    }
#endif
    for (int g = 0; g < kLanes / 4; ++g) std::memcpy(reinterpret_cast<char*>(&r.v) + g * 4 * sizeof(T), p, 4 * sizeof(T));
    return r;
  }
  // Lane i takes lane i ^ kFlip within its group of four: 1 swaps neighbours, 2 swaps the halves.
  template <int kFlip>
  Pack flip4() const {
    static_assert(kLanes % 4 == 0 && kFlip > 0 && kFlip < 4, "a permutation within groups of four");
    Pack r;
#if defined(__GNUC__) && (defined(__clang__) || __GNUC__ >= 12)
#if defined(__AVX__)
    if constexpr (kLanes == 8) {
      r.v = __builtin_shufflevector(v, v, 0 ^ kFlip, 1 ^ kFlip, 2 ^ kFlip, 3 ^ kFlip, 4 ^ kFlip, 5 ^ kFlip, 6 ^ kFlip, 7 ^ kFlip);
      return r;
    } else if constexpr (kLanes == 4) {
      r.v = __builtin_shufflevector(v, v, 0 ^ kFlip, 1 ^ kFlip, 2 ^ kFlip, 3 ^ kFlip);
      return r;
    }
#else
    if constexpr (kBytes == 32 && (kLanes == 8 || kLanes == 4)) {
      // Half k of the result is half k ^ (kFlip >= kLanes / 2) of this, permuted by kFlip % (kLanes / 2).
      typedef T Half __attribute__((vector_size(16)));
      Half h[2], out[2];
      std::memcpy(h, &v, sizeof h);
      constexpr int kAcross = kFlip >= kLanes / 2, kWithin = kFlip % (kLanes / 2);
      for (int k = 0; k < 2; ++k) {
        if constexpr (kLanes == 8)
          out[k] = __builtin_shufflevector(h[k ^ kAcross], h[k ^ kAcross], 0 ^ kWithin, 1 ^ kWithin, 2 ^ kWithin, 3 ^ kWithin);
        else
          out[k] = __builtin_shufflevector(h[k ^ kAcross], h[k ^ kAcross], 0 ^ kWithin, 1 ^ kWithin);
      }
      std::memcpy(&r.v, out, sizeof out);
      return r;
    }
#endif
#endif
    for (int i = 0; i < kLanes; ++i) r.v[i] = v[i ^ kFlip];
    return r;
  }
  // Lanes 4g .. 4g + 3 from quads[g], each rounded as T(x): groups of four made in double.
  static Pack from_quads(const Pack<double>* quads) {
    static_assert(Pack<double>::kLanes == 4 && kLanes % 4 == 0, "whole groups of four");
    Pack r;
#if defined(__GNUC__)
    typedef T Quad __attribute__((vector_size(4 * sizeof(T))));
    if constexpr (kLanes == 4) {
      r.v = __builtin_convertvector(quads[0].v, Quad);
      return r;
    }
#if defined(__AVX__) && (defined(__clang__) || __GNUC__ >= 12)
    if constexpr (kLanes == 8) {
      r.v = __builtin_shufflevector(__builtin_convertvector(quads[0].v, Quad), __builtin_convertvector(quads[1].v, Quad), 0,
                                    1, 2, 3, 4, 5, 6, 7);
      return r;
    }
#endif
#endif
    for (int i = 0; i < kLanes; ++i) r.v[i] = T(quads[i / 4].lane(i % 4));
    return r;
  }
  Pack& operator+=(const Pack& b) { return *this = *this + b; }
  Pack& operator-=(const Pack& b) { return *this = *this - b; }
  Pack& operator*=(const Pack& b) { return *this = *this * b; }

  // kLanes consecutive values (any alignment).
  static Pack load(const T* p) {
    Pack r;
    std::memcpy(&r.v, p, sizeof r.v);
    return r;
  }
  void store(T* p) const { std::memcpy(p, &v, sizeof v); }
  // store() past the caches (non-temporal stores on x86; a plain store elsewhere), for outputs
  // too large to stay cached: the lines are written without first being read. p aligned to
  // min(kBytes, 32); a run of them ends with stream_fence().
  void stream(T* p) const {
#if defined(__GNUC__) && defined(__SSE2__)
#if defined(__AVX__)
    if constexpr (kBytes % 32 == 0 && std::is_same_v<T, float>)
      return stream_parts<__m256>(p, [](float* q, __m256 x) { _mm256_stream_ps(q, x); });
    if constexpr (kBytes % 32 == 0 && std::is_same_v<T, double>)
      return stream_parts<__m256d>(p, [](double* q, __m256d x) { _mm256_stream_pd(q, x); });
#endif
    if constexpr (kBytes % 16 == 0 && std::is_same_v<T, float>)
      return stream_parts<__m128>(p, [](float* q, __m128 x) { _mm_stream_ps(q, x); });
    if constexpr (kBytes % 16 == 0 && std::is_same_v<T, double>)
      return stream_parts<__m128d>(p, [](double* q, __m128d x) { _mm_stream_pd(q, x); });
#endif
    store(p);
  }
  // The pack as native registers (copied whole, so the compiler keeps it in registers), each
  // passed to store_part with its place in p.
  template <class Native, class StorePart>
  void stream_parts(T* p, StorePart store_part) const {
    constexpr int kParts = int(sizeof v / sizeof(Native));
    Native parts[kParts];
    std::memcpy(parts, &v, sizeof parts);
    for (int k = 0; k < kParts; ++k) store_part(p + k * int(sizeof(Native) / sizeof(T)), parts[k]);
  }
  // out[i] = the sum of packs[i]'s lanes (pairwise), for i < count: one pass the compiler can
  // vectorise across i, where a sum per pack would be a chain of shuffles.
  static void sums(const Pack* packs, int count, T* out) {
    static_assert(sizeof(Pack) == kLanes * sizeof(T), "a pack is its lanes");
    const T* lanes = reinterpret_cast<const T*>(packs);
    for (int i = 0; i < count; ++i) {
      T s[kLanes];
      for (int k = 0; k < kLanes; ++k) s[k] = lanes[i * kLanes + k];
      for (int width = kLanes / 2; width > 0; width /= 2)
        for (int k = 0; k < width; ++k) s[k] += s[k + width];
      out[i] = s[0];
    }
  }
};

// Orders the stream() stores before what follows (they are weakly ordered on x86).
inline void stream_fence() {
#if defined(__GNUC__) && defined(__SSE2__)
  _mm_sfence();
#endif
}

}  // namespace zhf::runtime
