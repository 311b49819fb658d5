#include "zhf/frames/windows.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "zhf/frames/limits.h"
#include "zhf/frames/needlets.h"
#include "zhf/runtime/enum_names.h"
#include "zhf/tolerances/tolerances.h"

namespace zhf::frames {
namespace {

constexpr runtime::EnumName<WindowKind> kWindowNames[] = {
    {WindowKind::kStandard, "standard"}, {WindowKind::kSpline, "spline"}, {WindowKind::kMexican, "mexican"}};

void check(const Window& w) {
  check_dilation(w.dilation);
  if (w.kind == WindowKind::kMexican && (w.order < 1 || w.order > frames::kMaxMexicanOrder))
    throw std::invalid_argument("Mexican needlet order must be 1.." + std::to_string(frames::kMaxMexicanOrder) + " (got " + std::to_string(w.order) + ")");
}

// Cumulative centred cubic B-spline: F(s) = int_{-2}^{s} M, for s in [-2, 0] (F(s) = 1 - F(-s)
// beyond). M(s) = (2 - |s|)^3 / 6 on 1 <= |s| <= 2, (4 - 6 s^2 + 3 |s|^3) / 6 on |s| <= 1.
double spline_cumulative_left(double s) {
  if (s <= -1) return std::pow(s + 2, 4) / 24;
  return 1.0 / 24 + (4 * s - 2 * s * s * s - 0.75 * s * s * s * s + 2.75) / 6;
}

// phi(t) from the spline step, through the standard window's mapping (needlets.h).
double spline_phi(double t, double dilation) { return spline_step(phi_argument(t, dilation)); }

// Mexican: b^2 falls below kWindowNegligible of its peak outside [low, high] in x.
void mexican_support(int p, double& low, double& high) {
  const double peak = p * std::log(double(p)) - p;  // log b at x^2 = p
  auto excess = [&](double x) { return 2 * (2 * p * std::log(x) - x * x - peak) - std::log(zhf::tolerance::kWindowNegligible); };
  auto bisect = [&](double a, double b) {  // excess(a) and excess(b) of opposite signs
    for (int i = 0; i < 200; ++i) {
      const double m = (a + b) / 2;
      ((excess(m) > 0) == (excess(a) > 0) ? a : b) = m;
    }
    return (a + b) / 2;
  };
  low = bisect(std::numeric_limits<double>::min(), std::sqrt(double(p)));
  high = bisect(std::sqrt(double(p)), 1e3);
}

// The x = l / B^j where b may be non-negligible.
void support(const Window& w, double& low, double& high) {
  if (w.kind == WindowKind::kMexican) return mexican_support(w.order, low, high);
  low = 1 / w.dilation;
  high = w.dilation;
}

}  // namespace

bool parse_window_kind(const std::string& name, WindowKind& kind) { return runtime::parse_enum(kWindowNames, name, kind); }
const char* window_kind_name(WindowKind kind) { return runtime::enum_name(kWindowNames, kind); }

double spline_step(double u) {
  const double s = 2 * u;
  if (s <= -2) return 0;
  if (s >= 2) return 1;
  return s <= 0 ? spline_cumulative_left(s) : 1 - spline_cumulative_left(-s);
}

double window_value(const Window& w, double x) {
  check(w);
  switch (w.kind) {
    case WindowKind::kStandard: return needlet_window(x, w.dilation);
    case WindowKind::kSpline: return std::sqrt(std::max(0.0, spline_phi(x / w.dilation, w.dilation) - spline_phi(x, w.dilation)));
    case WindowKind::kMexican: return std::pow(x, 2 * w.order) * std::exp(-x * x);
  }
  return 0;
}

LevelRange levels_of_band(const Window& w, int l) {
  check(w);
  double low = 0, high = 0;
  support(w, low, high);
  const double log_b = std::log(w.dilation);
  return {int(std::floor(std::log(l / high) / log_b)), int(std::ceil(std::log(l / low) / log_b))};
}

BandRange bands_of_level(const Window& w, int j) {
  check(w);
  double low = 0, high = 0;
  support(w, low, high);
  const double scale = std::pow(w.dilation, j);
  return {std::max(1, int(std::floor(low * scale))), int(std::ceil(high * scale))};
}

std::vector<WindowValue> window_values(const Window& w, int lmax) {
  check(w);
  if (lmax < 0 || lmax > frames::kMaxNeedletBand)
    throw std::invalid_argument("lmax must be 0.." + std::to_string(frames::kMaxNeedletBand) + " (got " + std::to_string(lmax) + ")");
  std::vector<WindowValue> out;
  if (lmax == 0) return out;
  double low = 0, high = 0;
  support(w, low, high);
  const double floor_value = w.kind == WindowKind::kMexican ? std::sqrt(zhf::tolerance::kWindowNegligible) * window_value(w, std::sqrt(double(w.order))) : 0.0;
  for (int j = levels_of_band(w, 1).first; j <= levels_of_band(w, lmax).last; ++j) {
    const BandRange bands = bands_of_level(w, j);
    for (int l = bands.first; l <= std::min(lmax, bands.last); ++l) {
      const double b = window_value(w, l / std::pow(w.dilation, j));
      if (b > floor_value) out.push_back({j, l, b});
    }
  }
  return out;
}

double window_square_sum(const Window& w, int l) {
  const LevelRange levels = levels_of_band(w, l);
  double sum = 0;
  for (int j = levels.first; j <= levels.last; ++j) {
    const double b = window_value(w, l / std::pow(w.dilation, j));
    sum += b * b;
  }
  return sum;
}

double kernel_energy_outside(const Window& w, int j, double radius) {
  if (!(radius > 0 && radius <= runtime::kPi)) throw std::invalid_argument("cap radius must be in (0, pi]");
  const BandRange bands = bands_of_level(w, j);
  if (bands.last > frames::kMaxProfileBand)
    throw std::invalid_argument("level " + std::to_string(j) + " reaches band " + std::to_string(bands.last) + "; at most " + std::to_string(frames::kMaxProfileBand));
  std::vector<double> b(bands.last + 1, 0.0);
  for (int l = bands.first; l <= bands.last; ++l) b[l] = window_value(w, l / std::pow(w.dilation, j));
  const auto kernel = [&](double t) { return zonal_series(bands.first, bands.last, t, [&](int l) { return b[l]; }); };
  return localisation(kernel, bands.last, radius).outside_energy;
}

}  // namespace zhf::frames
