// The runtime's JSON reader, for the lobe tables it reads (table_io.h) with the standard library
// alone. The tools read every other JSON file through nlohmann-json (io/json.h), to the same rules.
//
// Strict RFC 8259: no NaN or Infinity tokens, no comments, no trailing commas or characters,
// control characters and lone surrogates refused, \u escapes decoded to UTF-8, duplicate keys
// refused. Limits (nesting depth, value count, string and number length) are checked while
// parsing, so hostile input is refused in bounded time and memory. Numbers are parsed exactly
// (std::from_chars); a number's token is kept so integers convert without rounding or wrapping.
//
// Field reads name what is wrong: "<source>: <path>: <problem>", e.g.
// "scene.json: signals[1].channels: must be 1..4 (got 7)". Every error is a runtime::InputError.
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "zhf/runtime/enum_names.h"
#include "zhf/runtime/errors.h"
#include "zhf/runtime/limits.h"

namespace zhf::runtime::json {

// The bounds of one parse (runtime/limits.h says what each is).
struct Limits {
  int max_depth = kMaxJsonDepth;
  std::size_t max_values = kMaxJsonValues;
  std::size_t max_string_bytes = kMaxJsonStringBytes;
  std::size_t max_number_chars = kMaxJsonNumberChars;
  std::size_t max_object_keys = kMaxJsonObjectKeys;
};

struct Value {
  enum class Kind { kNull, kBool, kNumber, kString, kArray, kObject };
  Value() = default;
  explicit Value(Kind k) : kind(k) {}

  Kind kind = Kind::kNull;
  bool boolean = false;
  double number = 0;
  bool integral = false;  // a number token without fraction or exponent
  std::string text;       // a string's contents, or a number's token
  std::vector<Value> items;                            // array
  std::vector<std::pair<std::string, Value>> members;  // object, in file order, keys unique

  const Value* find(std::string_view key) const {
    for (const auto& [k, v] : members)
      if (k == key) return &v;
    return nullptr;
  }
};

// A value as compact JSON text (members in file order, numbers as their tokens): what a reader
// keeps of a part it carries without interpreting, such as a lobe table's provenance.
inline void append_compact(const Value& v, std::string& out) {
  switch (v.kind) {
    case Value::Kind::kNull: out += "null"; return;
    case Value::Kind::kBool: out += v.boolean ? "true" : "false"; return;
    case Value::Kind::kNumber: out += v.text; return;
    case Value::Kind::kString:
      out += '"';
      for (const char c : v.text) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\') {
          out += '\\';
          out += c;
        } else if (u < 0x20) {
          char escape[8];
          std::snprintf(escape, sizeof escape, "\\u%04x", u);
          out += escape;
        } else {
          out += c;
        }
      }
      out += '"';
      return;
    case Value::Kind::kArray:
      out += '[';
      for (std::size_t i = 0; i < v.items.size(); ++i) {
        if (i) out += ',';
        append_compact(v.items[i], out);
      }
      out += ']';
      return;
    case Value::Kind::kObject:
      out += '{';
      for (std::size_t i = 0; i < v.members.size(); ++i) {
        if (i) out += ',';
        Value key{Value::Kind::kString};
        key.text = v.members[i].first;
        append_compact(key, out);
        out += ':';
        append_compact(v.members[i].second, out);
      }
      out += '}';
      return;
  }
}
inline std::string compact_text(const Value& v) {
  std::string out;
  append_compact(v, out);
  return out;
}

inline constexpr EnumName<Value::Kind> kKindNames[] = {
    {Value::Kind::kNull, "null"},       {Value::Kind::kBool, "a boolean"}, {Value::Kind::kNumber, "a number"},
    {Value::Kind::kString, "a string"}, {Value::Kind::kArray, "an array"}, {Value::Kind::kObject, "an object"}};

inline const char* kind_name(Value::Kind kind) { return enum_name(kKindNames, kind); }

namespace detail {

class Parser {
 public:
  Parser(std::string_view text, const std::string& source, const Limits& limits)
      : s_(text), source_(source), limits_(limits) {}

