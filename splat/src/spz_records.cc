#include "spz_records.h"

#include <cstdio>
#include <iterator>
#include <string_view>

#include "format_io.h"
#include "zhf/io/errors.h"
#include "zhf/splat/limits.h"

namespace zhf::splat {
namespace {

using io::InputError;

constexpr std::size_t kRecordHeaderBytes = 8;
// The reference library's coordinate-system record (Adobe's vendor id 0xADBE, extension 3): one
// uint32, 0 (unspecified: RUB, as the library reads it) or one of the 16 systems below.
constexpr std::uint32_t kCoordinateSystemRecord = 0xADBE0003;
constexpr const char* kCoordinateSystems[] = {"RUB", "LDB", "RDB", "LUB", "RUB", "LDF", "RDF", "LUF", "RUF",
                                              "LFD", "RFD", "LFU", "RFU", "LBD", "RBD", "LBU", "RBU"};
constexpr std::uint32_t kRubSystem = 4, kRdfSystem = 6;

// A system's letters (the directions of its x, y, z) as the map into the .ply's axes (RDF: x
// right, y down, z front): column i is the .ply direction of the file's axis i.
runtime::Matrix3 axes_of(std::string_view letters) {
  runtime::Matrix3 a{};
  for (int i = 0; i < 3; ++i) {
    const char c = letters[i];
    const int row = c == 'R' || c == 'L' ? 0 : c == 'D' || c == 'U' ? 1 : 2;
    a[3 * row + i] = c == 'R' || c == 'D' || c == 'F' ? 1 : -1;
  }
  return a;
}

std::string_view letters_of(SpzAxes axes) { return axes == SpzAxes::kRub ? "RUB" : "RDF"; }

// The signs that take a system's axes to the .ply's (RDF) axis by axis, for two systems whose
// axes lie along the same lines: +1 where their letters agree.
runtime::Matrix3 flips_to_ply(std::string_view letters) {
  runtime::Matrix3 f{};
  for (int i = 0; i < 3; ++i) f[4 * i] = letters[i] == "RDF"[i] ? 1 : -1;
  return f;
}

// The reference library's reading of a system into RDF, as its coordinateConverter builds it
// (nianticlabs/spz, src/cc/splat-types.h). Systems 1..8 (x along R/L, y along U/D, z along F/B)
// get a flip per axis: the letters' map. Systems 9..16 (y along F/B, z along U/D) are each
// system 8 below turned a quarter about x; the library flips the file's values with the flips of
// that partner, then turns them, (x, y, z) -> (x, z, -y). The letters' map turns first. The two
// agree where the partner's y and z flips are equal, and differ by a half turn about x (y and z
// negated) for LFD, RFD, LBU and RBU. `y_flipped`: the library's flip negates y.
runtime::Matrix3 reference_axes_of(std::uint32_t system, bool& y_flipped) {
  const bool rotated = system > 8;
  const runtime::Matrix3 flip = flips_to_ply(kCoordinateSystems[rotated ? system - 8 : system]);
  y_flipped = flip[4] < 0;
  if (!rotated) return flip;
  const runtime::Matrix3 quarter_turn = {1, 0, 0, 0, 0, 1, 0, -1, 0};
  return runtime::multiply(quarter_turn, flip);
}

}  // namespace

std::string hex32(std::uint32_t x) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%08x", x);
  return text;
}

std::vector<SpzExtension> parse_spz_records(const std::string& bytes, const std::string& path) {
  if (bytes.size() > kMaxSpzExtensionBytes)
    throw InputError(path + ": " + std::to_string(bytes.size()) + " bytes of extension records; at most " + std::to_string(kMaxSpzExtensionBytes));
  std::vector<SpzExtension> records;
  for (std::size_t at = 0; at < bytes.size();) {
    if (records.size() == std::size_t(kMaxSpzExtensionRecords))
      throw InputError(path + ": more than " + std::to_string(kMaxSpzExtensionRecords) + " extension records");
    if (bytes.size() - at < kRecordHeaderBytes) throw InputError(path + ": extension record " + std::to_string(records.size()) + ": truncated header");
    SpzExtension r;
    r.type = get_uint32(reinterpret_cast<const unsigned char*>(bytes.data() + at));
    const std::uint32_t length = get_uint32(reinterpret_cast<const unsigned char*>(bytes.data() + at + 4));
    at += kRecordHeaderBytes;
    if (r.type == 0) throw InputError(path + ": extension record " + std::to_string(records.size()) + ": type 0 is reserved");
    if (length > bytes.size() - at)
      throw InputError(path + ": extension record " + std::to_string(records.size()) + " (" + hex32(r.type) + "): " + std::to_string(length) +
                       " bytes, past the end of the records");
    r.payload = bytes.substr(at, length);
    at += length;
    records.push_back(std::move(r));
  }
  return records;
}

std::string spz_record_bytes(const std::vector<SpzExtension>& records) {
  std::string out;
  for (const SpzExtension& r : records) {
    unsigned char head[kRecordHeaderBytes];
    put_uint32(head, r.type);
    put_uint32(head + 4, static_cast<std::uint32_t>(r.payload.size()));
    out.append(reinterpret_cast<const char*>(head), kRecordHeaderBytes);
    out += r.payload;
  }
  return out;
}

SpzFileAxes spz_read_axes(std::vector<SpzExtension>& records, SpzAxes default_axes, bool as_reference, const std::string& path) {
  std::uint32_t system = default_axes == SpzAxes::kRub ? kRubSystem : kRdfSystem;
  SpzFileAxes axes;
  axes.source = std::string(default_axes == SpzAxes::kRub ? "rub" : "raw") + " (--spz-axes; no coordinate-system record)";
  std::vector<SpzExtension> others;
  bool seen = false;
  for (SpzExtension& r : records) {
    if (r.type != kCoordinateSystemRecord) {
      others.push_back(std::move(r));
      continue;
    }
    const std::string what = path + ": coordinate-system record";
    if (seen) throw InputError(what + ": given twice");
    if (r.payload.size() != 4) throw InputError(what + ": " + std::to_string(r.payload.size()) + " bytes; expected 4");
    system = get_uint32(reinterpret_cast<const unsigned char*>(r.payload.data()));
    if (system >= std::size(kCoordinateSystems)) throw InputError(what + ": " + std::to_string(system) + " is not a coordinate system (0..16)");
    seen = true;
    axes.source = std::string(kCoordinateSystems[system]) + " (coordinate-system record" + (system == 0 ? ", unspecified: RUB" : "") + ")";
  }
  records = std::move(others);
  if (system == 0) system = kRubSystem;
  if (as_reference) {
    bool y_flipped = false;
    axes.axes = reference_axes_of(system, y_flipped);
    axes.negate_band4_m4 = y_flipped;
    axes.source += ", as the reference library reads it";
  } else {
    axes.axes = axes_of(kCoordinateSystems[system]);
  }
  return axes;
}

SpzFileAxes spz_write_axes(SpzAxes axes, bool as_reference) {
  SpzFileAxes written;
  written.axes = runtime::transpose(axes_of(letters_of(axes)));
  written.negate_band4_m4 = as_reference && axes == SpzAxes::kRub;
  return written;
}

}  // namespace zhf::splat
