// How much zhf verify runs. Readers and commands check these before any work starts, so a hostile
// or mistaken input is refused at once, never half-done (the runtime's own limits, which every
// library shares, are in runtime/limits.h; scripts/check_one_place.py refuses a limit defined
// anywhere but a library's limits.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "zhf/runtime/limits.h"

namespace zhf::verify {

// Random rotations verify draws besides its fixed extreme set.
inline constexpr int kMaxVerifyRotations = 1000000;
// Seconds verify gives Node to turn one WGSL wrapper into SPIR-V (naga takes ~0.1 s for order 8)
// before it is stopped and the order reported as failed.
inline constexpr double kShaderCompileSeconds = 300;

// Seconds verify gives headless Chromium to start, compile one WGSL wrapper with Tint and run it on
// SwiftShader (order 8: about 20 s) before it is stopped and the order reported as failed.
inline constexpr double kBrowserRunSeconds = 600;

// A shader's SPIR-V read back from its compiler (an order-8 kernel's is about a megabyte).
inline constexpr std::size_t kMaxSpirvBytes = std::size_t(1) << 30;

}  // namespace zhf::verify