  Value parse() {
    skip_space();
    if (i_ == s_.size()) throw InputError(source_ + ": file is empty");
    Value v = value(0);
    skip_space();
    if (i_ != s_.size()) fail("unexpected characters after the value");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    std::size_t line = 1, column = 1;
    for (std::size_t k = 0; k < i_ && k < s_.size(); ++k) {
      if (s_[k] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    std::string message = source_ + ": not valid JSON at line " + std::to_string(line) + ", column " +
                          std::to_string(column) + ": " + what;
    if (i_ < s_.size()) message += " (at '" + excerpt(s_.substr(i_), 16) + "')";
    throw InputError(message);
  }

  void skip_space() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\n' || s_[i_] == '\t' || s_[i_] == '\r')) ++i_;
  }
  bool take(char c) {
    skip_space();
    if (i_ < s_.size() && s_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }
  void expect(char c, const char* what) {
    if (!take(c)) fail(std::string("expected ") + what);
  }
  bool literal(std::string_view word) {
    if (s_.substr(i_, word.size()) != word) return false;
    i_ += word.size();
    return true;
  }

  Value value(int depth) {
    if (++count_ > limits_.max_values) fail("more than " + std::to_string(limits_.max_values) + " values");
    skip_space();
    if (i_ >= s_.size()) fail("unexpected end of the file");
    Value v;
    const char c = s_[i_];
    if (c == '{' || c == '[') {
      if (depth >= limits_.max_depth) fail("nested deeper than " + std::to_string(limits_.max_depth) + " levels");
      ++i_;
      if (c == '{') {
        v.kind = Value::Kind::kObject;
        if (take('}')) return v;
        std::vector<std::size_t> key_at;  // where each key starts, for a duplicate's message
        do {
          skip_space();
          if (i_ >= s_.size() || s_[i_] != '"') fail("expected a key in quotes");
          if (v.members.size() == limits_.max_object_keys)
            fail("an object with more than " + std::to_string(limits_.max_object_keys) + " keys");
          key_at.push_back(i_);
          std::string key = string();
          expect(':', "':' after a key");
          v.members.emplace_back(std::move(key), value(depth + 1));
        } while (take(','));
        expect('}', "',' or '}'");
        refuse_duplicate_keys(v, key_at);
      } else {
        v.kind = Value::Kind::kArray;
        if (take(']')) return v;
        do v.items.push_back(value(depth + 1));
        while (take(','));
        expect(']', "',' or ']'");
      }
    } else if (c == '"') {
      v.kind = Value::Kind::kString;
      v.text = string();
    } else if (literal("true")) {
      v.kind = Value::Kind::kBool;
      v.boolean = true;
    } else if (literal("false")) {
      v.kind = Value::Kind::kBool;
    } else if (literal("null")) {
      v.kind = Value::Kind::kNull;
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      number(v);
    } else if (c == 'N' || c == 'I' || c == 'n' || c == 'i') {
      fail("NaN and Infinity are not JSON numbers");
    } else {
      fail("unexpected character");
    }
    return v;
  }

  // The keys of a complete object sorted once (k log k, where a search per key was quadratic): a
  // duplicate is named at its second place in the file.
  void refuse_duplicate_keys(const Value& object, const std::vector<std::size_t>& key_at) {
    std::vector<std::size_t> order(object.members.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    const auto key = [&](std::size_t k) -> const std::string& { return object.members[k].first; };
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key(a) != key(b) ? key(a) < key(b) : a < b; });
    for (std::size_t k = 1; k < order.size(); ++k)
      if (key(order[k]) == key(order[k - 1])) {
        i_ = key_at[order[k]];
        fail("the key '" + excerpt(key(order[k])) + "' appears twice");
      }
  }

  // -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?
  void number(Value& v) {
    const std::size_t start = i_;
    auto digits = [&] {
      const std::size_t from = i_;
      while (i_ < s_.size() && s_[i_] >= '0' && s_[i_] <= '9') ++i_;
      return i_ > from;
    };
    if (s_[i_] == '-') ++i_;
    if (i_ < s_.size() && s_[i_] == '0') {
      ++i_;
    } else if (!digits()) {
      fail("expected digits");
    }
    bool integral = true;
    if (i_ < s_.size() && s_[i_] == '.') {
      ++i_;
      integral = false;
      if (!digits()) fail("expected digits after '.'");
    }
    if (i_ < s_.size() && (s_[i_] == 'e' || s_[i_] == 'E')) {
      ++i_;
      integral = false;
      if (i_ < s_.size() && (s_[i_] == '+' || s_[i_] == '-')) ++i_;
      if (!digits()) fail("expected digits in the exponent");
    }
    const std::string_view token = s_.substr(start, i_ - start);
    if (token.size() > limits_.max_number_chars) {
      i_ = start;
      fail("a number longer than " + std::to_string(limits_.max_number_chars) + " characters");
    }
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), v.number);
    if (error == std::errc::result_out_of_range) {
      // Within max_number_chars only an exponent leaves a double's range: below it the value
      // is zero, above it there is no double.
      const std::size_t e = token.find_first_of("eE");
      if (e == std::string_view::npos || token[e + 1] != '-') {
        i_ = start;
        fail("the number is beyond the range of a double");
      }
      v.number = token[0] == '-' ? -0.0 : 0.0;
    }
    v.kind = Value::Kind::kNumber;
    v.integral = integral;
    v.text = std::string(token);
  }

