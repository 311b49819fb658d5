#include "zhf/frames/needlets.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>

#include "zhf/frames/limits.h"
#include "zhf/frames/windows.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"

namespace zhf::frames {
namespace {

double bump(double t) { return std::abs(t) < 1 ? std::exp(-1 / ((1 - t) * (1 + t))) : 0.0; }

// Gauss-Kronrod 7-15 on [a, b]: the 15-point estimate, and its difference from the 7-point one.
void kronrod(double a, double b, double& estimate, double& error) {
  static const double x[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                              0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                              0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                              0.207784955007898467600689403773245, 0.0};
  static const double wk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                               0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                               0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                               0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
  static const double wg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                               0.381830050505118944950369775488975, 0.417959183673469387755102040816327};
  const double c = (a + b) / 2, h = (b - a) / 2;
  double k = wk[7] * bump(c), g = wg[3] * bump(c);
  for (int i = 0; i < 7; ++i) {
    const double pair = bump(c - h * x[i]) + bump(c + h * x[i]);
    k += wk[i] * pair;
    if (i % 2) g += wg[i / 2] * pair;
  }
  estimate = k * h;
  error = std::abs((k - g) * h);
}

// Adaptive halving to an absolute tolerance, split evenly between the halves; a panel whose
// error estimate is down to the rounding of its own value is done.
double integrate_to(double a, double b, double tolerance, int depth) {
  double whole = 0, error = 0;
  kronrod(a, b, whole, error);
  if (error <= tolerance || error <= zhf::tolerance::kKronrodRounding * std::abs(whole) || depth >= 40) return whole;
  const double m = (a + b) / 2;
  return integrate_to(a, m, tolerance / 2, depth + 1) + integrate_to(m, b, tolerance / 2, depth + 1);
}

// int_a^b bump to kKronrodRelative of its own value, however small it is (a window's tail).
double integrate(double a, double b) {
  double whole = 0, error = 0;
  kronrod(a, b, whole, error);
  return integrate_to(a, b, zhf::tolerance::kKronrodRelative * std::abs(whole), 0);
}

}  // namespace

void check_dilation(double dilation) {
  if (!(dilation >= frames::kMinDilation && dilation <= frames::kMaxDilation))
    throw std::invalid_argument("B must be in [" + std::to_string(frames::kMinDilation).substr(0, 4) + ", " + std::to_string(int(frames::kMaxDilation)) +
                                "] (got " + std::to_string(dilation) + ")");
}

double bump_integral() {
  static const double value = integrate(-1, 0) + integrate(0, 1);
  return value;
}

double needlet_psi(double u) {
  if (u <= -1) return 0;
  if (u >= 1) return 1;
  // The smaller tail integrated: psi(u) = 1 - psi(-u), so the result is accurate near both ends.
  if (u > 0) return 1 - integrate(u, 1) / bump_integral();
  return integrate(-1, u) / bump_integral();
}

double phi_argument(double t, double dilation) {
  if (t <= 1 / dilation) return 1;
  if (t > 1) return -1;
  return 1 - 2 * dilation / (dilation - 1) * (t - 1 / dilation);
}

double needlet_phi(double t, double dilation) {
  check_dilation(dilation);
  return needlet_psi(phi_argument(t, dilation));
}

double needlet_window(double x, double dilation) {
  check_dilation(dilation);
  // b^2 = phi(x / B) - phi(x) = psi(u(x / B)) - psi(u(x)): one integral of the bump between the
  // two arguments, so a small weight keeps its relative precision (the difference of two values
  // near 1 would keep only its absolute precision, ~1e-16, and lose a small b^2's digits).
  const double lo = phi_argument(x, dilation), hi = phi_argument(x / dilation, dilation);
  if (!(hi > lo)) return 0.0;
  return std::sqrt(integrate(lo, hi) / bump_integral());
}

std::vector<WindowValue> needlet_windows(double dilation, int lmax) { return window_values(Window{WindowKind::kStandard, dilation, 1}, lmax); }

// ---- Cubatures ----------------------------------------------------------------------------------

