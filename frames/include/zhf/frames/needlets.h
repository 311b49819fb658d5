// Spherical needlets (Narcowich, Petrushev and Ward; the recipe of Marinucci et al. 2008 with the
// real dilation B > 1 of Baldi et al. 2009): band-limited, localised, rotation-invariant wavelets
// that form a tight frame.
//
// The window. From the bump f(t) = exp(-1 / (1 - t^2)) on (-1, 1):
//   psi(u) = int_{-1}^{u} f / int_{-1}^{1} f             a smooth step from 0 (u <= -1) to 1 (u >= 1),
//   phi(t) = 1 (t <= 1/B),  psi(1 - 2B/(B-1) (t - 1/B)) (1/B < t <= 1),  0 (t > 1),
//   b(x)   = sqrt(phi(x / B) - phi(x)),                   non-zero for 1/B < x < B,
// and level j weighs band l by b(l / B^j). The windows are a partition of unity,
// sum_{j >= 0} b^2(l / B^j) = 1 for every l >= 1 (the sum telescopes).
//
// The needlets. Level j sits at the nodes xi_k of a cubature (weights lambda_k) exact to degree
// 2 lmax_j, lmax_j its top band; with L_l(t) = (2l+1)/(4 pi) P_l(t), the kernel of band l,
//   psi_jk(x) = sqrt(lambda_k) K_j(x . xi_k),    K_j(t) = sum_l b(l / B^j) L_l(t).
// Band 0 belongs to the scaling function psi_0 = y_0^0 (one node, weight 4 pi, window 1). With
// beta_jk = <f, psi_jk>:  f = sum_jk beta_jk psi_jk  and  sum_jk beta_jk^2 = |f|^2  (tight frame,
// bound 1), because the cubature turns sum_k lambda_k y(xi_k) y(xi_k)^T into the identity on each
// band and the windows' squares sum to 1.
//
// A NeedletFrame serves signals of bands 0..L: every window is cut at L (a level wholly below L is
// unchanged; the top levels are the projections of the full needlets onto bands <= L), so the frame
// is tight on exactly that space.
//
// Rotation. <R psi_ak, psi_bi> = sqrt(lambda_k lambda_i) G_ab(R xi_k . xi_i) with
// G_ab(t) = sum_l b_a(l) b_b(l) L_l(t), non-zero only for levels whose windows overlap
// (neighbours); tabulating G_ab turns a rotation of needlet coefficients into table look-ups.
//
// Accuracy: window integrals by adaptive Gauss-Kronrod to 1e-17 absolute (psi, phi, b^2 to a few
// 1e-16); kernels by the three-term Legendre recurrence (relative 1e-15 of their peak); analysis
// and synthesis by the cubatures, exact in exact arithmetic. Costs are stated per function.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "zhf/frames/cubature.h"
#include "zhf/frames/designs.h"
#include "zhf/frames/limits.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/sh_eval.h"

namespace zhf::frames {

// Throws std::invalid_argument unless B is in [frames::kMinDilation, frames::kMaxDilation].
void check_dilation(double dilation);

// sum_{l = lo..hi} weight(l) L_l(t), with L_l(t) = (2l+1)/(4 pi) P_l(t) = sum_m y_l^m(x) y_l^m(xi)
// the kernel of band l at t = x . xi, written sqrt((2l+1)/(4 pi)) Q_l^0(t) on the runtime's
// Legendre recurrence.
template <class Weight>
double zonal_series(int lo, int hi, double t, Weight&& weight) {
  double sum = 0;
  runtime::legendre_column(0, hi, t, runtime::kInvSqrt4Pi, runtime::LegendreCoefficients<>{}, [&](int l, double q) {
    if (l >= lo) sum += weight(l) * std::sqrt(2 * l + 1) * runtime::kInvSqrt4Pi * q;
  });
  return sum;
}

// int_{-1}^{1} exp(-1 / (1 - t^2)) dt.
double bump_integral();
double needlet_psi(double u);
// B in [frames::kMinDilation, frames::kMaxDilation]: a B closer to 1 asks for ~log(l) / log(B) levels.
// phi(t) = psi(u(t)): u = 1 up to t = 1/B (phi = 1), -1 beyond t = 1 (phi = 0), linear between.
double phi_argument(double t, double dilation);
double needlet_phi(double t, double dilation);
double needlet_window(double x, double dilation);  // b(x)

struct WindowValue {
  int j, l;
  double value;
};
// Every non-zero b(l / B^j) for l = 0..lmax, j = 0, 1, ... Throws std::invalid_argument for B
// outside [frames::kMinDilation, frames::kMaxDilation] or lmax outside 0..frames::kMaxNeedletBand.
std::vector<WindowValue> needlet_windows(double dilation, int lmax);

// ---- The needlet frame ------------------------------------------------------------------------


struct NeedletLevel {
  int j = 0;                    // -1: the scaling function
  int lmin = 0, lmax = 0;       // bands with a non-zero window, cut at L
  std::vector<double> window;   // window[l - lmin]
  Cubature cubature;            // exact to degree 2 lmax
  int offset = 0;               // where the level's coefficients start
};

class NeedletFrame {
 public:
  // The scaling function and every level j >= 0 whose window reaches a band in 1..band_limit.
  // Throws std::invalid_argument for B outside [frames::kMinDilation, frames::kMaxDilation] or L outside
  // 0..frames::kMaxNeedletFrameBand, or a cubature that is not exact to the degree asked.
  NeedletFrame(double dilation, int band_limit, const CubatureSource& cubature = gauss_product_cubature);

  double dilation() const { return dilation_; }
  int band_limit() const { return band_limit_; }
  const std::vector<NeedletLevel>& levels() const { return levels_; }
  int size() const { return size_; }  // coefficient count

