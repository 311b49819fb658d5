// The tools' JSON reader: every JSON input outside the header-only runtime (scenes, manifests,
// coefficient files, path tables, directions, glTF, bench reports) is parsed by nlohmann-json and
// read through Field, which checks each value's type and range where it is used.
//
// Strict RFC 8259 as nlohmann-json reads it (no NaN or Infinity, no comments, no trailing commas
// or characters, well-formed UTF-8, numbers beyond a double refused), and more: duplicate keys and
// NUL characters in strings are refused, and the nesting depth, value count, string length and keys
// per object are checked while parsing, so hostile input is refused in bounded time and memory, and
// a document parses in time O(n log k) (n values, k keys an object). Objects keep
// their members in file order. Integers are kept exactly (nlohmann's integer types), so an integer
// field converts without rounding or wrapping.
//
// Errors are runtime::InputError, one line: "<source>: not valid JSON at line L, column C: ..."
// while parsing, "<source>: <path>: <problem>" while reading, e.g.
// "scene.json: signals[1].channels: must be 1..4 (got 7)".
//
// The runtime reads lobe tables with its own parser (runtime/json.h; docs/design.md says why);
// this one is for the files only the tools read.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "zhf/runtime/limits.h"

namespace zhf::io::json {

using Json = nlohmann::ordered_json;

// The bounds of one parse (runtime/limits.h says what each is; a reader may ask for less).
struct Limits {
  int max_depth = runtime::kMaxJsonDepth;
  std::size_t max_values = runtime::kMaxJsonValues;
  std::size_t max_string_bytes = runtime::kMaxJsonStringBytes;
  std::size_t max_object_keys = runtime::kMaxJsonObjectKeys;
};

// Parses a whole document; source names it in errors.
Json parse(std::string_view text, const std::string& source, const Limits& limits = {});
// The file (at most max_bytes) parsed.
Json read_file(const std::string& path, std::size_t max_bytes, const Limits& limits = {});

enum class Kind { kNull, kBool, kNumber, kString, kArray, kObject };
Kind kind_of(const Json& value);

// A value and the path that names it: every read checks the value's type and range and, when
// they are wrong, throws InputError "<source>: <path>: <problem>".
class Field {
 public:
  Field(const Json& value, std::string source, std::string path = {});

  const Json& value() const { return *value_; }
  const std::string& source() const { return source_; }
  // "lobes[3].xyz", or "top level".
  std::string where() const;

  [[noreturn]] void fail(const std::string& problem) const;

  bool is(Kind kind) const { return kind_of(*value_) == kind; }
  void expect(Kind kind) const;

  // Objects.
  std::optional<Field> find(std::string_view key) const;
  Field member(std::string_view key) const;
  // Refuses keys outside the list (a typo is an error, not a silent default).
  void allow_only(std::initializer_list<std::string_view> keys) const;

  // Arrays: the items, after checking the length.
  std::vector<Field> items(std::size_t min_size, std::size_t max_size) const;
  std::vector<Field> items(std::size_t exactly) const { return items(exactly, exactly); }

  // Scalars.
  double number() const;
  double number(double lo, double hi) const;
  // An exact integer in [lo, hi]: 3.0, 3e0 and out-of-range values are refused, never rounded
  // or wrapped.
  long long integer(long long lo, long long hi) const;
  int integer(int lo, int hi) const { return static_cast<int>(integer(static_cast<long long>(lo), static_cast<long long>(hi))); }
  bool boolean() const;
  const std::string& string() const;
  const std::string& one_of(std::initializer_list<std::string_view> allowed) const;
  const std::string& one_of(const std::vector<std::string>& allowed) const;
  const std::string& one_of(const std::vector<std::string_view>& allowed) const;

 private:
  std::string child(std::string_view key) const;

  const Json* value_;
  std::string source_;
  std::string path_;
};

}  // namespace zhf::io::json
