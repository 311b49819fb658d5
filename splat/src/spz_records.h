// A .spz file's extension records and the axes they or --spz-axes give it (docs/formats.md):
// records are a uint32 type, a uint32 byte length and the payload, back to back; the reference
// library's coordinate-system record names the file's axes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene_io.h"
#include "zhf/runtime/rotation.h"

namespace zhf::splat {

// The records filling `bytes` exactly (io::InputError naming path and the record otherwise).
std::vector<SpzExtension> parse_spz_records(const std::string& bytes, const std::string& path);
// The records as stored.
std::string spz_record_bytes(const std::vector<SpzExtension>& records);
// A .spz file's axes and how its SH change with them.
struct SpzFileAxes {
  runtime::Matrix3 axes = runtime::kIdentity;
  // The reference library's flip table gives band 4's m = 4 coefficient (the 24th above band 0,
  // even in y) the sign of its y flip: set where that flip negates y, so the coefficient is
  // negated in the file's values, as the library stores and reads it (docs/formats.md).
  bool negate_band4_m4 = false;
  std::string source;  // where the axes came from, for the report
};
// Reading: the file's axes in the .ply's (v_ply = axes v_file): its coordinate-system record's,
// which is taken out of `records`, else default_axes'. By the systems' letters, or with
// as_reference as the reference library converts them.
SpzFileAxes spz_read_axes(std::vector<SpzExtension>& records, SpzAxes default_axes, bool as_reference, const std::string& path);
// Writing: the .ply's axes in a file written with `axes` (v_file = axes v_ply).
SpzFileAxes spz_write_axes(SpzAxes axes, bool as_reference);
// "0x0000abcd", for messages.
std::string hex32(std::uint32_t x);

}  // namespace zhf::splat