  unsigned hex4() {
    if (i_ + 4 > s_.size()) fail("a \\u escape needs four hex digits");
    unsigned value = 0;
    for (int k = 0; k < 4; ++k) {
      const char h = s_[i_++];
      value <<= 4;
      if (h >= '0' && h <= '9') value |= unsigned(h - '0');
      else if (h >= 'a' && h <= 'f') value |= unsigned(h - 'a' + 10);
      else if (h >= 'A' && h <= 'F') value |= unsigned(h - 'A' + 10);
      else fail("a \\u escape needs four hex digits");
    }
    return value;
  }

  static void append_utf8(std::string& out, unsigned code) {
    if (code < 0x80) {
      out += static_cast<char>(code);
    } else if (code < 0x800) {
      out += static_cast<char>(0xc0 | (code >> 6));
      out += static_cast<char>(0x80 | (code & 0x3f));
    } else if (code < 0x10000) {
      out += static_cast<char>(0xe0 | (code >> 12));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (code & 0x3f));
    } else {
      out += static_cast<char>(0xf0 | (code >> 18));
      out += static_cast<char>(0x80 | ((code >> 12) & 0x3f));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (code & 0x3f));
    }
  }

  std::string string() {
    ++i_;  // the opening quote
    std::string out;
    while (true) {
      if (i_ >= s_.size()) fail("unterminated string");
      if (out.size() > limits_.max_string_bytes) fail("a string longer than " + std::to_string(limits_.max_string_bytes) + " bytes");
      const unsigned char c = static_cast<unsigned char>(s_[i_]);
      if (c == '"') {
        ++i_;
        return out;
      }
      if (c < 0x20) fail("a control character inside a string");
      ++i_;
      if (c != '\\') {
        out += static_cast<char>(c);
        continue;
      }
      if (i_ >= s_.size()) fail("unterminated escape");
      const char e = s_[i_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          unsigned code = hex4();
          if (code >= 0xdc00 && code <= 0xdfff) fail("a lone low surrogate in a \\u escape");
          if (code >= 0xd800 && code <= 0xdbff) {
            if (!literal("\\u")) fail("a high surrogate without its low half");
            const unsigned low = hex4();
            if (low < 0xdc00 || low > 0xdfff) fail("a high surrogate without its low half");
            code = 0x10000 + ((code - 0xd800) << 10) + (low - 0xdc00);
          }
          if (code == 0) fail("a NUL character (\\u0000) inside a string");
          append_utf8(out, code);
          break;
        }
        default:
          --i_;
          fail("an unknown escape");
      }
    }
  }

  std::string_view s_;
  const std::string& source_;
  const Limits& limits_;
  std::size_t i_ = 0;
  std::size_t count_ = 0;
};


}  // namespace detail

// Parses a whole document; source names it in errors.
inline Value parse(std::string_view text, const std::string& source, const Limits& limits = {}) {
  return detail::Parser(text, source, limits).parse();
}

