// 3D Gaussian Splatting scenes (.ply, as the 3DGS tools write them; PlayCanvas's compressed .ply;
// antimatter15's .splat; Niantic's .spz; glTF .glb with KHR_gaussian_splatting) transformed as a
// whole, and converted from one format to another:
// p' = s R p + t for positions (rotate and scale about the origin, then translate), the
// Gaussians' orientations and normals turned by R, log-scales plus log s, and each splat's
// view-dependent colour (SH of degree 0..4 in the file's convention, 3dgs by default) turned
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
#include <vector>

#include "zhf/runtime/conventions.h"
#include "zhf/runtime/rotation.h"
#include "zhf/splat/limits.h"

namespace zhf::splat {

struct Transform {
  runtime::Matrix3 r{1, 0, 0, 0, 1, 0, 0, 0, 1};  // orthogonal, v -> R v, in the file's axes
  double scale = 1;                                 // uniform, > 0
  std::array<double, 3> translation{};
  const runtime::Convention* convention = nullptr;  // the SH's; nullptr: 3dgs
};

enum class FileFormat { kPly, kCompressedPly, kSplat, kSpz, kGlb, kSog };

// "ply", "compressed-ply", "splat", "spz", "glb", "sog", or false.
bool parse_file_format(const std::string& name, FileFormat& format);
// ".ply", ".compressed.ply", ".splat", ".spz", ".glb", ".sog".
const char* file_format_extension(FileFormat format);
// "ply, compressed-ply, splat, spz, glb or sog", for messages.
std::string file_format_names();
// From the name's ending (any case; the longest that fits; a file named meta.json is a SOG), or false.
bool file_format_of(const std::string& path, FileFormat& format);

// The SH degree a format holds at most (.splat: colour only).
int file_format_max_sh_degree(FileFormat format);

// A .spz file's axes where it carries no coordinate-system record (docs/formats.md): kRaw, the
// .ply's own (what the reference library writes by default, its ply_to_spz and splat-transform),
// or kRub, the format's documented x right, y up, z back (Scaniverse's files, three.js).
enum class SpzAxes { kRaw, kRub };
// "raw", "rub", or false.
bool parse_spz_axes(const std::string& name, SpzAxes& axes);

struct Summary {
  std::uint64_t splats = 0;
  int sh_degree = -1;  // -1: no colour properties
  bool ascii = false;
  FileFormat in = FileFormat::kPly, out = FileFormat::kPly;
  int kept_degree = -1;        // the SH degree written (converted scenes)
  int dropped_degree = -1;     // the SH degree the output format could not hold (-1: none dropped)
  // Bands above kept_degree left out (--sh-degree, --max-sh-error): the relative L2 error of the
  // colours' SH over the scene, as zhf analyze measures it (sqrt of the dropped energy over the
  // whole), and the largest error of one splat's colour over view directions (docs/formats.md).
  double dropped_energy_error = 0, dropped_colour_error = 0;
  std::uint64_t dropped_bytes = 0;  // SH bytes the output does not hold (before a format's compression)
  bool antialiased = false;         // the input's flag (.spz)
  bool antialiasing_dropped = false;  // set, and the output format has no such flag
  std::string spz_axes_source;        // a .spz's axes and where they came from, e.g. "rub (coordinate-system record)"
  int carried_extensions = 0;         // .spz extension records carried unchanged
  int dropped_extensions = 0;         // left out, as --drop-spz-extensions asks
  std::uint64_t palette_entries = 0;  // a .sog turned: its SH palette's entries, each turned once
  std::vector<std::string> left_out;  // what of the input the output does not hold, a phrase each (converted scenes)
  // Splats the filters left out (Filters), by the first reason that applies, in this order.
  std::uint64_t nonfinite = 0, outside = 0, transparent = 0;
  std::uint64_t written() const { return splats - nonfinite - outside - transparent; }
  std::uint64_t clamped = 0;   // values outside the output's range, written as its nearest
  // Converted (any pair but .ply to .ply): per SH band (0: f_dc), the largest |written - exact|
  // of the transformed values, what the output format's steps cost; -1 for a band not written.
  std::array<double, kMaxSplatShDegree + 1> sh_error = unwritten();
  static std::array<double, kMaxSplatShDegree + 1> unwritten() {
    std::array<double, kMaxSplatShDegree + 1> a;
    a.fill(-1);
    return a;
  }
};

// Which splats are written. Each splat is judged as read: its position where the transform puts
// it (in the .ply's axes, s R p + t), its opacity, the finiteness of its values. Kept splats
// stay in the input's order. With any filter a scene is read twice (the first pass counts the
// splats the output's header needs), and a .ply goes through the canonical record.
struct Filters {
  bool drop_nonfinite = false;  // leave out a splat with a NaN or infinite value (else refused)
  std::optional<std::array<double, 6>> crop_box;     // x0 y0 z0 x1 y1 z1: kept inside, bounds included
  std::optional<std::array<double, 4>> crop_sphere;  // x y z r: kept within r of (x, y, z)
  std::optional<double> min_opacity;                 // kept where sigmoid(opacity) >= it, in 0..1
  bool any() const { return drop_nonfinite || crop_box || crop_sphere || min_opacity; }
};

// Splats per chunk: the memory bound (a degree-3 binary splat is 248 bytes).
inline constexpr std::uint64_t kChunkSplats = 1 << 16;

// progress(done, total) after each chunk; threads 0: all cores. Formats from the files' names
// unless given (.ply when the name says none); a .ply input whose first element is "chunk" is
// read as compressed.
struct Formats {
  std::optional<FileFormat> in, out;
  int spz_version = 4;  // written: 4 (zstd streams, the reference library's default) or 3 (gzip)
  SpzAxes spz_axes = SpzAxes::kRaw;  // of a .spz read without a coordinate-system record, and of one written
  // A .spz's axes converted as the reference library converts them, where it differs from the
  // systems' letters (docs/formats.md): LFD, RFD, LBU and RBU, and band 4's m = 4 coefficient.
  bool spz_as_reference = false;
  bool drop_spz_extensions = false;  // records a non-.spz output cannot carry: left out (else refused)
  bool keep_order = false;           // a compressed .ply in the input's order (default: Morton order)
  std::uint64_t sog_seed = 1;        // a .sog written from another format: its palette's k-means draws
  // The SH bands written: 0..sh_degree (at most the scene's), or the smallest degree whose
  // dropped energy error stays within max_sh_error; neither: all the output format holds.
  std::optional<int> sh_degree;
  std::optional<double> max_sh_error;
  Filters filters;
};
Summary transform_file(const std::string& in, const std::string& out, const Transform& transform, int threads,
                       const std::function<void(std::uint64_t, std::uint64_t)>& progress, const Formats& formats = {});
// Several scenes merged into one output, in the order given: each read in its own format and
// turned from its own axes into the .ply's, then all transformed alike. The output holds the
// highest SH degree among them; a scene of a lower degree gets zeros in the bands it lacks (its
// colours unchanged). Extension records of every .spz input are carried (or dropped) together;
// the output is marked antialiased only where every input is. One input: transform_file.
Summary transform_files(const std::vector<std::string>& in, const std::string& out, const Transform& transform, int threads,
                        const std::function<void(std::uint64_t, std::uint64_t)>& progress, const Formats& formats = {});

// What zhf splat --info reports of a scene, read whole (every value checked as a conversion checks
// it) and nothing written: its format, splats, SH degree, the box of its positions in the .ply's
// axes, its axes and where they came from, the antialiasing mark and its extension records.
struct SceneInfo {
  FileFormat format = FileFormat::kPly;
  std::uint64_t splats = 0;
  int sh_degree = 0;
  std::array<double, 3> low{}, high{};  // of the positions (empty scene: zeros)
  std::string axes_source;              // "" for a format in the .ply's axes
  bool antialiased = false;
  std::vector<std::uint32_t> extension_types;  // .spz extension records, in file order
};
SceneInfo describe_file(const std::string& in, const Formats& formats = {});

}  // namespace zhf::splat
