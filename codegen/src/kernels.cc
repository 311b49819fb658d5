#include "zhf/codegen/kernels.h"

#include <algorithm>
#include <cmath>

#include "band_lobes.h"
#include "band_quadratic.h"
#include "band_zxzxz.h"
#include "kernel_cost.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/zxzxz.h"

namespace zhf::codegen {
namespace {

using runtime::kBand1Axis;
using runtime::kInvSqrt4Pi;
using runtime::kPi;

// Builds each emitted function of one table on the expression graph, each band >= 2 by its method
// (band_lobes.h, band_zxzxz.h, band_quadratic.h).
class Builder {
 public:
  Builder(const runtime::LobeTable& table, const std::vector<Lobe>& lobes, const std::vector<int>& zero_bands,
          runtime::LobeStage stage, bool condon_shortley, const std::vector<BandMethod>& methods,
          const sh::BandMatrices& quarter_turn)
      : table_(table), lobes_(lobes), order_(table.order), count_(runtime::coefficient_count(table.order)),
        legendre_(std::max(table.order, 1)), live_(std::max(table.order, 1), true), methods_(methods),
        quarter_turn_(quarter_turn), wide_rotation_(stage != runtime::LobeStage::kFloat),
        wide_lobes_(stage == runtime::LobeStage::kDouble), condon_shortley_(condon_shortley) {
    for (int l : zero_bands)
      if (l >= 0 && l < order_) live_[l] = false;
  }

  Function sh_eval() const {
    Function f = make(KernelKind::kShEval, "sh_eval", 1,
                      "y[index(l,m)] = y_l^m(dir) for every band, dir a unit vector",
                      {{"dir", 3, false, 1}, {"y", count_, true, 1}});
    Graph& g = f.graph;
    const std::vector<int> y = unit_sh(g, Vec3{{g.input(0, 0), g.input(0, 1), g.input(0, 2)}}, std::vector<bool>(order_, true));
    for (int i = 0; i < count_; ++i) put(f, 1, i, y[i]);
    return f;
  }

  // z[l^2 + d] = sum_m A_l[m][d] f[l^2 + m] (transpose) or out[l^2 + m] = sum_d A_l[m][d] s[l^2 + d].
  Function sparse_multiply(bool transpose) const {
    const std::string doc = transpose
                                ? "lobe weights z = A^T f per band >= 2 (z[l*l + d], lobe position d); bands 0, 1 copied"
                                : "coefficients f = A s per band >= 2 from lobe samples s[l*l + d]; bands 0, 1 copied";
    Function f = make(transpose ? KernelKind::kLobeWeights : KernelKind::kFromSamples,
                      transpose ? "lobe_weights" : "coefficients_from_samples", 1, doc,
                      {{transpose ? "f" : "s", count_, false, 1}, {transpose ? "z" : "f", count_, true, 1}});
    Graph& g = f.graph;
    for (int i = 0; i < std::min(count_, 4); ++i) put(f, 1, i, g.input(0, i));
    for (const runtime::TableBand& band : table_.bands) {
      const int l = band.l, base = l * l;
      const std::vector<int> sums = band_sums(g, band.inverse, transpose, base);
      for (int i = 0; i < 2 * l + 1; ++i) put(f, 1, base + i, sums[i]);
    }
    if (!transpose && condon_shortley_) {
      // The system's coefficients are S f: the odd-m outputs negated (folded into their sums).
      const std::vector<int> odd = odd_m_indices();
      for (Output& o : f.outputs)
        if (std::find(odd.begin(), odd.end(), o.element) != odd.end()) o.node = g.neg(o.node);
    }
    return f;
  }

