// Which instruction-set path zhf's compiled rotation library runs (rotator.h beside this).
//
// The library holds the runtime (runtime/) and the generated kernels compiled once per path:
// on x86-64 "sse2" (baseline x86-64), "avx2" (x86-64-v3: AVX2, FMA, BMI) and "avx512"
// (x86-64-v4); on aarch64 "neon" (its baseline); in WebAssembly "simd128" (the module built
// with it) or "generic" (the scalar module); elsewhere "generic". On first use it picks the
// fastest path the CPU runs, or the one named by the environment variable ZHF_ISA. The paths
// compute the same rotations; their results may differ in the last bits (fused multiply-adds),
// each within the runtime's tolerances. Header-only users choose at compile time instead
// (docs/usage.md).
#pragma once

#include <string>
#include <vector>

namespace zhf::dispatch {

enum class Isa { kGeneric, kSse2, kAvx2, kAvx512, kNeon, kSimd128 };

// "generic", "sse2", "avx2", "avx512", "neon", "simd128".
const char* isa_name(Isa isa);

// The paths built into this library that this CPU runs, fastest first.
std::vector<Isa> supported_isas();

// The path in use: the one forced by use_isa, else ZHF_ISA's, else the fastest supported. Throws
// std::invalid_argument, one line naming ZHF_ISA, when ZHF_ISA names an unknown path or one this
// CPU lacks.
Isa active_isa();

// Forces a path by name for every rotator made afterwards (those made before keep theirs).
// Throws std::invalid_argument, one line, for an unknown name or a path this CPU lacks.
void use_isa(const std::string& name);

}  // namespace zhf::dispatch
