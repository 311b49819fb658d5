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

#include "zhf/io/files.h"
#include "zhf/io/ply.h"
#include "zhf/splat/scene.h"

namespace zhf::splat {

// The canonical record's header for SH degree 0..3 and that many splats.
io::ply::Header canonical_header(int degree, std::uint64_t splats);

class SceneReader {
 public:
  virtual ~SceneReader() = default;
  std::uint64_t splats() const { return splats_; }
  int degree() const { return degree_; }
  // The next `count` records (canonical_header(degree()) properties each); `first` is the first
  // one's index, for messages. Throws io::InputError naming the file, splat and field.
  virtual void read(std::uint64_t first, std::uint64_t count, double* records) = 0;
  // Throws when bytes follow the last splat.
  virtual void finish() = 0;

 protected:
  std::uint64_t splats_ = 0;
  int degree_ = 0;
};

class SceneWriter {
 public:
  virtual ~SceneWriter() = default;
  virtual void write(std::uint64_t count, const double* records) = 0;
  std::uint64_t clamped() const { return clamped_; }
  // Per SH band (0: f_dc), the largest |stored - given| of the values written: the format's error.
  const std::array<double, 4>& sh_error() const { return sh_error_; }
  // The SH degree this writer keeps of a scene of `degree`.
  virtual int kept_degree(int degree) const = 0;
  // After the last record, before the file is committed.
  virtual void finish() {}

 protected:
  void stored(int band, double given, double kept) { sh_error_[band] = std::max(sh_error_[band], std::abs(kept - given)); }
  std::uint64_t clamped_ = 0;
  std::array<double, 4> sh_error_{};
};

std::unique_ptr<SceneReader> open_reader(FileFormat format, const std::string& path);
// Each format's own (splat_file.cc, compressed_ply.cc, spz.cc, glb.cc), behind open_reader and open_writer.
std::unique_ptr<SceneReader> open_splat_reader(const std::string& path);
std::unique_ptr<SceneWriter> open_splat_writer(io::PendingFile& out, int degree);
std::unique_ptr<SceneReader> open_compressed_ply_reader(const std::string& path);
std::unique_ptr<SceneWriter> open_compressed_ply_writer(io::PendingFile& out, int degree, std::uint64_t splats);
std::unique_ptr<SceneReader> open_spz_reader(const std::string& path);
std::unique_ptr<SceneWriter> open_spz_writer(io::PendingFile& out, int degree, std::uint64_t splats, int version);
std::unique_ptr<SceneReader> open_glb_reader(const std::string& path);
std::unique_ptr<SceneWriter> open_glb_writer(io::PendingFile& out, int degree, std::uint64_t splats);
// Records of SH degree `degree` into `out`.
std::unique_ptr<SceneWriter> open_writer(FileFormat format, io::PendingFile& out, int degree, std::uint64_t splats, int spz_version);

}  // namespace zhf::splat