  // The standard rotation, each band by its method; several channels share the per-rotation work.
  Function rotation(int channels, bool batch) const {
    std::string doc = "rotated = coefficients of f(R^T w), R row-major mapping v to R v" + channel_doc(channels);
    if (batch) doc += ", for count vectors each with its own R (structure of arrays; the arrays must not overlap)";
    Function f = make(batch ? KernelKind::kBatch : KernelKind::kRotate, batch ? "rotate_batch" : "rotate", channels, doc,
                      {{"R", 9, false, 1}, {"coeffs", count_, false, channels}, {"rotated", count_, true, channels}});
    f.batch = batch;
    Graph& g = f.graph;
    const int in = 1, out = 2;
    copy_band0_rotate_band1(f, in, out, channels);
    const std::vector<bool> by_lobes = live_by(BandMethod::kLobes);
    const std::vector<std::vector<int>> h = lobe_polynomials(g, /*transpose=*/false, by_lobes);
    g.set_wide(false);
    const EulerTurns turns = euler_turns(g, live_by(BandMethod::kZxzxz));
    for (const runtime::TableBand& band : table_.bands) {
      const int l = band.l, base = l * l;
      if (!live_[l]) {
        put_zeros(f, out, l);
        continue;
      }
      if (!by_lobes[l]) {
        std::vector<int> v(2 * l + 1);
        for (int i = 0; i < 2 * l + 1; ++i) v[i] = g.input(in, base + i, channels);
        v = band_by_formula(g, l, turns, v);
        for (int i = 0; i < 2 * l + 1; ++i) put(f, out, base + i, v[i]);
        continue;
      }
      std::vector<int> zhat(2 * l + 1);
      g.set_wide(false);  // the lobe weights only round once per term: float suffices
      for (int d = 0; d < 2 * l + 1; ++d) zhat[d] = lobe_weight(g, band, d, [&](int k) { return g.input(in, base + k, channels); });
      g.set_wide(wide_lobes_);
      for (int m = -l; m <= l; ++m) {
        std::vector<std::pair<double, int>> terms;
        for (int d = 0; d < 2 * l + 1; ++d) terms.push_back({1.0, g.mul(h[band.lobes[d]][runtime::index(l, m)], zhat[d])});
        put(f, out, base + m + l, g.scale(legendre_.output_scale(l, m), g.linear(terms)));
      }
      g.set_wide(false);
    }
    g.set_wide(false);
    return f;
  }

  // rotated = A s with s the band's function sampled at R^T w_d: same result, the work
  // arranged as a renderer sampling a texture would.
  Function signal_tailored(int channels) const {
    Function f = make(KernelKind::kSignalTailored, "rotate_signal_tailored", channels,
                      "rotated = A s, s = each band of f sampled at the inverse-rotated lobes R^T w_d" + channel_doc(channels),
                      {{"R", 9, false, 1}, {"coeffs", count_, false, channels}, {"rotated", count_, true, channels}});
    Graph& g = f.graph;
    copy_band0_rotate_band1(f, 1, 2, channels);
    const std::vector<std::vector<int>> h = lobe_polynomials(g, /*transpose=*/true, live_);
    for (const runtime::TableBand& band : table_.bands) {
      const int l = band.l, base = l * l;
      if (!live_[l]) {
        put_zeros(f, 2, l);
        continue;
      }
      std::vector<int> weighted(2 * l + 1);
      for (int m = -l; m <= l; ++m)
        weighted[m + l] = g.scale(legendre_.output_scale(l, m), g.input(1, base + m + l, channels));
      std::vector<int> samples(2 * l + 1);
      for (int d = 0; d < 2 * l + 1; ++d) {
        std::vector<std::pair<double, int>> terms;
        for (int m = -l; m <= l; ++m) terms.push_back({1.0, g.mul(h[band.lobes[d]][runtime::index(l, m)], weighted[m + l])});
        samples[d] = g.linear(terms);
      }
      g.set_wide(false);  // each sample rounded once: float suffices for A s
      for (int m = -l; m <= l; ++m) {
        std::vector<std::pair<double, int>> terms;
        for (int d = 0; d < 2 * l + 1; ++d) terms.push_back({band.inverse(m + l, d) * lobe_scale(band, d), samples[d]});
        put(f, 2, base + m + l, g.linear(terms));
      }
      g.set_wide(wide_lobes_);
    }
    g.set_wide(false);
    return f;
  }

