#include "zhf/io/json.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>
#include <utility>

#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/runtime/enum_names.h"

namespace zhf::io::json {
namespace {

constexpr runtime::EnumName<Kind> kKindNames[] = {{Kind::kNull, "null"},       {Kind::kBool, "a boolean"}, {Kind::kNumber, "a number"},
                                                   {Kind::kString, "a string"}, {Kind::kArray, "an array"}, {Kind::kObject, "an object"}};

const char* kind_name(Kind kind) { return runtime::enum_name(kKindNames, kind); }

// nlohmann's message after "parse error ": "at line L, column C: <what>; last read: '<token>'",
// perhaps followed by "; expected <what>", with the token (which may hold any bytes) cut to its
// last characters and escaped.
std::string parse_error_text(const std::string& what) {
  static constexpr std::string_view kPrefix = "parse error ";
  static constexpr std::string_view kLastRead = "; last read: '";
  static constexpr std::string_view kExpected = "'; expected ";
  const std::size_t at = what.find(kPrefix);
  const std::string text = at == std::string::npos ? what : what.substr(at + kPrefix.size());
  const std::size_t last = text.find(kLastRead);
  if (last == std::string::npos) return text;
  const std::size_t from = last + kLastRead.size();
  const std::size_t expected = text.rfind(kExpected);
  const std::size_t to = expected != std::string::npos && expected >= from ? expected : text.size() - 1;
  std::string token = text.substr(from, to > from ? to - from : 0);
  constexpr std::size_t kTokenTail = 16;
  if (token.size() > kTokenTail) token = token.substr(token.size() - kTokenTail);
  const std::string rest = to + 1 < text.size() ? text.substr(to + 1) : "";
  return text.substr(0, last) + " (after '" + excerpt(token) + "')" + rest;
}

// The document built from nlohmann's SAX events, with the limits, duplicate keys and NUL
// characters checked as each arrives: a refusal throws out of the parse, so nothing beyond a
// limit is built. It runs in time O(n log k) for n values and at most k keys an object: members
// are appended in file order without the linear search of nlohmann's ordered_map (whose emplace
// made the parse quadratic in the keys of an object), and each object's keys are sorted once when
// it closes to find a duplicate.
class Builder {
 public:
  Builder(const std::string& source, const Limits& limits) : source_(source), limits_(limits) {}

  Json take() { return std::move(root_); }

  bool null() { return add(Json(nullptr)); }
  bool boolean(bool value) { return add(Json(value)); }
  bool number_integer(Json::number_integer_t value) { return add(Json(value)); }
  bool number_unsigned(Json::number_unsigned_t value) { return add(Json(value)); }
  bool number_float(Json::number_float_t value, const std::string&) { return add(Json(value)); }
  bool string(std::string& value) {
    check_string(value);
    return add(Json(std::move(value)));
  }
  bool binary(Json::binary_t&) { fail("binary data"); }
  bool start_object(std::size_t) { return open(Json::object()); }
  bool start_array(std::size_t) { return open(Json::array()); }
  bool key(std::string& key) {
    check_string(key);
    if (++open_.back().keys > limits_.max_object_keys)
      fail("an object with more than " + std::to_string(limits_.max_object_keys) + " keys");
    key_ = std::move(key);
    return true;
  }
  bool end_array() {
    open_.pop_back();
    return true;
  }
  bool end_object() {
    const Json::object_t& members = open_.back().value->get_ref<const Json::object_t&>();
    std::vector<const std::string*> keys;
    keys.reserve(members.size());
    for (const auto& member : members) keys.push_back(&member.first);
    std::sort(keys.begin(), keys.end(), [](const std::string* a, const std::string* b) { return *a < *b; });
    for (std::size_t k = 1; k < keys.size(); ++k)
      if (*keys[k] == *keys[k - 1]) fail("the key '" + excerpt(*keys[k]) + "' appears twice");
    open_.pop_back();
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) {
    // The one range error of parsing: a number beyond a double ("number overflow parsing '1e400'").
    const std::string what = e.what();
    if (e.id == kNumberOverflow) {
      const std::size_t quote = what.find('\'');
      const std::string token = quote == std::string::npos ? what : what.substr(quote + 1, what.size() - quote - 2);
      throw InputError(source_ + ": not valid JSON: the number '" + excerpt(token) + "' is beyond the range of a double");
    }
    throw InputError(source_ + ": not valid JSON " + parse_error_text(what));
  }

 private:
  static constexpr int kNumberOverflow = 406;  // nlohmann's out_of_range.406
  struct Open {
    Json* value;
    std::size_t keys = 0;
  };

  [[noreturn]] void fail(const std::string& problem) const { throw InputError(source_ + ": not valid JSON: " + problem); }
  void count() {
    if (++values_ > limits_.max_values) fail("more than " + std::to_string(limits_.max_values) + " values");
  }
  void check_string(const std::string& s) const {
    if (s.size() > limits_.max_string_bytes) fail("a string longer than " + std::to_string(limits_.max_string_bytes) + " bytes");
    if (s.find('\0') != std::string::npos) fail("a NUL character (\\u0000) inside a string");
  }
  // Puts value where the document is at: the root, the open array's end or the open object's
  // last key. The open containers' addresses stay valid: nothing is added to a container while a
  // child of it is open.
  Json* place(Json&& value) {
    count();
    if (open_.empty()) {
      root_ = std::move(value);
      return &root_;
    }
    Json& into = *open_.back().value;
    if (into.is_array()) {
      Json::array_t& items = into.get_ref<Json::array_t&>();
      items.push_back(std::move(value));
      return &items.back();
    }
    auto& members = static_cast<std::vector<Json::object_t::value_type>&>(into.get_ref<Json::object_t&>());
    members.emplace_back(std::move(key_), std::move(value));
    return &members.back().second;
  }
  bool add(Json&& value) {
    place(std::move(value));
    return true;
  }
  bool open(Json&& container) {
    if (int(open_.size()) >= limits_.max_depth) fail("nested deeper than " + std::to_string(limits_.max_depth) + " levels");
    open_.push_back({place(std::move(container))});
    return true;
  }

