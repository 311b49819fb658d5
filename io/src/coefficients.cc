#include "zhf/io/coefficients.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/json.h"
#include "zhf/io/limits.h"
#include "zhf/io/numbers.h"
#include "zhf/runtime/limits.h"

namespace zhf::io {
namespace {

int order_of_count(size_t count) {
  for (int n = 1; n <= runtime::kMaxShOrder; ++n)
    if (static_cast<size_t>(n) * n == count) return n;
  return 0;
}

// Checks one vector's channels against the file's shape so far and appends them.
void add_vector(CoefficientFile& out, std::vector<std::vector<double>> channels, const std::string& where) {
  const size_t count = channels.front().size();
  for (const auto& c : channels)
    if (c.size() != count) throw InputError(where + ": channels differ in length");
  const int order = order_of_count(count);
  if (order == 0)
    throw InputError(where + ": " + std::to_string(count) + " coefficients per channel is not N^2 for an order N <= " +
                     std::to_string(runtime::kMaxShOrder));
  if (out.order == 0) {
    out.order = order;
    out.channels = static_cast<int>(channels.size());
  } else if (order != out.order) {
    throw InputError(where + ": order " + std::to_string(order) + " (" + std::to_string(count) +
                     " coefficients), but earlier vectors have order " + std::to_string(out.order));
  } else if (static_cast<int>(channels.size()) != out.channels) {
    throw InputError(where + ": " + std::to_string(channels.size()) + " channels, earlier vectors have " +
                     std::to_string(out.channels));
  }
  for (auto& c : channels) out.signals.push_back(std::move(c));
}

double checked(double x, const std::string& where) {
  if (!(std::abs(x) <= kMaxCoefficientMagnitude))
    throw InputError(where + ": " + runtime::format_number(x, 6) + " is beyond the largest coefficient magnitude, " + runtime::format_number(kMaxCoefficientMagnitude));
  return x;
}

CoefficientFile parse_json(const std::string& text, const std::string& source, int channels) {
  const json::Json root = json::parse(text, source);
  const json::Field top(root, source);
  top.expect(json::Kind::kArray);
  if (root.empty()) throw InputError(source + ": no coefficient vectors");
  CoefficientFile out;
  const std::vector<json::Field> vectors = top.items(1, root.size());
  for (size_t v = 0; v < vectors.size(); ++v) {
    const json::Field& vec = vectors[v];
    vec.expect(json::Kind::kArray);
    if (vec.value().empty()) vec.fail("must be a non-empty array");
    std::vector<std::vector<double>> parts;
    const bool multi = vec.value().front().is_array();
    for (const json::Field& part : multi ? vec.items(1, kMaxChannels) : std::vector<json::Field>{vec}) {
      parts.emplace_back();
      for (const json::Field& x : part.items(1, kMaxCoefficientCount)) parts.back().push_back(checked(x.number(), source + ": " + x.where()));
    }
    const std::string where = source + ": vector " + std::to_string(v);
    if (channels > 0 && static_cast<int>(parts.size()) != channels)
      throw InputError(where + ": " + std::to_string(parts.size()) + " channels, --channels says " + std::to_string(channels));
    add_vector(out, std::move(parts), where);
  }
  return out;
}

CoefficientFile parse_text(const std::string& text, const std::string& source, int channels) {
  if (channels <= 0) channels = 1;
  CoefficientFile out;
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const std::string where = source + ": line " + std::to_string(number);
    std::istringstream tokens(line);
    std::vector<double> values;
    std::string token;
    while (tokens >> token) {
      const ParsedNumber x = parse_number(token);
      if (!x.value) throw InputError(where + ": '" + excerpt(token) + "' " + x.problem);
      values.push_back(checked(*x.value, where));
    }
    if (values.size() % channels != 0)
      throw InputError(where + ": " + std::to_string(values.size()) + " numbers do not split into " + std::to_string(channels) + " channels");
    const size_t per = values.size() / channels;
    std::vector<std::vector<double>> parts;
    for (int c = 0; c < channels; ++c) parts.emplace_back(values.begin() + c * per, values.begin() + (c + 1) * per);
    add_vector(out, std::move(parts), where);
  }
  if (out.signals.empty()) throw InputError(source + ": no coefficient vectors");
  return out;
}

}  // namespace

CoefficientFile parse_coefficients(const std::string& text, const std::string& source, int channels) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) throw InputError(source + ": file is empty");
  return text[first] == '[' || text[first] == '{' ? parse_json(text, source, channels) : parse_text(text, source, channels);
}

CoefficientFile read_coefficients(const std::string& path, int channels) {
  return parse_coefficients(read_text_file(path, io::kMaxCoefficientBytes), path, channels);
}

}  // namespace zhf::io