// A value and the path that names it: every read checks the value's type and range and, when
// they are wrong, throws InputError "<source>: <path>: <problem>".
class Field {
 public:
  Field(const Value& value, std::string source, std::string path = {})
      : value_(&value), source_(std::move(source)), path_(std::move(path)) {}

  const Value& value() const { return *value_; }
  // "lobes[3].xyz", or "top level".
  std::string where() const { return path_.empty() ? "top level" : path_; }

  [[noreturn]] void fail(const std::string& problem) const { throw InputError(source_ + ": " + where() + ": " + problem); }

  void expect(Value::Kind kind) const {
    if (value_->kind != kind) fail(std::string("expected ") + kind_name(kind) + ", found " + kind_name(value_->kind));
  }

  // Objects.
  std::optional<Field> find(std::string_view key) const {
    expect(Value::Kind::kObject);
    const Value* v = value_->find(key);
    if (!v) return std::nullopt;
    return Field(*v, source_, child(key));
  }
  Field member(std::string_view key) const {
    std::optional<Field> f = find(key);
    if (!f) Field(*value_, source_, child(key)).fail("missing");
    return *f;
  }
  // Refuses keys outside the list (a typo is an error, not a silent default).
  void allow_only(std::initializer_list<std::string_view> keys) const {
    expect(Value::Kind::kObject);
    for (const auto& [key, v] : value_->members) {
      bool known = false;
      for (std::string_view k : keys) known = known || k == key;
      if (!known) Field(v, source_, child(key)).fail("unknown field");
    }
  }

  // Arrays: the items, after checking the length.
  std::vector<Field> items(std::size_t min_size, std::size_t max_size) const {
    expect(Value::Kind::kArray);
    const std::size_t n = value_->items.size();
    if (n < min_size || n > max_size) {
      if (min_size == max_size) fail("expected " + std::to_string(min_size) + " entries, found " + std::to_string(n));
      fail("expected " + std::to_string(min_size) + " to " + std::to_string(max_size) + " entries, found " + std::to_string(n));
    }
    std::vector<Field> out;
    out.reserve(n);
    for (std::size_t i = 0; i < n; ++i) out.emplace_back(value_->items[i], source_, path_ + "[" + std::to_string(i) + "]");
    return out;
  }
  std::vector<Field> items(std::size_t exactly) const { return items(exactly, exactly); }

  // Scalars.
  double number() const {
    expect(Value::Kind::kNumber);
    return value_->number;  // the parser admits finite numbers only
  }
  double number(double lo, double hi) const {
    const double x = number();
    if (!(x >= lo && x <= hi))
      fail("must be in [" + format_number(lo, 6) + ", " + format_number(hi, 6) + "] (got " + excerpt(value_->text) + ")");
    return x;
  }
  // An exact integer in [lo, hi]: "3.0", "3e0" and out-of-range values are refused, never
  // rounded or wrapped.
  long long integer(long long lo, long long hi) const {
    expect(Value::Kind::kNumber);
    long long x = 0;
    const std::string& t = value_->text;
    const auto [end, error] = std::from_chars(t.data(), t.data() + t.size(), x);
    if (!value_->integral || error == std::errc::invalid_argument) fail("expected an integer, found " + excerpt(t));
    if (error == std::errc::result_out_of_range || x < lo || x > hi)
      fail("must be " + std::to_string(lo) + ".." + std::to_string(hi) + " (got " + excerpt(t) + ")");
    return x;
  }
  int integer(int lo, int hi) const { return static_cast<int>(integer(static_cast<long long>(lo), static_cast<long long>(hi))); }
  bool boolean() const {
    expect(Value::Kind::kBool);
    return value_->boolean;
  }
  const std::string& string() const {
    expect(Value::Kind::kString);
    return value_->text;
  }

 private:
  std::string child(std::string_view key) const {
    const std::string name = excerpt(key, 40);
    return path_.empty() ? name : path_ + "." + name;
  }

  const Value* value_;
  std::string source_;
  std::string path_;
};

}  // namespace zhf::runtime::json
