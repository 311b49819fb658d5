// Scenes as streams of the canonical record, the 3DGS tools' binary .ply properties in double
// (x y z nx ny nz f_dc_0..2 f_rest_* opacity scale_0..2 rot_0..3): how zhf splat converts
// between formats. Readers check sizes before reading and every value as they read it.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "zhf/io/files.h"
#include "zhf/io/ply.h"
#include "zhf/runtime/rotation.h"
#include "zhf/splat/scene.h"

namespace zhf::splat {

// The canonical record's header for SH degree 0..kMaxSplatShDegree and that many splats.
io::ply::Header canonical_header(int degree, std::uint64_t splats);

// A .spz extension record zhf does not read (type, payload), carried as it is.
struct SpzExtension {
  std::uint32_t type = 0;
  std::string payload;
};

class SceneReader {
 public:
  virtual ~SceneReader() = default;
  std::uint64_t splats() const { return splats_; }
  int degree() const { return degree_; }
  // The file's axes in the .ply's: v_ply = axes() v_file (a signed permutation).
  const runtime::Matrix3& axes() const { return axes_; }
  // Where axes() came from, for the report ("" for a format with the .ply's axes).
  const std::string& axes_source() const { return axes_source_; }
  bool antialiased() const { return antialiased_; }
  const std::vector<SpzExtension>& extensions() const { return extensions_; }
  // What of the file an output of format `to` written from the canonical record does not hold, a
  // phrase each ("" none): a .ply's properties outside the record; into a .ply its comments, ASCII
  // and double precision; into other formats normals that are not all 0 (known after the last read).
  virtual std::vector<std::string> left_out(FileFormat /*to*/) const { return {}; }
  // The next `count` records (canonical_header(degree()) properties each); `first` is the first
  // one's index, for messages. Throws io::InputError naming the file, splat and field.
  virtual void read(std::uint64_t first, std::uint64_t count, double* records) = 0;
  // Throws when bytes follow the last splat.
  virtual void finish() = 0;
  // A NaN or infinite value is read as it is, for the caller to leave its splat out, instead of
  // refused (the formats that store floats: .ply, .splat, .glb; the others cannot hold one).
  void keep_nonfinite() { keep_nonfinite_ = true; }

 protected:
  bool keep_nonfinite_ = false;
  std::uint64_t splats_ = 0;
  int degree_ = 0;
  runtime::Matrix3 axes_ = runtime::kIdentity;
  std::string axes_source_;
  bool antialiased_ = false;
  std::vector<SpzExtension> extensions_;
};

// What a writer is given beyond the records.
struct WriteOptions {
  int degree = 0;  // of the records, at most file_format_max_sh_degree of the format
  std::uint64_t splats = 0;
  int spz_version = 4;
  SpzAxes spz_axes = SpzAxes::kRaw;
  bool spz_as_reference = false;
  bool antialiased = false;                 // .spz's flag
  std::vector<SpzExtension> spz_extensions;  // carried into a .spz
  bool keep_order = false;                   // a compressed .ply in the input's order, not Morton's
  std::uint64_t seed = 1;                    // a .sog's palette (k-means draws)
  int threads = 0;                           // a .sog's palette fit: 0, all cores
};

class SceneWriter {
 public:
  virtual ~SceneWriter() = default;
  virtual void write(std::uint64_t count, const double* records) = 0;
  std::uint64_t clamped() const { return clamped_; }
  // Per SH band (0: f_dc), the largest |stored - given| of the values written: the format's error.
  const std::array<double, kMaxSplatShDegree + 1>& sh_error() const { return sh_error_; }
  // The .ply's axes in the file's: v_file = axes() v_ply.
  const runtime::Matrix3& axes() const { return axes_; }
  // After the last record, before the file is committed.
  virtual void finish() {}

 protected:
  void stored(int band, double given, double kept) { sh_error_[band] = std::max(sh_error_[band], std::abs(kept - given)); }
  std::uint64_t clamped_ = 0;
  std::array<double, kMaxSplatShDegree + 1> sh_error_{};
  runtime::Matrix3 axes_ = runtime::kIdentity;
};

// Each format's own (ply_scene.cc, splat_file.cc, compressed_ply.cc, spz.cc, glb.cc, sog.cc), one
// signature for all: registry.cc's rows hold them, and open_reader and open_writer pick one.
std::unique_ptr<SceneReader> open_ply_reader(const std::string& path, const Formats& formats);
std::unique_ptr<SceneWriter> open_ply_writer(io::PendingFile& out, const WriteOptions& options);
std::unique_ptr<SceneReader> open_splat_reader(const std::string& path, const Formats& formats);
std::unique_ptr<SceneWriter> open_splat_writer(io::PendingFile& out, const WriteOptions& options);
std::unique_ptr<SceneReader> open_compressed_ply_reader(const std::string& path, const Formats& formats);
std::unique_ptr<SceneWriter> open_compressed_ply_writer(io::PendingFile& out, const WriteOptions& options);
std::unique_ptr<SceneReader> open_spz_reader(const std::string& path, const Formats& formats);
std::unique_ptr<SceneWriter> open_spz_writer(io::PendingFile& out, const WriteOptions& options);
std::unique_ptr<SceneReader> open_glb_reader(const std::string& path, const Formats& formats);
std::unique_ptr<SceneWriter> open_glb_writer(io::PendingFile& out, const WriteOptions& options);
std::unique_ptr<SceneReader> open_sog_reader(const std::string& path, const Formats& formats);
std::unique_ptr<SceneWriter> open_sog_writer(io::PendingFile& out, const WriteOptions& options);
// A .sog turned into a .sog: positions and orientations per splat, the SH palette once (sog.cc).
Summary transform_sog(const std::string& in, const std::string& out, const Transform& transform, const Formats& formats, Summary summary);

}  // namespace zhf::splat
