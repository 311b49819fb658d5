#include "zhf/io/rotation_text.h"

#include <cmath>
#include <cstdlib>
#include <vector>

#include "zhf/io/errors.h"

namespace zhf::io {
namespace {

std::vector<double> numbers(const std::string& text, size_t expected, const std::string& option) {
  std::vector<double> out;
  size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && (text[i] == ' ' || text[i] == ',' || text[i] == '\t')) ++i;
    if (i == text.size()) break;
    size_t j = i;
    while (j < text.size() && text[j] != ' ' && text[j] != ',' && text[j] != '\t') ++j;
    const std::string token = text.substr(i, j - i);
    char* end = nullptr;
    const double x = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0') throw InputError(option + ": '" + token + "' is not a number");
    if (!std::isfinite(x)) throw InputError(option + ": '" + token + "' is not finite");
    out.push_back(x);
    i = j;
  }
  if (out.size() != expected)
    throw InputError(option + ": expected " + std::to_string(expected) + " numbers, found " + std::to_string(out.size()));
  return out;
}

// Row-major rotation by angle about the unit axis u (Rodrigues).
std::array<double, 9> about(const double u[3], double angle) {
  const double c = std::cos(angle), s = std::sin(angle), t = 1 - c;
  return {t * u[0] * u[0] + c,        t * u[0] * u[1] - s * u[2], t * u[0] * u[2] + s * u[1],
          t * u[0] * u[1] + s * u[2], t * u[1] * u[1] + c,        t * u[1] * u[2] - s * u[0],
          t * u[0] * u[2] - s * u[1], t * u[1] * u[2] + s * u[0], t * u[2] * u[2] + c};
}

std::array<double, 9> product(const std::array<double, 9>& a, const std::array<double, 9>& b) {
  std::array<double, 9> out{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) out[3 * i + j] += a[3 * i + k] * b[3 * k + j];
  return out;
}

}  // namespace

std::array<double, 9> parse_rotation(const std::string& text, RotationForm form, const std::string& option) {
  switch (form) {
    case RotationForm::kMatrix: {
      const std::vector<double> v = numbers(text, 9, option);
      std::array<double, 9> out{};
      std::copy(v.begin(), v.end(), out.begin());
      return out;
    }
    case RotationForm::kZyz: {
      const std::vector<double> v = numbers(text, 3, option);
      const double z[3] = {0, 0, 1}, y[3] = {0, 1, 0};
      return product(product(about(z, v[0]), about(y, v[1])), about(z, v[2]));
    }
    case RotationForm::kAxisAngle: {
      const std::vector<double> v = numbers(text, 4, option);
      const double norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      if (!(norm > 0) || !std::isfinite(norm)) throw InputError(option + ": the axis (" + text + ") has no direction");
      const double u[3] = {v[0] / norm, v[1] / norm, v[2] / norm};
      return about(u, v[3]);
    }
  }
  return {};
}

}  // namespace zhf::io