  // Shading: int L(R^T w) t(w) dw, the lighting rotated by R against a transfer vector, in one
  // function. Per band l >= 2 (RZHB, coupling C^D = Y_R): with zhat_d the lobe weights of L,
  //   int = sum_d zhat_d t_l(R w_d),  t_l(R w_d) = sum_m (K_lm t_lm) H_lm(R u_d) / |u_d|^l,
  // so t is scaled once and evaluated at each rotated lobe. from_lobes: the lighting comes as its
  // lobe weights z = A^T L (lobe_weights' layout: bands 0 and 1 SH), which skips the sparse stage
  // for lighting that is shaded under many rotations.
  Function shading(bool from_lobes) const {
    const std::string doc = std::string("result[0] = integral of the lighting rotated by R (f(R^T w)) times transfer") +
                            (from_lobes ? ", the lighting given as lobe weights z (lobe_weights)" : "");
    Function f = make(from_lobes ? KernelKind::kShadeLobes : KernelKind::kShade, from_lobes ? "shade_lobes" : "shade", 1, doc,
                      {{"R", 9, false, 1}, {from_lobes ? "z" : "light", count_, false, 1}, {"transfer", count_, false, 1},
                       {"result", 1, true, 1}});
    Graph& g = f.graph;
    const int light = 1, transfer = 2;
    std::vector<std::pair<double, int>> total;
    if (live_[0]) total.push_back({1.0, g.mul(g.input(light, 0), g.input(transfer, 0))});
    if (order_ > 1 && live_[1])
      for (int m = -1; m <= 1; ++m) {
        std::vector<std::pair<double, int>> terms;
        for (int n = -1; n <= 1; ++n)
          terms.push_back({1.0, g.mul(g.input(0, 3 * kBand1Axis[m + 1] + kBand1Axis[n + 1]), g.input(light, runtime::index(1, n)))});
        total.push_back({1.0, g.mul(g.linear(terms), g.input(transfer, runtime::index(1, m)))});
      }
    // From the light's coefficients, the bands the rotations take by a formula (zxzxz, quadratic)
    // rotate the light and dot it with the transfer; from lobe weights, every band is by lobes.
    const std::vector<bool> by_lobes = from_lobes ? live_ : live_by(BandMethod::kLobes);
    const std::vector<std::vector<int>> h = lobe_polynomials(g, /*transpose=*/false, by_lobes);
    g.set_wide(false);
    const EulerTurns turns = euler_turns(g, from_lobes ? std::vector<bool>(order_, false) : live_by(BandMethod::kZxzxz));
    for (const runtime::TableBand& band : table_.bands) {
      const int l = band.l, base = l * l;
      if (live_[l] && !by_lobes[l]) {
        std::vector<int> v(2 * l + 1);
        for (int i = 0; i < 2 * l + 1; ++i) v[i] = g.input(light, base + i);
        v = band_by_formula(g, l, turns, v);
        for (int i = 0; i < 2 * l + 1; ++i) total.push_back({1.0, g.mul(v[i], g.input(transfer, base + i))});
        continue;
      }
      if (!by_lobes[l]) continue;
      std::vector<int> scaled(2 * l + 1);
      for (int m = -l; m <= l; ++m) scaled[m + l] = g.scale(legendre_.output_scale(l, m), g.input(transfer, base + m + l));
      for (int d = 0; d < 2 * l + 1; ++d) {
        g.set_wide(false);
        int zhat = 0;
        if (from_lobes) {
          zhat = g.scale(lobe_scale(band, d), g.input(light, base + d));
        } else {
          zhat = lobe_weight(g, band, d, [&](int k) { return g.input(light, base + k); });
        }
        g.set_wide(wide_lobes_);
        std::vector<std::pair<double, int>> at_lobe;
        for (int m = -l; m <= l; ++m) at_lobe.push_back({1.0, g.mul(h[band.lobes[d]][runtime::index(l, m)], scaled[m + l])});
        total.push_back({1.0, g.mul(zhat, g.linear(at_lobe))});
      }
    }
    put(f, 3, 0, total.empty() ? g.constant(0) : g.linear(total));
    g.set_wide(false);
    return f;
  }

