// What splat/ reads besides .ply (io/limits.h): compressed scenes, .glb, and the scale a transform
// may apply. Readers and commands check these before any work starts, so a hostile or mistaken
// input is refused at once, never half-done (the runtime's own limits, which every library shares,
// are in runtime/limits.h; scripts/check_one_place.py refuses a limit defined anywhere but a
// library's limits.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "zhf/runtime/limits.h"

namespace zhf::splat {

// A compressed scene (.spz) whose header claims more than this many bytes per byte of the file
// is refused before anything is decompressed: deflate cannot expand beyond about 1032:1, and a
// real scene's attributes compress far less (zstd could go further only on degenerate data).
inline constexpr double kMaxCompressionRatio = 1100;
// A .glb scene's JSON chunk (a splat file's is a few kilobytes; whole glTF scenes are larger);
// its chunks, and its meshes, primitives, nodes, accessors, views and buffers (each).
inline constexpr std::size_t kMaxGlbJsonBytes = std::size_t(16) << 20;
// Its nesting depth and values (a splat scene's glTF is a few levels and hundreds of values).
inline constexpr int kMaxGlbJsonDepth = 32;
inline constexpr std::size_t kMaxGlbJsonValues = std::size_t(1) << 20;
inline constexpr int kMaxGlbChunks = 16;
inline constexpr int kMaxGlbObjects = 1 << 16;
// A scene's SH degree: 0..4, as .ply (72 f_rest) and .spz version 4 carry it; each channel's
// coefficients above band 0.
inline constexpr int kMaxSplatShDegree = 4;
inline constexpr int kMaxRestPerChannel = (kMaxSplatShDegree + 1) * (kMaxSplatShDegree + 1) - 1;
// A .spz position is 24-bit signed fixed point: at most 23 bits after the point.
inline constexpr int kMaxSpzFractionalBits = 23;
// A ZIP archive without ZIP64 (a .sog as written): offsets and sizes below 2^32 - 1, the value
// that marks a ZIP64 record.
inline constexpr std::uint64_t kZip32Marker = 0xffffffffu;
// A .spz file's extension records (the reference library's are a few bytes each).
inline constexpr std::size_t kMaxSpzExtensionBytes = std::size_t(1) << 20;
inline constexpr int kMaxSpzExtensionRecords = 64;
// zhf splat --max-sh-error: the colour error's view directions (docs/formats.md).
inline constexpr int kColourErrorDirections = 256;
// A ZIP archive's entries (a bundled SOG has 8 or fewer); a SOG's meta.json, one WebP image, its
// splats (WebP's 16383 x 16383 texels) and SH palette entries (16-bit labels).
inline constexpr int kMaxZipEntries = 64;
inline constexpr std::uint64_t kMaxSogMetaBytes = std::uint64_t(1) << 20;
inline constexpr std::uint64_t kMaxSogImageBytes = std::uint64_t(1) << 30;
inline constexpr std::uint64_t kMaxSogSplats = std::uint64_t(16380) * 16380;
inline constexpr int kMaxSogPalette = 1 << 16;
// A SOG's images decoded (4 bytes a texel; five or six images of the splats and the palette's):
// the cap is checked from meta.json before any image is decoded. WebP's lossless coding has no
// expansion bound (a uniform image of 448 x 448 texels takes 60 bytes), so no ratio to the file's
// size can stand in for it. 4 GiB hold about 180 million splats of SH degree 3 (24 bytes a splat).
inline constexpr std::uint64_t kMaxSogDecodedBytes = std::uint64_t(4) << 30;
// sign(p) ln(|p| + 1) of a position: beyond 88 its inverse leaves float's range.
inline constexpr double kMaxSogLogPosition = 88;
// zhf splat with several --in: scenes merged into one output (their splats together: io's
// kMaxPlyVertices, what a .ply written from them can hold).
inline constexpr int kMaxMergedScenes = 64;
// zhf splat --scale: a factor in [kMinSplatScale, kMaxSplatScale].
inline constexpr double kMinSplatScale = 1e-30, kMaxSplatScale = 1e30;

// A .glb's extensionsRequired; a buffer view's byteStride (the glTF specification's range).
inline constexpr int kMaxGltfRequiredExtensions = 64;
inline constexpr long long kMinGltfByteStride = 4, kMaxGltfByteStride = 252;

}  // namespace zhf::splat
