#include "format_io.h"

#include <cerrno>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "zhf/io/errors.h"

namespace zhf::splat {

std::ifstream open_input(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw io::InputError(path + ": cannot open: " + std::strerror(errno));
  return file;
}

std::uint64_t regular_file_size(const std::string& path, const char* why) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw io::InputError(path + ": not a regular file (" + why + ")");
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) throw io::InputError(path + ": cannot read its size: " + ec.message());
  return size;
}

std::string where(const std::string& path, std::uint64_t splat, const std::string& field) {
  return path + ": splat " + std::to_string(splat) + ": " + field;
}

float clamped_float(double value, std::uint64_t& clamped) {
  constexpr double kMax = std::numeric_limits<float>::max();
  if (std::abs(value) > kMax) {
    ++clamped;
    return static_cast<float>(std::copysign(kMax, value));
  }
  return static_cast<float>(value);
}

std::uint32_t clamped_round(double x, std::uint32_t max, std::uint64_t& clamped) {
  const double r = std::nearbyint(x);
  if (r < 0 || r > max) {
    ++clamped;
    return r < 0 ? 0 : max;
  }
  return static_cast<std::uint32_t>(r);
}

// About x (y, z -> -y, -z): cos(m phi) terms (-1)^(l + m), sin(|m| phi) terms -(-1)^(l + |m|).
// About z (phi -> phi + pi): (-1)^m for both.
const std::array<double, kMaxRestPerChannel>& half_turn_signs(Axis axis) {
  static const auto make = [](Axis about) {
    std::array<double, kMaxRestPerChannel> s{};
    for (int k = 0; k < kMaxRestPerChannel; ++k) {
      const int l = Canonical::band(k), m = k + 1 - l * (l + 1);
      const double odd_m = std::abs(m) % 2 == 0 ? 1 : -1;
      if (about == Axis::kZ) s[k] = odd_m;
      else s[k] = (m >= 0 ? 1 : -1) * ((l + std::abs(m)) % 2 == 0 ? 1 : -1);
    }
    return s;
  };
  static const std::array<double, kMaxRestPerChannel> about_x = make(Axis::kX), about_z = make(Axis::kZ);
  return axis == Axis::kX ? about_x : about_z;
}

double sigmoid(double x) { return 1 / (1 + std::exp(-x)); }
double logit(double p) { return std::log(p / (1 - p)); }

double opacity_of_alpha(double alpha) {
  constexpr double kAlphaMargin = 1e-6;  // an input, not a tolerance: splat-transform's rule
  return logit(std::clamp(alpha, kAlphaMargin, 1 - kAlphaMargin));
}

}  // namespace zhf::splat
