#include "registry.h"

#include <filesystem>
#include <vector>

#include "zhf/runtime/enum_names.h"
#include "zhf/splat/limits.h"

namespace zhf::splat {
namespace {

constexpr FormatRow kFormats[] = {
    {FileFormat::kPly, "ply", ".ply", kMaxSplatShDegree, 4, open_ply_reader, open_ply_writer},
    {FileFormat::kCompressedPly, "compressed-ply", ".compressed.ply", 3, 1, open_compressed_ply_reader, open_compressed_ply_writer},
    {FileFormat::kSplat, "splat", ".splat", 0, 0, open_splat_reader, open_splat_writer},
    {FileFormat::kSpz, "spz", ".spz", kMaxSplatShDegree, 1, open_spz_reader, open_spz_writer},
    {FileFormat::kGlb, "glb", ".glb", 3, 4, open_glb_reader, open_glb_writer},
    {FileFormat::kSog, "sog", ".sog", 3, 0, open_sog_reader, open_sog_writer},
};

}  // namespace

const FormatRow& format_row(FileFormat format) {
  for (const FormatRow& f : kFormats)
    if (f.format == format) return f;
  return kFormats[0];
}

std::unique_ptr<SceneReader> open_reader(FileFormat format, const std::string& path, const Formats& formats) {
  std::unique_ptr<SceneReader> reader = format_row(format).open_reader(path, formats);
  if (formats.filters.drop_nonfinite) reader->keep_nonfinite();
  return reader;
}

std::unique_ptr<SceneWriter> open_writer(FileFormat format, io::PendingFile& out, const WriteOptions& options) {
  return format_row(format).open_writer(out, options);
}

bool parse_file_format(const std::string& name, FileFormat& format) {
  for (const FormatRow& f : kFormats)
    if (name == f.name) {
      format = f.format;
      return true;
    }
  return false;
}

int file_format_max_sh_degree(FileFormat format) { return format_row(format).max_sh_degree; }

const char* file_format_extension(FileFormat format) { return format_row(format).extension; }

std::string file_format_names() {
  std::vector<std::string> names;
  for (const FormatRow& f : kFormats) names.push_back(f.name);
  return runtime::name_list(names);
}

bool file_format_of(const std::string& path, FileFormat& format) {
  std::string lower = std::filesystem::path(path).filename().string();
  for (char& c : lower) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  if (lower == "meta.json") {  // a SOG's files beside their meta.json
    format = FileFormat::kSog;
    return true;
  }
  std::size_t best = 0;
  for (const FormatRow& f : kFormats) {
    const std::string extension = f.extension;
    if (lower.size() > extension.size() && extension.size() > best && lower.compare(lower.size() - extension.size(), extension.size(), extension) == 0) {
      format = f.format;
      best = extension.size();
    }
  }
  return best > 0;
}

bool parse_spz_axes(const std::string& name, SpzAxes& axes) {
  if (name != "raw" && name != "rub") return false;
  axes = name == "rub" ? SpzAxes::kRub : SpzAxes::kRaw;
  return true;
}

}  // namespace zhf::splat
