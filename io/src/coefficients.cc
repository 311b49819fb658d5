#include "zhf/io/coefficients.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "zhf/io/errors.h"
#include "zhf/io/files.h"

namespace zhf::io {
namespace {

int order_of_count(size_t count) {
  for (int n = 1; n <= kMaxCoefficientOrder; ++n)
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
                     std::to_string(kMaxCoefficientOrder));
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

double finite_number(const nlohmann::json& v, const std::string& where) {
  if (!v.is_number()) throw InputError(where + ": not a number");
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw InputError(where + ": not finite");
  return x;
}

CoefficientFile parse_json(const std::string& text, const std::string& source, int channels) {
  const nlohmann::json j = parse_json_text(text, source);
  if (!j.is_array()) throw InputError(source + ": must be an array of coefficient vectors");
  if (j.empty()) throw InputError(source + ": no coefficient vectors");
  CoefficientFile out;
  for (size_t v = 0; v < j.size(); ++v) {
    const std::string where = source + ": vector " + std::to_string(v);
    const nlohmann::json& vec = j[v];
    if (!vec.is_array() || vec.empty()) throw InputError(where + ": must be a non-empty array");
    std::vector<std::vector<double>> parts;
    if (vec.front().is_array()) {
      for (size_t c = 0; c < vec.size(); ++c) {
        if (!vec[c].is_array() || vec[c].empty()) throw InputError(where + ", channel " + std::to_string(c) + ": must be a non-empty array of numbers");
        parts.emplace_back();
        for (size_t i = 0; i < vec[c].size(); ++i)
          parts.back().push_back(finite_number(vec[c][i], where + ", channel " + std::to_string(c) + ", entry " + std::to_string(i)));
      }
    } else {
      parts.emplace_back();
      for (size_t i = 0; i < vec.size(); ++i) parts.back().push_back(finite_number(vec[i], where + ", entry " + std::to_string(i)));
    }
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
      char* end = nullptr;
      const double x = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0') throw InputError(where + ": '" + token + "' is not a number");
      if (!std::isfinite(x)) throw InputError(where + ": '" + token + "' is not finite");
      values.push_back(x);
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
  return parse_coefficients(read_text_file(path), path, channels);
}

}  // namespace zhf::io