  // The dense band matrices of R through the lobes: D_l[m][m'] = sum_d y_l^m(R w_d) A_l[m'][d]
  // (the standard rotation with f the unit vectors), packed as dense_matrix_offset says.
  Function rotation_matrices() const {
    const int size = dense_matrix_offset(order_);
    Function f = make(KernelKind::kRotationMatrices, "rotation_matrices", 1,
                      "M = the dense band matrices of R (band l at l(2l-1)(2l+1)/3, row-major): build once, apply many",
                      {{"R", 9, false, 1}, {"M", size, true, 1}});
    Graph& g = f.graph;
    for (int l = 0; l < std::min(order_, 2); ++l) {
      const int side = 2 * l + 1;
      for (int m = 0; m < side; ++m)
        for (int n = 0; n < side; ++n) {
          int value = g.constant(0);
          if (live_[l]) value = l == 0 ? g.constant(1) : g.input(0, 3 * kBand1Axis[m] + kBand1Axis[n]);
          put(f, 1, dense_matrix_offset(l) + side * m + n, value);
        }
    }
    const std::vector<std::vector<int>> h = lobe_polynomials(g, /*transpose=*/false, live_);
    for (const runtime::TableBand& band : table_.bands) {
      const int l = band.l, side = 2 * l + 1;
      for (int m = -l; m <= l; ++m)
        for (int n = 0; n < side; ++n) {
          std::vector<std::pair<double, int>> terms;
          if (live_[l])
            for (int d = 0; d < side; ++d)
              terms.push_back({band.inverse(n, d) * lobe_scale(band, d), h[band.lobes[d]][runtime::index(l, m)]});
          put(f, 1, dense_matrix_offset(l) + side * (m + l) + n, g.scale(legendre_.output_scale(l, m), g.linear(terms)));
        }
    }
    g.set_wide(false);
    return f;
  }

  Function apply_rotation_matrices(int channels) const {
    Function f = make(KernelKind::kApplyMatrices, "apply_rotation_matrices", channels,
                      "rotated = M coeffs, band by band, M from rotation_matrices" + channel_doc(channels),
                      {{"M", dense_matrix_offset(order_), false, 1},
                       {"coeffs", count_, false, channels},
                       {"rotated", count_, true, channels}});
    Graph& g = f.graph;
    for (int l = 0; l < order_; ++l) {
      const int side = 2 * l + 1;
      for (int m = 0; m < side; ++m) {
        std::vector<std::pair<double, int>> terms;
        if (live_[l])
          for (int n = 0; n < side; ++n)
            terms.push_back({1.0, g.mul(g.input(0, dense_matrix_offset(l) + side * m + n), g.input(1, l * l + n, channels))});
        put(f, 2, l * l + m, g.linear(terms));
      }
    }
    return f;
  }

  // A zonal function about a unit axis a, with zonal[l] its band-l coefficient when a = +z,
  // has f_{l,m} = sqrt(4 pi / (2l+1)) zonal[l] y_l^m(a): rotating it is evaluating the SH at
  // R a, N^2 work and no lobes.
  Function zonal_rotation(int channels) const {
    Function f = make(KernelKind::kZonal, "rotate_zonal", channels,
                      "rotated = coefficients of the zonal function (axis, zonal[l] = its y_l^0 weight about +z) turned by R" +
                          channel_doc(channels),
                      {{"R", 9, false, 1}, {"axis", 3, false, 1}, {"zonal", order_, false, channels},
                       {"rotated", count_, true, channels}});
    Graph& g = f.graph;
    Vec3 v;
    for (int i = 0; i < 3; ++i)
      v.c[i] = g.linear({{1.0, g.mul(g.input(0, 3 * i), g.input(1, 0))},
                         {1.0, g.mul(g.input(0, 3 * i + 1), g.input(1, 1))},
                         {1.0, g.mul(g.input(0, 3 * i + 2), g.input(1, 2))}});
    const std::vector<int> y = unit_sh(g, v, live_, /*fold=*/[](int l) { return std::sqrt(4 * kPi / (2 * l + 1)); });
    for (int l = 0; l < order_; ++l)
      for (int m = -l; m <= l; ++m)
        put(f, 3, runtime::index(l, m), live_[l] ? g.mul(y[runtime::index(l, m)], g.input(2, l, channels)) : g.constant(0));
    return f;
  }