  const std::string& source_;
  const Limits& limits_;
  Json root_;
  std::vector<Open> open_;  // the open arrays and objects, innermost last
  std::string key_;         // the open object's key awaiting its value
  std::size_t values_ = 0;
};

}  // namespace

Json parse(std::string_view text, const std::string& source, const Limits& limits) {
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) throw InputError(source + ": file is empty");
  Builder builder(source, limits);
  Json::sax_parse(text.begin(), text.end(), &builder);
  return builder.take();
}

Json read_file(const std::string& path, std::size_t max_bytes, const Limits& limits) {
  return parse(read_text_file(path, max_bytes), path, limits);
}

Kind kind_of(const Json& value) {
  switch (value.type()) {
    case Json::value_t::boolean: return Kind::kBool;
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float: return Kind::kNumber;
    case Json::value_t::string: return Kind::kString;
    case Json::value_t::array: return Kind::kArray;
    case Json::value_t::object: return Kind::kObject;
    default: return Kind::kNull;  // null; parsing makes no binary or discarded values
  }
}

Field::Field(const Json& value, std::string source, std::string path)
    : value_(&value), source_(std::move(source)), path_(std::move(path)) {}

std::string Field::where() const { return path_.empty() ? "top level" : path_; }

void Field::fail(const std::string& problem) const { throw InputError(source_ + ": " + where() + ": " + problem); }

void Field::expect(Kind kind) const {
  if (!is(kind)) fail(std::string("expected ") + kind_name(kind) + ", found " + kind_name(kind_of(*value_)));
}

std::optional<Field> Field::find(std::string_view key) const {
  expect(Kind::kObject);
  const auto it = value_->find(std::string(key));
  if (it == value_->end()) return std::nullopt;
  return Field(*it, source_, child(key));
}

Field Field::member(std::string_view key) const {
  std::optional<Field> f = find(key);
  if (!f) Field(*value_, source_, child(key)).fail("missing");
  return *f;
}

void Field::allow_only(std::initializer_list<std::string_view> keys) const {
  expect(Kind::kObject);
  for (const auto& [key, v] : value_->items()) {
    bool known = false;
    for (std::string_view k : keys) known = known || k == key;
    if (!known) Field(v, source_, child(key)).fail("unknown field");
  }
}

std::vector<Field> Field::items(std::size_t min_size, std::size_t max_size) const {
  expect(Kind::kArray);
  const std::size_t n = value_->size();
  if (n < min_size || n > max_size) {
    if (min_size == max_size) fail("expected " + std::to_string(min_size) + " entries, found " + std::to_string(n));
    fail("expected " + std::to_string(min_size) + " to " + std::to_string(max_size) + " entries, found " + std::to_string(n));
  }
  std::vector<Field> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) out.emplace_back((*value_)[i], source_, path_ + "[" + std::to_string(i) + "]");
  return out;
}

double Field::number() const {
  expect(Kind::kNumber);
  return value_->get<double>();  // parsing admits finite numbers only
}

double Field::number(double lo, double hi) const {
  const double x = number();
  if (!(x >= lo && x <= hi))
    fail("must be in [" + runtime::format_number(lo, 6) + ", " + runtime::format_number(hi, 6) + "] (got " + excerpt(value_->dump()) + ")");
  return x;
}

long long Field::integer(long long lo, long long hi) const {
  expect(Kind::kNumber);
  if (value_->is_number_float()) fail("expected an integer, found " + excerpt(value_->dump()));
  const bool in_range = value_->is_number_unsigned()
                            ? value_->get<std::uint64_t>() <= static_cast<std::uint64_t>(hi) && hi >= 0 &&
                                  static_cast<long long>(value_->get<std::uint64_t>()) >= lo
                            : value_->get<std::int64_t>() >= lo && value_->get<std::int64_t>() <= hi;
  if (!in_range) fail("must be " + std::to_string(lo) + ".." + std::to_string(hi) + " (got " + excerpt(value_->dump()) + ")");
  return value_->get<long long>();
}

bool Field::boolean() const {
  expect(Kind::kBool);
  return value_->get<bool>();
}

const std::string& Field::string() const {
  expect(Kind::kString);
  return value_->get_ref<const std::string&>();
}

const std::string& Field::one_of(std::initializer_list<std::string_view> allowed) const {
  return one_of(std::vector<std::string_view>(allowed));
}

const std::string& Field::one_of(const std::vector<std::string>& allowed) const {
  return one_of(std::vector<std::string_view>(allowed.begin(), allowed.end()));
}

const std::string& Field::one_of(const std::vector<std::string_view>& allowed) const {
  const std::string& s = string();
  std::string list;
  for (std::string_view a : allowed) {
    if (a == s) return s;
    list += (list.empty() ? "" : ", ") + std::string(a);
  }
  fail("'" + excerpt(s) + "' is not one of " + list);
}

std::string Field::child(std::string_view key) const {
  const std::string name = excerpt(key, 40);
  return path_.empty() ? name : path_ + "." + name;
}

}  // namespace zhf::io::json
