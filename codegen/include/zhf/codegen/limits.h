// What codegen/ emits and reads: kernel orders, shader bindings, scenes, path tables and manifests.
// Readers and commands check these before any work starts, so a hostile or mistaken input is
// refused at once, never half-done (the runtime's own limits, which every library shares, are in
// runtime/limits.h; scripts/check_one_place.py refuses a limit defined anywhere but a library's
// limits.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "zhf/runtime/limits.h"

namespace zhf::codegen {

// Emitted kernels: emit, generate, scenes and verify go up to order 12, where a kernel file
// reaches megabytes (generated/ holds runtime::kMinGeneratedOrder..kMaxGeneratedOrder).
inline constexpr int kMaxEmitOrder = 12;
// zhf emit --method auto tries every assignment of methods to bands up to this many bands >= 2
// (2^6 graphs at order 8), above it lobes below one band and zxzxz from it on.
inline constexpr int kMaxExhaustiveMethodBands = 6;
// The descriptor set (WebGPU: bind group) and binding a shader evaluator's data is read from:
// Vulkan guarantees only 4 sets, WebGPU 4 groups of up to 1000 bindings.
inline constexpr int kMaxStorageSet = 3, kMaxStorageBinding = 999;
// Scene specs and their signals.
inline constexpr std::size_t kMaxSceneBytes = std::size_t(1) << 20;
inline constexpr int kMaxSceneSignals = 256;
// Path tables, and their measured_on note (it goes into a comment of zhf_kernels.h).
inline constexpr std::size_t kMaxPathTableBytes = std::size_t(64) << 10;
inline constexpr std::size_t kMaxPathTableNoteChars = 300;
// Manifests: their size, files per manifest and functions per file (generous, checked before use).
inline constexpr std::size_t kMaxManifestBytes = std::size_t(4) << 20;
inline constexpr std::size_t kMaxManifestFiles = 4096;
inline constexpr std::size_t kMaxManifestFunctions = 256;

// An emitted file already at the target, read to compare before it is replaced (the largest
// generated header is a few megabytes); a function's operation counts in a manifest.
inline constexpr std::size_t kMaxEmittedFileBytes = std::size_t(1) << 30;
inline constexpr long long kMaxFunctionOps = 1LL << 30;

}  // namespace zhf::codegen