  // What of rotation(1, false) by lobes depends on the lobe set, built the same way on a graph of
  // its own: the lobe weights zhat, R's projection where the stage has one, R u_d, and without
  // lobe sharing the SH at R u_d. With sharing every lobe is a distinct direction (a repeat would
  // make the top band singular), so their SH share nothing and cost the same for every set;
  // without, one direction may serve several bands and its SH are then made once.
  OpCount lobe_dependent_count() const {
    Graph g;
    std::vector<int> nodes;
    g.set_wide(false);
    for (const runtime::TableBand& band : table_.bands)
      for (int d = 0; d < 2 * band.l + 1; ++d)
        nodes.push_back(lobe_weight(g, band, d, [&](int k) { return g.input(1, band.l * band.l + k); }));
    if (!table_.lobe_sharing) {
      for (const std::vector<int>& h : lobe_polynomials(g, /*transpose=*/false, live_))
        std::copy_if(h.begin(), h.end(), std::back_inserter(nodes), [](int node) { return node >= 0; });
      return g.count(nodes);
    }
    const std::vector<int> r = lobe_rotation(g);
    for (const Lobe& lobe : lobes_) {
      const Vec3 v = rotated_lobe(g, r, lobe.scaled, /*transpose=*/false);
      nodes.insert(nodes.end(), v.c, v.c + 3);
    }
    return g.count(nodes);
  }

 private:
  // A function named <stem>[_rgb|_rgba]_orderN.
  Function make(KernelKind kind, const std::string& stem, int channels, const std::string& doc, std::vector<Param> params) const {
    Function f;
    f.kind = kind;
    f.channels = channels;
    f.member = stem + channel_suffix(channels);
    f.name = f.member + "_order" + std::to_string(order_);
    f.doc = doc;
    f.params = std::move(params);
    if (condon_shortley_) {
      f.doc += "; Condon-Shortley signs ((-1)^m), R and directions in the same system's axes";
      take_condon_shortley_arguments(f);
    }
    return f;
  }
  // The system's arguments as zhf's: R -> K R K, a direction d -> K d (K = diag(-1, -1, 1): the
  // entries with exactly one index 2 of R, x and y of d), coefficients f -> S f (S: (-1)^m).
  void take_condon_shortley_arguments(Function& f) const {
    switch (f.kind) {
      case KernelKind::kRotate:
      case KernelKind::kSignalTailored:
      case KernelKind::kBatch:
      case KernelKind::kRotationMatrices:
        f.graph.negate_inputs(0, {2, 5, 6, 7});
        break;
      case KernelKind::kZonal:
        f.graph.negate_inputs(0, {2, 5, 6, 7});
        f.graph.negate_inputs(1, {0, 1});
        break;
      case KernelKind::kShEval:
        f.graph.negate_inputs(0, {0, 1});
        break;
      case KernelKind::kLobeWeights:
        f.graph.negate_inputs(0, odd_m_indices());
        break;
      case KernelKind::kFromSamples:  // its outputs: negated where it puts them (sparse_multiply)
      case KernelKind::kApplyMatrices:  // the matrices are the system's already
      case KernelKind::kProduct:        // built without a table: product_function folds their signs
      case KernelKind::kSquare:
        break;
      case KernelKind::kShade:  // both vectors S f: the dot product is zhf's of the same vectors
        f.graph.negate_inputs(0, {2, 5, 6, 7});
        f.graph.negate_inputs(1, odd_m_indices());
        f.graph.negate_inputs(2, odd_m_indices());
        break;
      case KernelKind::kShadeLobes:  // z as lobe_weights gives it: bands 0 and 1 S f, lobe weights as they are
        f.graph.negate_inputs(0, {2, 5, 6, 7});
        f.graph.negate_inputs(1, {1, 3});
        f.graph.negate_inputs(2, odd_m_indices());
        break;
    }
  }
  std::vector<int> odd_m_indices() const { return codegen::odd_m_indices(count_); }
  static std::string channel_doc(int channels) {
    return channels == 1 ? "" : channels == 3 ? ", for three channels" : ", for four channels";
  }
  static void put(Function& f, int param, int element, int node) { f.outputs.push_back({param, element, node}); }
  void put_zeros(Function& f, int param, int l) const {
    for (int m = -l; m <= l; ++m) put(f, param, runtime::index(l, m), f.graph.constant(0));
  }
  // |u_d|^-l: band l's polynomials are homogeneous of degree l in the rescaled lobe u_d.
  double lobe_scale(const runtime::TableBand& band, int d) const {
    return std::pow(norm2(lobes_[band.lobes[d]].scaled), -0.5 * band.l);
  }

