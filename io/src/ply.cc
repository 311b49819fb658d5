#include "zhf/io/ply.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <optional>
#include <sstream>

#include "zhf/io/errors.h"
#include "zhf/io/limits.h"
#include "zhf/io/numbers.h"

namespace zhf::io::ply {
namespace {

struct TypeName {
  std::string_view name;
  Type type;
};
constexpr TypeName kTypeNames[] = {
    {"char", Type::kInt8},     {"int8", Type::kInt8},       {"uchar", Type::kUint8},    {"uint8", Type::kUint8},
    {"short", Type::kInt16},   {"int16", Type::kInt16},     {"ushort", Type::kUint16},  {"uint16", Type::kUint16},
    {"int", Type::kInt32},     {"int32", Type::kInt32},     {"uint", Type::kUint32},    {"uint32", Type::kUint32},
    {"float", Type::kFloat32}, {"float32", Type::kFloat32}, {"double", Type::kFloat64}, {"float64", Type::kFloat64},
};

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

template <class T>
T load(const unsigned char* p) {
  T value;
  std::memcpy(&value, p, sizeof value);
  return value;
}

}  // namespace

namespace {

int find_property(const std::vector<Property>& properties, std::string_view name) {
  for (std::size_t i = 0; i < properties.size(); ++i)
    if (properties[i].name == name) return static_cast<int>(i);
  return -1;
}

}  // namespace

int Header::find(std::string_view name) const { return find_property(properties, name); }
int Element::find(std::string_view name) const { return find_property(properties, name); }

std::size_t type_size(Type type) {
  switch (type) {
    case Type::kInt8:
    case Type::kUint8: return 1;
    case Type::kInt16:
    case Type::kUint16: return 2;
    case Type::kInt32:
    case Type::kUint32:
    case Type::kFloat32: return 4;
    case Type::kFloat64: return 8;
  }
  return 0;
}

bool is_float(Type type) { return type == Type::kFloat32 || type == Type::kFloat64; }

namespace {

// Both readers: `any_elements` false keeps a splat file's rule of one element, "vertex".
Header parse_header(std::istream& in, const std::string& source, bool any_elements) {
  Header header;
  bool format_seen = false;
  std::size_t properties = 0;
  for (int number = 1;; ++number) {
    std::string line;
    // A line ends at '\n'; the header's size is bounded before any line is kept.
    for (char c; in.get(c) && c != '\n';) {
      line += c;
      if (header.text.size() + line.size() > kMaxPlyHeaderBytes)
        throw InputError(source + ": the header is longer than " + std::to_string(kMaxPlyHeaderBytes) + " bytes");
    }
    if (!in) throw InputError(source + ": the header ends before end_header");
    header.text += line + "\n";
    const std::string where = source + ": header line " + std::to_string(number);
    if (!line.empty() && line.back() == '\r') throw InputError(where + ": a CR line ending (zhf reads LF-terminated PLY only)");
    const std::vector<std::string> w = words(line);
    if (number == 1) {
      if (line != "ply") throw InputError(source + ": not a PLY file (it does not start with \"ply\")");
      continue;
    }
    if (w.empty()) throw InputError(where + ": an empty line");
    const std::string& keyword = w[0];
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "end_header") {
      if (w.size() != 1) throw InputError(where + ": end_header followed by '" + excerpt(line) + "'");
      break;
    }
    if (keyword == "format") {
      if (format_seen || w.size() != 3 || w[2] != "1.0") throw InputError(where + ": expected 'format <kind> 1.0' once");
      if (w[1] == "ascii") {
        header.format = Format::kAscii;
      } else if (w[1] == "binary_little_endian") {
        header.format = Format::kBinaryLittleEndian;
      } else if (w[1] == "binary_big_endian") {
        throw InputError(where + ": big-endian PLY is not supported (convert it to little-endian)");
      } else {
        throw InputError(where + ": unknown format '" + excerpt(w[1]) + "'");
      }
      format_seen = true;
    } else if (keyword == "element") {
      if (!any_elements) {
        if (!header.elements.empty())
          throw InputError(where + ": a second element ('" + excerpt(line) + "'); a splat file has vertices only");
        if (w.size() != 3 || w[1] != "vertex") throw InputError(where + ": expected 'element vertex <count>'");
      }
      if (w.size() != 3) throw InputError(where + ": expected 'element <name> <count>'");
      if (header.elements.size() == kMaxPlyElements)
        throw InputError(where + ": more than " + std::to_string(kMaxPlyElements) + " elements");
      for (const Element& e : header.elements)
        if (e.name == w[1]) throw InputError(where + ": element '" + excerpt(w[1]) + "' appears twice");
      const std::string& count = w[2];
      if (count.empty() || count.size() > kMaxPlyCountDigits || count.find_first_not_of("0123456789") != std::string::npos ||
          std::stoull(count) > kMaxPlyVertices)
        throw InputError(where + ": the " + (any_elements ? "'" + excerpt(w[1]) + "'" : std::string("vertex")) + " count '" +
                         excerpt(count) + "' is not a count up to 2^31");
      header.elements.push_back({w[1], std::stoull(count), {}, 0});
    } else if (keyword == "property") {
      if (header.elements.empty()) throw InputError(where + ": a property before 'element vertex'");
      if (w.size() >= 2 && w[1] == "list") throw InputError(where + ": list properties are not supported in a splat file");
      if (w.size() != 3) throw InputError(where + ": expected 'property <type> <name>'");
      if (properties == kMaxPlyProperties) throw InputError(where + ": more than " + std::to_string(kMaxPlyProperties) + " properties");
      const TypeName* type = nullptr;
      for (const TypeName& t : kTypeNames)
        if (t.name == w[1]) type = &t;
      if (!type) throw InputError(where + ": unknown property type '" + excerpt(w[1]) + "'");
      Element& element = header.elements.back();
      if (element.find(w[2]) >= 0) throw InputError(where + ": property '" + excerpt(w[2]) + "' appears twice");
      element.properties.push_back({w[2], type->type, element.record_bytes});
      element.record_bytes += type_size(type->type);
      ++properties;
    } else {
      throw InputError(where + ": unknown header line '" + excerpt(line) + "'");
    }
  }
  if (!format_seen) throw InputError(source + ": the header has no format line");
  for (const Element& e : header.elements)
    if (e.properties.empty()) throw InputError(source + ": element '" + excerpt(e.name) + "' has no properties");
  for (const Element& e : header.elements)
    if (e.name == "vertex") {
      header.vertices = e.count;
      header.properties = e.properties;
      header.record_bytes = e.record_bytes;
    }
  if (!any_elements && header.properties.empty()) throw InputError(source + ": the header has no vertex element with properties");
  if (any_elements && header.elements.empty()) throw InputError(source + ": the header has no element");
  return header;
}

}  // namespace