namespace {

// Every product of two functions of bands <= lmax integrated exactly: the cubature the level needs.
void check_cubature(const Cubature& c, int degree) {
  if (c.degree < degree || c.points.empty() || c.points.size() != c.weights.size())
    throw std::invalid_argument("cubature '" + c.name + "' is exact to degree " + std::to_string(c.degree) + ", " +
                                std::to_string(degree) + " needed");
}

double dot(const Point& a, const Point& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double clamp_dot(double t) { return std::min(1.0, std::max(-1.0, t)); }

Point rotate_point(const runtime::Matrix3& r, const Point& p) {
  return {r[0] * p[0] + r[1] * p[1] + r[2] * p[2], r[3] * p[0] + r[4] * p[1] + r[5] * p[2], r[6] * p[0] + r[7] * p[1] + r[8] * p[2]};
}

}  // namespace

// ---- The needlet frame --------------------------------------------------------------------------

NeedletFrame::NeedletFrame(double dilation, int band_limit, const CubatureSource& cubature)
    : dilation_(dilation), band_limit_(band_limit) {
  check_dilation(dilation);
  if (band_limit < 0 || band_limit > frames::kMaxNeedletFrameBand)
    throw std::invalid_argument("band limit must be 0.." + std::to_string(frames::kMaxNeedletFrameBand) + " (got " + std::to_string(band_limit) + ")");
  NeedletLevel scaling;
  scaling.j = -1;
  scaling.window = {1.0};
  scaling.cubature.points = {{0, 0, 1}};
  scaling.cubature.weights = {4 * runtime::kPi};
  scaling.cubature.name = "one node";
  levels_.push_back(scaling);
  for (const WindowValue& w : needlet_windows(dilation, band_limit)) {
    if (levels_.back().j != w.j) {
      NeedletLevel level;
      level.j = w.j;
      level.lmin = w.l;
      levels_.push_back(level);
    }
    NeedletLevel& level = levels_.back();
    level.window.resize(w.l - level.lmin + 1, 0.0);
    level.window[w.l - level.lmin] = w.value;
    level.lmax = w.l;
  }
  for (NeedletLevel& level : levels_) {
    if (level.j >= 0) {
      level.cubature = cubature(2 * level.lmax);
      check_cubature(level.cubature, 2 * level.lmax);
    }
    level.offset = size_;
    size_ += static_cast<int>(level.cubature.points.size());
  }
}

void NeedletFrame::check_size(const std::vector<double>& v, std::size_t n, const char* what) const {
  if (v.size() != n)
    throw std::invalid_argument(std::string(what) + ": " + std::to_string(v.size()) + " values, " + std::to_string(n) + " expected");
}

std::vector<double> NeedletFrame::analyze(const std::vector<double>& sh) const {
  check_size(sh, runtime::coefficient_count(band_limit_ + 1), "SH coefficients");
  std::vector<double> beta(size_), y(sh.size());
  for (const NeedletLevel& level : levels_) {
    for (std::size_t k = 0; k < level.cubature.points.size(); ++k) {
      runtime::eval_sh(level.lmax + 1, level.cubature.points[k].data(), y.data());
      double sum = 0;
      for (int l = level.lmin; l <= level.lmax; ++l) {
        double band = 0;
        for (int m = -l; m <= l; ++m) band += sh[runtime::index(l, m)] * y[runtime::index(l, m)];
        sum += level.window[l - level.lmin] * band;
      }
      beta[level.offset + k] = std::sqrt(level.cubature.weights[k]) * sum;
    }
  }
  return beta;
}

std::vector<double> NeedletFrame::synthesize(const std::vector<double>& beta) const {
  check_size(beta, size_, "needlet coefficients");
  std::vector<double> sh(runtime::coefficient_count(band_limit_ + 1), 0.0), y(sh.size());
  for (const NeedletLevel& level : levels_) {
    for (std::size_t k = 0; k < level.cubature.points.size(); ++k) {
      runtime::eval_sh(level.lmax + 1, level.cubature.points[k].data(), y.data());
      const double weight = std::sqrt(level.cubature.weights[k]) * beta[level.offset + k];
      for (int l = level.lmin; l <= level.lmax; ++l) {
        const double scale = weight * level.window[l - level.lmin];
        for (int m = -l; m <= l; ++m) sh[runtime::index(l, m)] += scale * y[runtime::index(l, m)];
      }
    }
  }
  return sh;
}

std::vector<double> NeedletFrame::analyze_samples(const Cubature& samples, const std::vector<double>& values) const {
  check_cubature(samples, 2 * band_limit_);
  check_size(values, samples.points.size(), "samples");
  std::vector<double> beta(size_, 0.0);
  for (std::size_t s = 0; s < samples.points.size(); ++s) {
    const double weighted = samples.weights[s] * values[s];
    for (int a = 0; a < static_cast<int>(levels_.size()); ++a) {
      const NeedletLevel& level = levels_[a];
      for (std::size_t k = 0; k < level.cubature.points.size(); ++k)
        beta[level.offset + k] +=
            weighted * std::sqrt(level.cubature.weights[k]) * kernel(a, clamp_dot(dot(samples.points[s], level.cubature.points[k])));
    }
  }
  return beta;
}

double NeedletFrame::evaluate(const std::vector<double>& beta, const Point& x) const {
  check_size(beta, size_, "needlet coefficients");
  double sum = 0;
  for (int a = 0; a < static_cast<int>(levels_.size()); ++a) {
    const NeedletLevel& level = levels_[a];
    for (std::size_t k = 0; k < level.cubature.points.size(); ++k)
      sum += beta[level.offset + k] * std::sqrt(level.cubature.weights[k]) * kernel(a, clamp_dot(dot(x, level.cubature.points[k])));
  }
  return sum;
}

double NeedletFrame::kernel(int a, double t) const {
  const NeedletLevel& level = levels_.at(a);
  return zonal_series(level.lmin, level.lmax, t, [&](int l) { return level.window[l - level.lmin]; });
}

bool NeedletFrame::levels_overlap(int a, int b) const {
  const NeedletLevel &p = levels_.at(a), &q = levels_.at(b);
  return std::max(p.lmin, q.lmin) <= std::min(p.lmax, q.lmax);
}

double NeedletFrame::cross_kernel(int a, int b, double t) const {
  if (!levels_overlap(a, b)) return 0;
  const NeedletLevel &p = levels_[a], &q = levels_[b];
  return zonal_series(std::max(p.lmin, q.lmin), std::min(p.lmax, q.lmax), t,
                      [&](int l) { return p.window[l - p.lmin] * q.window[l - q.lmin]; });
}

std::vector<double> NeedletFrame::rotate_exact(const std::vector<double>& beta, const runtime::Matrix3& r) const {
  const std::vector<double> f = synthesize(beta);
  const sh::BandMatrices bands = sh::ivanic_ruedenberg(sh::to_eigen(r), band_limit_ + 1);
  const Eigen::VectorXd g = sh::apply_band_matrices(bands, Eigen::Map<const Eigen::VectorXd>(f.data(), f.size()));
  return analyze(std::vector<double>(g.data(), g.data() + g.size()));
}

// ---- Look-up tables -----------------------------------------------------------------------------

UniformTable::UniformTable(const std::function<double(double)>& f, int size) {
  if (size < frames::kMinNeedletTableSize || size > frames::kMaxNeedletTableSize)
    throw std::invalid_argument("table size must be " + std::to_string(frames::kMinNeedletTableSize) + ".." + std::to_string(frames::kMaxNeedletTableSize) +
                                " (got " + std::to_string(size) + ")");
  values_.resize(size);
  for (int i = 0; i < size; ++i) values_[i] = f(i == size - 1 ? 1.0 : -1.0 + 2.0 * i / (size - 1));
}

double UniformTable::operator()(double t, Interpolation how) const {
  const int last = size() - 1;
  const double u = (clamp_dot(t) + 1) * 0.5 * last;
  if (how == Interpolation::kLinear) {
    const int i = std::min(static_cast<int>(u), last - 1);
    const double s = u - i;
    return values_[i] + s * (values_[i + 1] - values_[i]);
  }
  // The three nodes around the nearest one (shifted inwards at the ends), Lagrange form.
  const int c = std::min(std::max(static_cast<int>(std::lround(u)), 1), last - 1);
  const double s = u - c;
  return values_[c - 1] * s * (s - 1) / 2 + values_[c] * (1 - s) * (1 + s) + values_[c + 1] * s * (s + 1) / 2;
}

double table_error(const UniformTable& table, const std::function<double(double)>& f, Interpolation how, int probes) {
  double worst = 0, peak = 0;
  for (int i = 0; i < probes; ++i) {
    const double t = -1.0 + 2.0 * i / (probes - 1), exact = f(t);
    worst = std::max(worst, std::abs(table(t, how) - exact));
    peak = std::max(peak, std::abs(exact));
  }
  return peak > 0 ? worst / peak : worst;
}

TabulatedNeedletRotation::TabulatedNeedletRotation(const NeedletFrame& frame, int table_size, Interpolation how)
    : frame_(frame), how_(how) {
  const int n = static_cast<int>(frame.levels().size());
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      if (frame.levels_overlap(a, b))
        pairs_.push_back({a, b, UniformTable([&](double t) { return frame.cross_kernel(a, b, t); }, table_size)});
}

std::vector<double> TabulatedNeedletRotation::rotate(const std::vector<double>& beta, const runtime::Matrix3& r) const {
  if (beta.size() != static_cast<std::size_t>(frame_.size()))
    throw std::invalid_argument("needlet coefficients: " + std::to_string(beta.size()) + " values, " + std::to_string(frame_.size()) +
                                " expected");
  // beta scaled by sqrt(lambda) once, so the inner loop is a dot product and a look-up.
  std::vector<double> scaled(beta.size()), out(beta.size(), 0.0);
  for (const NeedletLevel& level : frame_.levels())
    for (std::size_t k = 0; k < level.cubature.points.size(); ++k)
      scaled[level.offset + k] = beta[level.offset + k] * std::sqrt(level.cubature.weights[k]);
  std::vector<Point> turned;
  for (const Pair& pair : pairs_) {
    const NeedletLevel &from = frame_.levels()[pair.a], &to = frame_.levels()[pair.b];
    turned.clear();
    for (const Point& p : from.cubature.points) turned.push_back(rotate_point(r, p));
    for (std::size_t i = 0; i < to.cubature.points.size(); ++i) {
      double sum = 0;
      for (std::size_t k = 0; k < turned.size(); ++k) sum += scaled[from.offset + k] * pair.table(dot(turned[k], to.cubature.points[i]), how_);
      out[to.offset + i] += std::sqrt(to.cubature.weights[i]) * sum;
    }
  }
  return out;
}

// ---- Localisation -------------------------------------------------------------------------------

int needlet_top_band(double dilation, int j) {
  check_dilation(dilation);
  const double top = std::ceil(std::pow(dilation, j + 1)) - 1;  // compared before the cast: B^(j+1) may pass any int
  if (!(j >= 0 && top <= frames::kMaxNeedletBand))
    throw std::invalid_argument("level " + std::to_string(j) + " of B = " + std::to_string(dilation) + " reaches past band " +
                                std::to_string(frames::kMaxNeedletBand));
  return static_cast<int>(top);
}

std::function<double(double)> needlet_kernel(double dilation, int j) {
  const int top = needlet_top_band(dilation, j);
  std::vector<double> window(top + 1, 0.0);  // once: each value is a quadrature
  for (int l = 1; l <= top; ++l) window[l] = needlet_window(l / std::pow(dilation, j), dilation);
  return [window, top](double t) { return zonal_series(1, top, t, [&](int l) { return window[l]; }); };
}

double sh_delta_kernel(int lmax, double t) {
  return zonal_series(0, lmax, t, [](int) { return 1.0; });
}

namespace {
constexpr int kLargestRule = 64;  // sh::gauss_legendre's most nodes
}  // namespace

Localisation localisation(const std::function<double(double)>& kernel, int degree, double cap) {
  if (degree < 0 || degree > frames::kMaxProfileBand)
    throw std::invalid_argument("profile degree must be 0.." + std::to_string(frames::kMaxProfileBand) + " (got " + std::to_string(degree) + ")");
  // K^2 has degree 2 degree: one Gauss-Legendre rule of degree + 1 nodes is exact; past the
  // largest rule, panels of it (twice as many nodes in all as the degree needs).
  const int nodes = std::min(degree + 1, kLargestRule);
  const int panels = degree + 1 <= kLargestRule ? 1 : 2 * ((degree + kLargestRule) / kLargestRule);
  std::vector<double> x, w;
  sh::gauss_legendre(nodes, x, w);
  const double edge = std::cos(cap);
  auto energy = [&](double a, double b) {
    double sum = 0;
    const double width = (b - a) / panels;
    for (int p = 0; p < panels; ++p) {
      const double start = a + p * width;
      for (std::size_t i = 0; i < x.size(); ++i) {
        const double k = kernel(start + width / 2 * (x[i] + 1));
        sum += w[i] * k * k;
      }
    }
    return sum * width / 2;
  };
  Localisation out;
  const double outside = energy(-1, edge), inside = energy(edge, 1);
  out.outside_energy = outside / (outside + inside);
  const double peak = kernel(1);
  for (int i = 0; i <= 20000; ++i) {
    const double theta = cap + (runtime::kPi - cap) * i / 20000;
    out.sidelobe = std::max(out.sidelobe, std::abs(kernel(std::cos(theta))) / std::abs(peak));
  }
  return out;
}

MaskExperiment mask_experiment(const NeedletFrame& frame, double cut, double margin) {
  const int band_limit = frame.band_limit(), n = runtime::coefficient_count(band_limit + 1);
  std::mt19937_64 rng(1);
  sh::Normal<> normal(0, 1);
  std::vector<double> whole(n);
  for (int l = 0; l <= band_limit; ++l)
    for (int m = -l; m <= l; ++m) whole[runtime::index(l, m)] = normal(rng) / (l + 1);
  // The cut signal's coefficients: f y is a polynomial in z on each side for every phi mode.
  const double s = std::sin(cut);
  std::vector<double> z, wz;
  sh::gauss_legendre(band_limit + 1, z, wz);
  const int phis = 2 * band_limit + 1;
  std::vector<double> cut_signal(n, 0.0), y(n);
  auto value = [&](const double* dir) {
    runtime::eval_sh(band_limit + 1, dir, y.data());
    double v = 0;
    for (int i = 0; i < n; ++i) v += whole[i] * y[i];
    return v;
  };
  for (int side : {-1, 1})
    for (std::size_t i = 0; i < z.size(); ++i) {
      const double zz = side * ((1 + s) / 2 + (1 - s) / 2 * z[i]), r = std::sqrt(std::max(0.0, 1 - zz * zz));
      for (int k = 0; k < phis; ++k) {
        const double phi = 2 * runtime::kPi * k / phis, dir[3] = {r * std::cos(phi), r * std::sin(phi), zz};
        const double weight = wz[i] * (1 - s) / 2 * 2 * runtime::kPi / phis * value(dir);
        for (int c = 0; c < n; ++c) cut_signal[c] += weight * y[c];
      }
    }
  MaskExperiment out;
  for (int l = 0; l <= band_limit; ++l) {
    double diff = 0, norm = 0;
    for (int m = -l; m <= l; ++m) {
      const int i = runtime::index(l, m);
      diff += (cut_signal[i] - whole[i]) * (cut_signal[i] - whole[i]);
      norm += whole[i] * whole[i];
    }
    out.band_error.push_back(std::sqrt(diff / norm));
  }
  // Ringing of the SH projection beyond the margin, on a grid of latitudes and longitudes.
  const double beyond = std::sin(std::min(cut + margin * runtime::kPi / band_limit, runtime::kPi / 2));
  double peak = 0;
  for (int i = 0; i <= 180; ++i)
    for (int k = 0; k < 2 * phis; ++k) {
      const double zz = -1 + 2.0 * i / 180, r = std::sqrt(std::max(0.0, 1 - zz * zz)), phi = runtime::kPi * k / phis;
      const double dir[3] = {r * std::cos(phi), r * std::sin(phi), zz};
      const double exact = value(dir);
      peak = std::max(peak, std::abs(exact));
      if (std::abs(zz) <= beyond) continue;
      double projected = 0;
      for (int c = 0; c < n; ++c) projected += cut_signal[c] * y[c];
      out.sh_ringing = std::max(out.sh_ringing, std::abs(projected - exact));
    }
  out.sh_ringing /= peak;
  const std::vector<double> beta_whole = frame.analyze(whole), beta_cut = frame.analyze(cut_signal);
  for (const NeedletLevel& level : frame.levels()) {
    if (level.j < 0) continue;
    MaskLevel m;
    m.j = level.j;
    m.coefficients = static_cast<int>(level.cubature.points.size());
    double rms = 0;
    for (int k = 0; k < m.coefficients; ++k) rms += beta_whole[level.offset + k] * beta_whole[level.offset + k];
    rms = std::sqrt(rms / m.coefficients);
    const double level_beyond = std::sin(std::min(cut + margin * runtime::kPi / level.lmax, runtime::kPi / 2));
    for (int k = 0; k < m.coefficients; ++k) {
      const double error = std::abs(beta_cut[level.offset + k] - beta_whole[level.offset + k]) / rms;
      if (std::abs(level.cubature.points[k][2]) > level_beyond) {
        ++m.outside;
        m.outside_error = std::max(m.outside_error, error);
      } else {
        m.inside_error = std::max(m.inside_error, error);
      }
    }
    out.levels.push_back(m);
  }
  return out;
}

}  // namespace zhf::frames