  // zhat_{l,d} = sum_m (A_l[m][d] / |u_d|^l) f_{l,m}, f_{l,m} = input(m + l).
  template <class Input>
  int lobe_weight(Graph& g, const runtime::TableBand& band, int d, const Input& input) const {
    std::vector<std::pair<double, int>> terms;
    for (int k = 0; k < 2 * band.l + 1; ++k) terms.push_back({band.inverse(k, d) * lobe_scale(band, d), input(k)});
    return g.linear(terms);
  }

  // R's nodes as the lobes are rotated by them: projected onto the rotations at LobeStage::kDouble.
  // Leaves the graph at the rotation's width.
  std::vector<int> lobe_rotation(Graph& g) const {
    g.set_wide(wide_rotation_);
    std::vector<int> r(9);
    for (int i = 0; i < 9; ++i) r[i] = g.input(0, i);
    return wide_lobes_ ? orthonormalized_rotation(g) : r;
  }

  // y_l^m at the unit vector v for the bands marked, each times fold(l) (folded into the
  // constants); -1 elsewhere.
  template <class Fold = double (*)(int)>
  std::vector<int> unit_sh(Graph& g, const Vec3& v, const std::vector<bool>& bands,
                           Fold fold = [](int) { return 1.0; }) const {
    std::vector<int> y(count_, -1);
    if (bands[0]) y[0] = g.constant(fold(0) * kInvSqrt4Pi);
    if (order_ > 1 && bands[1])
      for (int m = -1; m <= 1; ++m) y[runtime::index(1, m)] = g.scale(fold(1) * kSqrt3Over4Pi, v.c[kBand1Axis[m + 1]]);
    std::vector<bool> high = bands;
    for (int l = 0; l < std::min(order_, 2); ++l) high[l] = false;
    const std::vector<int> h = homogeneous_sh(g, v, 1.0, order_, high, legendre_);
    for (int l = 2; l < order_; ++l)
      if (high[l])
        for (int m = -l; m <= l; ++m)
          y[runtime::index(l, m)] = g.scale(fold(l) * legendre_.output_scale(l, m), h[runtime::index(l, m)]);
    return y;
  }

  // Band 0 is invariant; band 1 is c (y, z, x), so its matrix is R on those axes.
  void copy_band0_rotate_band1(Function& f, int in, int out, int channels) const {
    Graph& g = f.graph;
    put(f, out, 0, live_[0] ? g.input(in, 0, channels) : g.constant(0));
    if (order_ < 2) return;
    if (!live_[1]) {
      put_zeros(f, out, 1);
      return;
    }
    for (int m = -1; m <= 1; ++m) {
      std::vector<std::pair<double, int>> terms;
      for (int n = -1; n <= 1; ++n)
        terms.push_back({1.0, g.mul(g.input(0, 3 * kBand1Axis[m + 1] + kBand1Axis[n + 1]), g.input(in, runtime::index(1, n), channels))});
      put(f, out, runtime::index(1, m), g.linear(terms));
    }
  }

