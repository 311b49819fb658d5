// A .spz file's extension records and the axes they or --spz-axes give it (docs/formats.md):
// records are a uint32 type, a uint32 byte length and the payload, back to back; the reference
// library's coordinate-system record names the file's axes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "formats.h"
#include "zhf/runtime/rotation.h"

namespace zhf::splat {

// The records filling `bytes` exactly (io::InputError naming path and the record otherwise).
std::vector<SpzExtension> parse_spz_records(const std::string& bytes, const std::string& path);
// The records as stored.
std::string spz_record_bytes(const std::vector<SpzExtension>& records);
// The file's axes in the .ply's (v_ply = A v_file): its coordinate-system record's, which is taken
// out of `records`, else default_axes'. `source` says which, for the report.
runtime::Matrix3 spz_read_axes(std::vector<SpzExtension>& records, SpzAxes default_axes, const std::string& path, std::string& source);
// The .ply's axes in a file written with `axes` (v_file = B v_ply).
runtime::Matrix3 spz_write_axes(SpzAxes axes);
// "0x0000abcd", for messages.
std::string hex32(std::uint32_t x);

}  // namespace zhf::splat
