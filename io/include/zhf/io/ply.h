// PLY headers, as 3D Gaussian Splatting tools write them: one element "vertex" of scalar
// properties, ascii or binary_little_endian 1.0, with comments and obj_info lines kept as they
// are; or, for PlayCanvas's compressed splat files, several elements. Limits are checked before
// any data is read: a header of at most 64 KiB, at most 1024 properties and 8 elements, at most
// 2^31 rows an element; list properties, elements where one is expected and big-endian data are
// refused with the line that says so.
#pragma once

#include <cstddef>
#include <cstdint>
#include <istream>
#include <string>
#include <string_view>
#include <vector>
#include "zhf/io/limits.h"

namespace zhf::io::ply {

enum class Format { kAscii, kBinaryLittleEndian };
enum class Type { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

struct Property {
  std::string name;
  Type type = Type::kFloat32;
  std::size_t offset = 0;  // in a binary record
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
  std::size_t record_bytes = 0;  // binary: bytes per row

  // The property's position, or -1.
  int find(std::string_view name) const;
};

struct Header {
  Format format = Format::kBinaryLittleEndian;
  std::string text;  // the header's bytes, from "ply" through "end_header\n", written back as they are
  std::uint64_t vertices = 0;
  std::vector<Property> properties;
  std::size_t record_bytes = 0;  // binary: bytes per vertex
  std::vector<Element> elements;   // every element, in the file's order (the vertex one included)

  // The vertex property's position, or -1.
  int find(std::string_view name) const;
};

std::size_t type_size(Type type);
bool is_float(Type type);

// Reads the header from the start of the stream; throws InputError "<source>: header line K: ...".
// One element, "vertex".
Header read_header(std::istream& in, const std::string& source);
// Any elements (vertices, properties and record_bytes then describe the "vertex" one, if any).
Header read_header_elements(std::istream& in, const std::string& source);

// A binary little-endian value of the property in a record, as a double, and back (rounded to
// the property's type; integer properties are never written by zhf).
double read_binary(const unsigned char* record, const Property& property);
void write_binary(unsigned char* record, const Property& property, double value);

// ASCII data, one vertex a line. The next line (at most kMaxPlyAsciiLine bytes, without its
// newline), read into buffer; throws InputError "<source>: splat K: ..." when it is longer or
// missing.
std::string_view read_ascii_line(std::istream& in, std::vector<char>& buffer, const std::string& source, std::uint64_t vertex,
                                 std::uint64_t vertices);
// A line's tokens, split at spaces and tabs.
std::vector<std::string_view> split_ascii(std::string_view line);
// One token per property into values: floats strictly (finite), integers in their type's range.
// False when any is not.
bool parse_ascii(const std::vector<std::string_view>& tokens, const Header& header, double* values);
// The same for a line, throwing InputError "<source>: splat K: property P: '<token>' <problem>".
void parse_ascii_or_throw(std::string_view line, const Header& header, const std::string& source, std::uint64_t vertex, double* values);
// After the last line: only spaces, tabs and newlines may follow (InputError otherwise).
void check_ascii_end(std::istream& in, const std::string& source);

}  // namespace zhf::io::ply