  // Per lobe, the homogeneous polynomials of every band marked that uses it, at R u_d (or R^T u_d):
  // the lobes rotated in the wide type from LobeStage::kDoubleRotation on, R projected and the SH
  // wide too at kDouble. The graph is left at the SH's width: the caller narrows where float
  // suffices.
  std::vector<std::vector<int>> lobe_polynomials(Graph& g, bool transpose, const std::vector<bool>& bands) const {
    const std::vector<int> r = lobe_rotation(g);
    std::vector<std::vector<bool>> bands_of_lobe(lobes_.size(), std::vector<bool>(order_, false));
    for (const runtime::TableBand& band : table_.bands)
      if (bands[band.l])
        for (int d : band.lobes) bands_of_lobe[d][band.l] = true;
    std::vector<std::vector<int>> h;
    for (size_t d = 0; d < lobes_.size(); ++d) {
      g.set_wide(wide_rotation_);
      const Vec3 v = rotated_lobe(g, r, lobes_[d].scaled, transpose);
      g.set_wide(wide_lobes_);
      h.push_back(homogeneous_sh(g, v, norm2(lobes_[d].scaled), order_, bands_of_lobe[d], legendre_));
    }
    return h;
  }

  // The live bands >= 2 the rotations take by this method.
  std::vector<bool> live_by(BandMethod method) const {
    std::vector<bool> bands(order_, false);
    for (const runtime::TableBand& band : table_.bands) bands[band.l] = live_[band.l] && methods_[band.l] == method;
    return bands;
  }
  // Band l (v[m + l]) rotated by its method, zxzxz or quadratic.
  std::vector<int> band_by_formula(Graph& g, int l, const EulerTurns& t, const std::vector<int>& v) const {
    return methods_[l] == BandMethod::kQuadratic ? quadratic_band(g, v) : zxzxz_band(g, l, t, quarter_turn_[l], v);
  }
  const runtime::LobeTable& table_;
  const std::vector<Lobe>& lobes_;
  int order_;
  int count_;
  Legendre legendre_;
  std::vector<bool> live_;  // bands not known to be zero
  const std::vector<BandMethod>& methods_;  // [l] of the rotation kernels
  const sh::BandMatrices& quarter_turn_;    // X_l = D_l(Rx(+90 deg))
  bool wide_rotation_;  // the lobes are rotated in the wide type
  bool wide_lobes_;     // ... and R projected, their SH and the sums over lobes too
  bool condon_shortley_;  // ModuleOptions::condon_shortley
};

}  // namespace

std::vector<int> Function::output_nodes() const {
  std::vector<int> nodes;
  for (const Output& o : outputs) nodes.push_back(o.node);
  return nodes;
}

std::vector<int> odd_m_indices(int count) {
  std::vector<int> odd;
  for (int i = 0; i < count; ++i)
    if ((i - runtime::band_of(i) * (runtime::band_of(i) + 1)) % 2) odd.push_back(i);
  return odd;
}

std::string channel_suffix(int channels) { return channels == 3 ? "_rgb" : channels == 4 ? "_rgba" : ""; }

int dense_matrix_offset(int band) { return band * (2 * band - 1) * (2 * band + 1) / 3; }

runtime::LobeStage Module::rotation_lobe_stage() const {
  for (int l = 2; l < order && l < int(band_methods.size()); ++l)
    if (band_methods[l] == BandMethod::kLobes) return lobe_stage;
  return runtime::LobeStage::kFloat;
}


std::vector<Lobe> lobes_of(const runtime::LobeTable& table) {
  std::vector<Lobe> lobes;
  for (const runtime::TableLobe& t : table.lobes) {
    Lobe lobe;
    std::copy(t.xyz.begin(), t.xyz.end(), lobe.unit);
    scale_lobe(t.xyz.data(), lobe.scaled);
    lobe.source = t.source;
    lobes.push_back(lobe);
  }
  return lobes;
}

OpCount rotation_op_count(const Module& module, const ModuleOptions& options, const std::vector<BandMethod>& methods,
                          const sh::BandMatrices& quarter_turn) {
  const Builder builder(module.table, module.lobes, options.zero_bands, module.lobe_stage, options.condon_shortley, methods,
                        quarter_turn);
  const Function f = builder.rotation(1, false);
  return f.graph.count(f.output_nodes());
}

OpCount lobe_dependent_op_count(const runtime::LobeTable& table) {
  const std::vector<Lobe> lobes = lobes_of(table);
  const sh::BandMatrices no_quarter_turns;  // every band by lobes
  const Builder builder(table, lobes, {}, lobe_stage_for(table, ModuleOptions{}), /*condon_shortley=*/false,
                        std::vector<BandMethod>(std::max(table.order, 1), BandMethod::kLobes), no_quarter_turns);
  return builder.lobe_dependent_count();
}

Module build_module(const runtime::LobeTable& table, const ModuleOptions& options) {
  Module module;
  module.order = table.order;
  module.table = table;
  module.lobes = lobes_of(table);
  module.lobe_stage = lobe_stage_for(module.table, options);
  const sh::BandMatrices quarter_turn = sh::quarter_turn_x(std::max(table.order, 1));
  if (options.band_method == BandMethod::kQuadratic) {
    module.band_methods.assign(table.order, BandMethod::kZxzxz);
    if (table.order > 2) module.band_methods[2] = BandMethod::kQuadratic;
    module.band_methods_reason = "band 2 quadratic, the others by zxzxz, as asked";
  } else if (options.band_method) {
    module.band_methods.assign(table.order, *options.band_method);
    module.band_methods_reason = std::string("every band by ") + band_method_name(*options.band_method) + ", as asked";
  } else {
    module.band_methods = cheapest_band_methods(module, options, quarter_turn, module.band_methods_reason);
  }
  const Builder builder(module.table, module.lobes, options.zero_bands, module.lobe_stage, options.condon_shortley,
                        module.band_methods, quarter_turn);
  auto wants = [](const std::vector<int>& list, int channels) {
    return std::find(list.begin(), list.end(), channels) != list.end();
  };
  if (options.sh_eval) module.functions.push_back(builder.sh_eval());
  if (options.lobe_multiplies && table.order > 2) {
    module.functions.push_back(builder.sparse_multiply(true));
    module.functions.push_back(builder.sparse_multiply(false));
  }
  for (int channels : {1, 3, 4}) {
    if (wants(options.standard_channels, channels)) module.functions.push_back(builder.rotation(channels, false));
    if (wants(options.tailored_channels, channels)) module.functions.push_back(builder.signal_tailored(channels));
  }
  if (options.batch) module.functions.push_back(builder.rotation(1, true));
  if (!options.dense_channels.empty()) module.functions.push_back(builder.rotation_matrices());
  for (int channels : {1, 3, 4})
    if (wants(options.dense_channels, channels)) module.functions.push_back(builder.apply_rotation_matrices(channels));
  for (int channels : {1, 3, 4})
    if (wants(options.zonal_channels, channels)) module.functions.push_back(builder.zonal_rotation(channels));
  if (options.shading) {
    module.functions.push_back(builder.shading(false));
    if (options.lobe_multiplies && table.order > 2) module.functions.push_back(builder.shading(true));
  }
  if (options.products)
    for (bool square : {false, true}) module.functions.push_back(product_function(table.order, square, options.condon_shortley));
  return module;
}

Module build_lanes_module(const runtime::LobeTable& table) {
  using namespace zhf::tolerance;
  Module module;
  module.kind = ModuleKind::kLanesTables;
  module.order = table.order;
  module.table = table;
  const double model = lanes_float_error_model(table);
  module.lobe_stage = kLanesFloatMargin * model <= kFloatRotation           ? runtime::LobeStage::kFloat
                      : kLanesLobesInDoubleMargin * model <= kFloatRotation ? runtime::LobeStage::kDoubleRotation
                                                                            : runtime::LobeStage::kDouble;
  return module;
}
}  // namespace zhf::codegen
