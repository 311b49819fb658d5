// 3D Gaussian Splatting scenes (.ply, as the 3DGS tools write them; PlayCanvas's compressed .ply;
// antimatter15's .splat; Niantic's .spz; glTF .glb with KHR_gaussian_splatting) transformed as a
// whole, and converted from one format to another:
// p' = s R p + t for positions (rotate and scale about the origin, then translate), the
// Gaussians' orientations and normals turned by R, log-scales plus log s, and each splat's
// view-dependent colour (SH of degree 0..3 in the file's convention, 3dgs by default) turned
// with R, so that the colour seen from R d after equals the colour seen from d before.
// R may be a reflection (a mirrored scene): an orientation then becomes R Q F, F = diag(1, 1, -1),
// which is a rotation and keeps the Gaussian's shape.
//
// .ply to .ply: the file's columns, their types and order, its comments and every property zhf
// does not transform are written back unchanged. ASCII and binary little-endian are read and
// written in the same format. Any other pair goes through the 3DGS tools' binary .ply record
// (x y z nx ny nz f_dc_0..2 f_rest_* opacity scale_0..2 rot_0..3, in double): a reader fills it
// (a binary .ply needs x..z, f_dc, opacity, scale and rot to be converted), the transform acts on
// it, a writer quantises it (docs/formats.md: what each format keeps and what it costs). Streaming: a bounded chunk of splats is in memory at a time, spread over
// threads. Any bad input (header, counts, truncation, trailing bytes, a non-finite number)
// throws InputError before the output is committed: nothing is written.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "zhf/runtime/conventions.h"
#include "zhf/runtime/rotation.h"

namespace zhf::splat {

struct Transform {
  runtime::Matrix3 r{1, 0, 0, 0, 1, 0, 0, 0, 1};  // orthogonal, v -> R v, in the file's axes
  double scale = 1;                                 // uniform, > 0
  std::array<double, 3> translation{};
  const runtime::Convention* convention = nullptr;  // the SH's; nullptr: 3dgs
};

enum class FileFormat { kPly, kCompressedPly, kSplat, kSpz, kGlb };

// "ply", "compressed-ply", "splat", "spz", "glb", or false.
bool parse_file_format(const std::string& name, FileFormat& format);
const char* file_format_name(FileFormat format);
// ".ply", ".compressed.ply", ".splat", ".spz", ".glb".
const char* file_format_extension(FileFormat format);
// "ply, compressed-ply, splat, spz or glb", for messages.
std::string file_format_names();
// From the name's ending (any case; the longest that fits), or false.
bool file_format_of(const std::string& path, FileFormat& format);

struct Summary {
  std::uint64_t splats = 0;
  int sh_degree = -1;  // -1: no colour properties
  bool ascii = false;
  FileFormat in = FileFormat::kPly, out = FileFormat::kPly;
  int dropped_degree = -1;     // the SH degree the output format could not hold (-1: none dropped)
  std::uint64_t clamped = 0;   // values outside the output's range, written as its nearest
  // Converted (any pair but .ply to .ply): per SH band (0: f_dc), the largest |written - exact|
  // of the transformed values, what the output format's steps cost; -1 for a band not written.
  std::array<double, 4> sh_error{-1, -1, -1, -1};
};

// Splats per chunk: the memory bound (a degree-3 binary splat is 248 bytes).
inline constexpr std::uint64_t kChunkSplats = 1 << 16;

// progress(done, total) after each chunk; threads 0: all cores. Formats from the files' names
// unless given (.ply when the name says none); a .ply input whose first element is "chunk" is
// read as compressed.
struct Formats {
  std::optional<FileFormat> in, out;
  int spz_version = 4;  // written: 4 (zstd streams, the reference library's default) or 3 (gzip)
};
Summary transform_file(const std::string& in, const std::string& out, const Transform& transform, int threads,
                       const std::function<void(std::uint64_t, std::uint64_t)>& progress, const Formats& formats = {});

}  // namespace zhf::splat