Header read_header(std::istream& in, const std::string& source) { return parse_header(in, source, false); }

Header read_header_elements(std::istream& in, const std::string& source) { return parse_header(in, source, true); }

double read_binary(const unsigned char* record, const Property& property) {
  const unsigned char* p = record + property.offset;
  switch (property.type) {
    case Type::kInt8: return load<std::int8_t>(p);
    case Type::kUint8: return load<std::uint8_t>(p);
    case Type::kInt16: return load<std::int16_t>(p);
    case Type::kUint16: return load<std::uint16_t>(p);
    case Type::kInt32: return load<std::int32_t>(p);
    case Type::kUint32: return load<std::uint32_t>(p);
    case Type::kFloat32: return load<float>(p);
    case Type::kFloat64: return load<double>(p);
  }
  return 0;
}

void write_binary(unsigned char* record, const Property& property, double value) {
  unsigned char* p = record + property.offset;
  if (property.type == Type::kFloat32) {
    const float f = static_cast<float>(value);
    std::memcpy(p, &f, sizeof f);
  } else {
    std::memcpy(p, &value, sizeof value);
  }
}

std::string_view read_ascii_line(std::istream& in, std::vector<char>& buffer, const std::string& source, std::uint64_t vertex,
                                 std::uint64_t vertices) {
  buffer.resize(io::kMaxPlyAsciiLine + 2);
  in.getline(buffer.data(), std::streamsize(buffer.size()));
  if (in.fail() && !in.eof())
    throw InputError(source + ": splat " + std::to_string(vertex) + ": a line longer than " + std::to_string(io::kMaxPlyAsciiLine) + " bytes");
  if (in.gcount() == 0 && in.eof())
    throw InputError(source + ": truncated: the data ends before splat " + std::to_string(vertex) + " of " + std::to_string(vertices));
  return std::string_view(buffer.data());
}

std::vector<std::string_view> split_ascii(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    if (i == line.size()) break;
    std::size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
    tokens.push_back(line.substr(i, j - i));
    i = j;
  }
  return tokens;
}

namespace {

// A token of the property's type as a double: floats strictly (finite), integers in range.
std::optional<double> parse_token(std::string_view token, Type type, std::string& problem) {
  if (is_float(type)) {
    const ParsedNumber x = parse_number(token);
    if (!x.value) {
      problem = x.problem;
      return std::nullopt;
    }
    if (type == Type::kFloat64) return x.value;
    // A float property holds a float: the text's nearest, as a binary file would store it.
    const float single = static_cast<float>(*x.value);
    if (!std::isfinite(single)) {
      problem = "is beyond the range of float";
      return std::nullopt;
    }
    return double(single);
  }
  long long value = 0;
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  const long long low = type == Type::kInt8 ? -128 : type == Type::kInt16 ? -32768 : type == Type::kInt32 ? -2147483648LL : 0;
  const long long high = type == Type::kInt8 ? 127 : type == Type::kUint8 ? 255 : type == Type::kInt16 ? 32767
                         : type == Type::kUint16 ? 65535 : type == Type::kInt32 ? 2147483647LL : 4294967295LL;
  if (error != std::errc() || end != token.data() + token.size() || value < low || value > high) {
    problem = "is not an integer of the property's type";
    return std::nullopt;
  }
  return double(value);
}

}  // namespace

bool parse_ascii(const std::vector<std::string_view>& tokens, const Header& header, double* values) {
  if (tokens.size() != header.properties.size()) return false;
  std::string problem;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const std::optional<double> x = parse_token(tokens[i], header.properties[i].type, problem);
    if (!x) return false;
    values[i] = *x;
  }
  return true;
}

void parse_ascii_or_throw(std::string_view line, const Header& header, const std::string& source, std::uint64_t vertex, double* values) {
  const std::vector<std::string_view> tokens = split_ascii(line);
  const std::string at = source + ": splat " + std::to_string(vertex) + ": ";
  if (tokens.size() != header.properties.size())
    throw InputError(at + std::to_string(tokens.size()) + " numbers, the header has " + std::to_string(header.properties.size()) + " properties");
  std::string problem;
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const std::optional<double> x = parse_token(tokens[i], header.properties[i].type, problem);
    if (!x) throw InputError(at + "property " + header.properties[i].name + ": '" + excerpt(tokens[i]) + "' " + problem);
    values[i] = *x;
  }
}

void check_ascii_end(std::istream& in, const std::string& source) {
  for (char c; in.get(c);)
    if (c != ' ' && c != '\t' && c != '\n') throw InputError(source + ": data after the last splat");
}

}  // namespace zhf::io::ply