  // beta = <f, psi> from f's SH coefficients (order L + 1, zhf's convention). Cost: O(size L^2).
  std::vector<double> analyze(const std::vector<double>& sh) const;
  // beta from samples of f at a cubature exact to degree 2 L (f of bands <= L). Cost:
  // O(samples size L).
  std::vector<double> analyze_samples(const Cubature& samples, const std::vector<double>& values) const;
  // sum beta psi as SH coefficients of order L + 1. Cost: O(size L^2).
  std::vector<double> synthesize(const std::vector<double>& beta) const;
  // sum beta psi at a unit direction, each needlet by its Legendre series. Cost: O(size L).
  double evaluate(const std::vector<double>& beta, const Point& x) const;

  // K of level index `level` (into levels()) at t in [-1, 1]. Cost: O(L).
  double kernel(int level, double t) const;
  // G between two levels (zero everywhere unless their windows overlap). Cost: O(L).
  double cross_kernel(int a, int b, double t) const;
  bool levels_overlap(int a, int b) const;

  // The coefficients of f(R^T x) from those of f: synthesise, rotate the SH (Ivanic-Ruedenberg
  // band matrices), analyse. Cost: O(size L^2 + L^4).
  std::vector<double> rotate_exact(const std::vector<double>& beta, const runtime::Matrix3& r) const;

 private:
  void check_size(const std::vector<double>& v, std::size_t n, const char* what) const;
  double dilation_;
  int band_limit_;
  std::vector<NeedletLevel> levels_;
  int size_ = 0;
};

// ---- Look-up tables ---------------------------------------------------------------------------

// A function of t in [-1, 1] sampled at `size` equally spaced t; read back by linear or quadratic
// (three nearest nodes) interpolation: what a shader does with a 1D texture. Cost per read: O(1).
enum class Interpolation { kLinear, kQuadratic };
class UniformTable {
 public:
  UniformTable(const std::function<double(double)>& f, int size);
  double operator()(double t, Interpolation how) const;
  int size() const { return static_cast<int>(values_.size()); }
  const std::vector<double>& values() const { return values_; }

 private:
  std::vector<double> values_;
};

// max |table(t) - f(t)| over `probes` equally spaced t (midpoints of the nodes among them),
// relative to max |f| over the same t.
double table_error(const UniformTable& table, const std::function<double(double)>& f, Interpolation how, int probes = 20011);

// Rotation of needlet coefficients through tabulated G_ab, one table per pair of overlapping
// levels. Cost per rotation: O(sum over overlapping pairs of M_a M_b) look-ups.
class TabulatedNeedletRotation {
 public:
  // Keeps a reference to frame, which must outlive it.
  TabulatedNeedletRotation(const NeedletFrame& frame, int table_size, Interpolation how);
  std::vector<double> rotate(const std::vector<double>& beta, const runtime::Matrix3& r) const;

 private:
  struct Pair {
    int a, b;
    UniformTable table;
  };
  const NeedletFrame& frame_;
  Interpolation how_;
  std::vector<Pair> pairs_;
};

}  // namespace zhf::frames

namespace zhf::frames {

// ---- Localisation ---------------------------------------------------------------------------

// The full needlet kernel of level j (its window uncut): sum_l b(l / B^j) (2l+1)/(4 pi) P_l(t) over
// B^(j-1) < l < B^(j+1); and the truncated SH delta of bands 0..lmax, sum_l (2l+1)/(4 pi) P_l(t).
// Top bands: needlet_top_band(B, j) = ceil(B^(j+1)) - 1; std::invalid_argument for a level below 0
// or reaching past frames::kMaxNeedletBand. Cost: O(lmax) per t.
int needlet_top_band(double dilation, int j);
std::function<double(double)> needlet_kernel(double dilation, int j);  // its windows computed once
double sh_delta_kernel(int lmax, double t);

// How much of a zonal kernel K (a polynomial of degree `degree` in t = cos theta) lies outside the
// cap theta < cap: its energy fraction there, int_{theta > cap} K^2 / int K^2 (Gauss-Legendre on
// each side: exact to degree 63, on panels of 64 nodes beyond, converged to rounding), and its
// largest |K| there relative to K(1) (sampled at 20001 angles). Degrees up to
// frames::kMaxProfileBand (std::invalid_argument beyond).
struct Localisation {
  double outside_energy = 0;
  double sidelobe = 0;
};
Localisation localisation(const std::function<double(double)>& kernel, int degree, double cap);

// A random signal of bands 0..L (power ~ 1 / (l + 1)^2, seed fixed) cut to zero in the band
// |latitude| < cut (radians), analysed in SH to L and in needlets: which coefficients the cut
// disturbs. The SH coefficients of the cut signal are exact (Gauss-Legendre in z on each side of
// the cut times equal steps in phi integrate its piecewise polynomials exactly).
// Distances beyond the cut are counted in half-wavelengths of the top band: `margin` pi / lmax
// for a level of top band lmax, margin pi / L for the SH projection.
struct MaskLevel {
  int j = 0;
  int coefficients = 0, outside = 0;  // needlets, and those centred beyond the cut and the margin
  double outside_error = 0;           // max |beta(cut) - beta(whole)| / rms beta(whole) there
  double inside_error = 0;            // the same for the needlets centred nearer
};
struct MaskExperiment {
  std::vector<double> band_error;  // per band l: |f_l(cut) - f_l(whole)| / |f_l(whole)|
  double sh_ringing = 0;           // max |P_L(cut)(x) - f(x)| / max |f| at x beyond the cut and the margin
  std::vector<MaskLevel> levels;
};
MaskExperiment mask_experiment(const NeedletFrame& frame, double cut, double margin);

}  // namespace zhf::frames
