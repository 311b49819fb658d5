// One row per scene format: its name, file extension, highest SH degree and the functions that
// read and write it. Everything that asks what a format is or holds asks here.
#pragma once

#include <memory>
#include <string>

#include "scene_io.h"

namespace zhf::splat {

struct FormatRow {
  FileFormat format;
  const char* name;       // as --format and --in-format take it
  const char* extension;  // the longest ending that names it
  int max_sh_degree;
  int sh_value_bytes;  // one SH coefficient of one channel, as stored before any compression
  std::unique_ptr<SceneReader> (*open_reader)(const std::string& path, const Formats& formats);
  std::unique_ptr<SceneWriter> (*open_writer)(io::PendingFile& out, const WriteOptions& options);
};

const FormatRow& format_row(FileFormat format);

// The format's reader; with formats.filters.drop_nonfinite it keeps NaN and infinity for the filter.
std::unique_ptr<SceneReader> open_reader(FileFormat format, const std::string& path, const Formats& formats);
// Records of SH degree options.degree into `out`.
std::unique_ptr<SceneWriter> open_writer(FileFormat format, io::PendingFile& out, const WriteOptions& options);

}  // namespace zhf::splat
