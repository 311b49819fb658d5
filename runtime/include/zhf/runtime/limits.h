// The runtime's limits, which every library shares: SH orders, lobe table orders and sizes, the
// generated and zxzxz orders, product orders and threads. Each library's own limits (file sizes,
// counts, its options' ranges) are in its limits.h beside its readers; scripts/check_one_place.py
// refuses a limit defined anywhere else. Readers and commands check these before any work starts,
// so a hostile or mistaken input is refused at once, never half-done. Order N = N bands = N^2
// coefficients.
#pragma once

#include <cstddef>

namespace zhf::runtime {

// SH evaluation: the normalised recurrences stay finite in float below order 64 (|Q| < 5e12).
// Also the bound for coefficient files and the reference rotations.
inline constexpr int kMaxShOrder = 64;

// Lobe tables: order 2 is the empty table (band 1 rotates as a vector); 32 is the largest the
// search and the run-time path were measured at (condition 205, float error 8e-7). A table file
// is read up to 16 MiB (the largest checked-in table, order 32, is 0.9 MiB).
inline constexpr int kMinTableOrder = 2;
inline constexpr int kMaxTableOrder = 32;
inline constexpr std::size_t kMaxTableBytes = std::size_t(16) << 20;
// The table-free zxzxz path (zxzxz_rotation.h, Rotator::zxzxz): its fixed quarter turns take
// ~5.6 MB in float at 128, and its per-call buffers live on the stack.
inline constexpr int kMaxZxzxzOrder = 128;
// Up to this order its double results keep tolerance::kDouble; above, the quarter turns' rounding
// (the recurrence in long double) sets tolerance::kHighOrderZxzxzDouble.
inline constexpr int kMaxDoubleAccurateZxzxzOrder = 64;

// The generated kernels compiled into the runtime (generated/cpp): orders 2..8.
inline constexpr int kMinGeneratedOrder = 2;
inline constexpr int kMaxGeneratedOrder = 8;

// SH products: Gaunt tables and the products built on them go to order 16 (l <= 15, 3j arguments
// up to 45); triple-product couplings are dense N^2 x N^2 x N^2 tensors once a slot is in ZHF
// form, so they stop at order 8 (2 MiB).
inline constexpr int kMaxGauntOrder = 16;
inline constexpr int kMaxTripleCouplingOrder = 8;

// JSON documents (runtime/json.h reads lobe tables with them, io/json.h every other file): arrays
// and objects inside each other, values (nested ones included), the bytes of a string or key after
// unescaping, the characters of a number's token, and the members of one object: each object's
// keys are sorted once when it closes to find a duplicate, so a document of n values parses in
// O(n log k) time.
inline constexpr int kMaxJsonDepth = 64;
inline constexpr std::size_t kMaxJsonValues = std::size_t(1) << 24;
inline constexpr std::size_t kMaxJsonStringBytes = std::size_t(1) << 16;
inline constexpr std::size_t kMaxJsonNumberChars = 64;
inline constexpr std::size_t kMaxJsonObjectKeys = 4096;

// Threads a caller may ask for (--threads, threads=): the bound on every thread pool zhf starts.
inline constexpr int kMaxThreads = 256;

}  // namespace zhf::runtime
