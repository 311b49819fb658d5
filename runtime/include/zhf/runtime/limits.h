// Every order range, count and input size zhf accepts, in one place (scripts/check_one_place.sh
// fails the tests when a limit is defined anywhere else). Readers and commands check these
// before any work starts, so a hostile or mistaken input is refused at once, never half-done.
// Order N = N bands = N^2 coefficients.
#pragma once

#include <cstddef>
#include <cstdint>

namespace zhf::runtime {

// SH evaluation: the normalised recurrences stay finite in float below order 64 (|Q| < 5e12).
// Also the bound for coefficient files and the reference rotations.
inline constexpr int kMaxShOrder = 64;
inline constexpr std::size_t kMaxCoefficientCount = std::size_t(kMaxShOrder) * kMaxShOrder;
// Coefficients read from files: up to this magnitude, so squares and their sums (band energies)
// stay finite.
inline constexpr double kMaxCoefficientMagnitude = 1e150;

// Lobe tables: order 2 is the empty table (band 1 rotates as a vector); 32 is the largest the
// search and the run-time path were measured at (condition 205, float error 8e-7).
inline constexpr int kMinTableOrder = 2;
inline constexpr int kMaxTableOrder = 32;
// The table-free zxzxz path (zxzxz_rotation.h, Rotator::zxzxz): its fixed quarter turns take
// ~5.6 MB in float at 128, and its per-call buffers live on the stack.
inline constexpr int kMaxZxzxzOrder = 128;
// Up to this order its double results keep tolerance::kDouble; above, the quarter turns' rounding
// (the recurrence in long double) sets tolerance::kHighOrderZxzxzDouble.
inline constexpr int kMaxDoubleAccurateZxzxzOrder = 64;
// Candidate directions and the sparsity search need a lobe band: order 3 up. Order 32 has 6.4
// million candidates; above it their tables no longer fit in memory.
inline constexpr int kMinSearchOrder = 3;
inline constexpr int kMaxSearchOrder = kMaxTableOrder;

// Emitted kernels: generated/ holds orders 2..8 (compiled into the runtime); emit, generate,
// scenes and verify go up to 12, where a kernel file reaches megabytes.
inline constexpr int kMinGeneratedOrder = 2;
inline constexpr int kMaxGeneratedOrder = 8;
inline constexpr int kMaxEmitOrder = 12;
// zhf emit --method auto tries every assignment of methods to bands up to this many bands >= 2
// (2^6 graphs at order 8), above it lobes below one band and zxzxz from it on.
inline constexpr int kMaxExhaustiveMethodBands = 6;
// The lobe-parallel kernel (lanes.h) and its tables.
inline constexpr int kMinLanesOrder = 3;
inline constexpr int kMaxLanesOrder = 8;
// Channels per coefficient vector (grey, RGB, RGBA) in files, scenes, products and emitted kernels.
inline constexpr int kMaxChannels = 4;
// zhf bench's orders: the lobe-path rows stop at 16, where a run still takes minutes.
inline constexpr int kMaxBenchOrder = 16;

// SH products: Gaunt tables and the products built on them go to order 16 (l <= 15, 3j arguments
// up to 45); triple-product couplings are dense N^2 x N^2 x N^2 tensors once a slot is in ZHF
// form, so they stop at order 8 (2 MiB).
inline constexpr int kMaxGauntOrder = 16;
inline constexpr int kMaxTripleCouplingOrder = 8;

// Frames (frames/): design strengths searched (efficient designs of 1302 points at t = 50);
// points in a point-set file; Gauss product cubatures (64 Gauss-Legendre nodes, the most sh/'s
// root finder gives); projection orders; frame reports' and the tight-frame rotation's bands.
inline constexpr int kMaxDesignStrength = 100;
inline constexpr int kMaxDesignPoints = 100000;
inline constexpr int kMaxDesignStarts = 100000;
inline constexpr int kMaxCubatureDegree = 126;
inline constexpr int kMaxProjectionOrder = 64;
inline constexpr int kMaxFrameBand = 63;
inline constexpr int kMaxTightFrameOrder = 32;
// Needlets: the dilation B (a B closer to 1 asks for ~log(l) / log(B) levels), window bands, the
// band limit L of a needlet frame (its levels need cubatures of degree 2L), look-up table sizes,
// and the degree of a localisation profile.
inline constexpr double kMinDilation = 1.05, kMaxDilation = 64;
inline constexpr int kMaxNeedletBand = 4096;
// Mexican needlets x^(2p) exp(-x^2): orders p.
inline constexpr int kMaxMexicanOrder = 8;
inline constexpr int kMaxNeedletFrameBand = 63;
inline constexpr int kMinNeedletTableSize = 3, kMaxNeedletTableSize = 1 << 20;
// The descriptor set (WebGPU: bind group) and binding a shader evaluator's data is read from:
// Vulkan guarantees only 4 sets, WebGPU 4 groups of up to 1000 bindings.
inline constexpr int kMaxStorageSet = 3, kMaxStorageBinding = 999;
// A kernel profile: its degree (zhf needlets profile, the windows' localisation).
inline constexpr int kMaxProfileBand = 1023;

// candidates --json up to this order: its 174242 directions take about 400 MiB to write (order 20
// has 584162 and 1.4 GiB, order 32 6.4 million and 15 GiB).
inline constexpr int kMaxCandidatesJsonOrder = 16;
// The search tabulates candidates' SH values up front when they fit in this many doubles (1 GiB),
// else evaluates them on demand (same results, slower).
inline constexpr std::size_t kMaxTabulatedValues = std::size_t(1) << 27;

// Random rotations zhf verify draws besides its fixed extreme set.
inline constexpr int kMaxVerifyRotations = 1000000;

// Seconds a command may take to stop after SIGINT or SIGTERM before the watchdog removes its
// temporaries and ends it (work that polls stops well within this).
inline constexpr int kInterruptGraceSeconds = 3;
// Seconds verify gives Node to turn one WGSL wrapper into SPIR-V (naga takes ~0.1 s for order 8)
// before it is stopped and the order reported as failed.
inline constexpr double kShaderCompileSeconds = 300;

// Threads a caller may ask for (--threads, threads=): the bound on every thread pool zhf starts.
inline constexpr int kMaxThreads = 256;

// Input files, by kind: checked before they are read (the largest checked-in table, order 32,
// is 0.9 MiB; a coefficient file of this size holds tens of millions of numbers).
inline constexpr std::size_t kMaxTableBytes = std::size_t(16) << 20;
inline constexpr std::size_t kMaxSceneBytes = std::size_t(1) << 20;
inline constexpr std::size_t kMaxPathTableBytes = std::size_t(64) << 10;
// A path table's measured_on note (it goes into a comment of zhf_kernels.h).
inline constexpr std::size_t kMaxPathTableNoteChars = 300;
inline constexpr std::size_t kMaxManifestBytes = std::size_t(4) << 20;
inline constexpr std::size_t kMaxCoefficientBytes = std::size_t(64) << 20;
// Inside files: functions per manifest file and files per manifest (generous, checked before use);
// signals per scene; an ASCII .ply line (1024 properties of up to 60 characters).
inline constexpr std::size_t kMaxManifestFunctions = 256;
inline constexpr std::size_t kMaxManifestFiles = 4096;
inline constexpr int kMaxSceneSignals = 256;
inline constexpr std::size_t kMaxPlyAsciiLine = 64 << 10;
// .ply scenes: header size, properties (all elements together), elements, rows of an element
// (splats).
inline constexpr std::size_t kMaxPlyHeaderBytes = std::size_t(64) << 10;
inline constexpr std::size_t kMaxPlyProperties = 1024;
inline constexpr std::size_t kMaxPlyElements = 8;
inline constexpr std::uint64_t kMaxPlyVertices = std::uint64_t(1) << 31;
// A compressed scene (.spz) whose header claims more than this many bytes per byte of the file
// is refused before anything is decompressed: deflate cannot expand beyond about 1032:1, and a
// real scene's attributes compress far less (zstd could go further only on degenerate data).
inline constexpr double kMaxCompressionRatio = 1100;
// A .glb scene's JSON chunk (a splat file's is a few kilobytes; whole glTF scenes are larger).
inline constexpr std::size_t kMaxGlbJsonBytes = std::size_t(16) << 20;
// Its chunks, and its meshes, primitives, nodes, accessors, views and buffers (each).
inline constexpr int kMaxGlbChunks = 16;
inline constexpr int kMaxGlbObjects = 1 << 16;
// Radiance .hdr images: file and header size, width and height, pixels.
inline constexpr std::size_t kMaxHdrBytes = std::size_t(256) << 20;
inline constexpr std::size_t kMaxHdrHeader = 64 << 10;
inline constexpr int kMaxHdrSide = 32767;
inline constexpr long long kMaxHdrPixels = 1LL << 25;
// zhf needlets prt: vertices per side of the ground grid (64^2 = 4096 vertices: about 80 s here).
inline constexpr int kMaxPrtSide = 64;
// HEALPix FITS maps: Nside (12 Nside^2 pixels: 805 million, 6.4 GB as doubles, at the limit) and
// the bytes of the headers before the map's table (a map's are a few kilobytes).
inline constexpr long long kMaxHealpixNside = 8192;
inline constexpr std::size_t kMaxHealpixHeaderBytes = std::size_t(1) << 20;
// Jacobi steps of a HEALPix map's analysis (healpy's iter; 3 is its default and usually enough).
inline constexpr int kMaxHealpixIterations = 20;
// Options: zhf analyze's and analyze()'s relative tolerance goes down to this (double rounding);
// zhf splat --scale is a factor in [kMinSplatScale, kMaxSplatScale]; a search's local phase gets
// at least kMinSearchSeconds of a time limit.
inline constexpr double kMinZonalTolerance = 1e-15;
inline constexpr double kMinSplatScale = 1e-30, kMaxSplatScale = 1e30;
inline constexpr double kMinSearchSeconds = 1e-3;

}  // namespace zhf::runtime
