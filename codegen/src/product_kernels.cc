// The SH product kernels: h = P_N(f g) and P_N(f^2) (runtime/product.h) as one expression graph,
// by whichever of two factorings needs fewer multiplies at the order.
//
// Pairs (cheaper at low orders). h_c = sum G_abc f_a g_b over the Gaunt table: band 0 couples by
// G_0bc = delta_bc / sqrt(4 pi), so f_0 and g_0 are scaled once and h_c gets f0' g_c + f_c g0';
// every other pair product s_ab = f_a g_b + f_b g_a is formed once and shared by the outputs, which
// sum it with terms of equal |G| sharing one multiply.
//
// Gauss-Fourier (cheaper from order 4). Write f = sum_m G_m(z) trig_m(phi) with trig_m = cos(m phi),
// 1 or sin(|m| phi) and G_m(z) = sum_l f_lm E_lm(z) (E_lm: y_lm without its trig factor). Then
//   f g = sum_{m1,m2} G_m1 G_m2 trig_m1 trig_m2,  trig products = (trig_sum +- trig_difference)/2,
// so every output frequency m3 collects S_m3(z) = sum of +-G_m1 G_m2 with additions only (the
// values are pre-scaled by 1/sqrt2 so the halves vanish: band-0 terms are doubled by an addition), and
//   h_l3m3 = Phi_m3 int E_l3m3(z) S_m3(z) dz,  Phi = 2 pi (m3 = 0) or pi.
// The z integrand is a polynomial of degree l3 + 2N - 2 (sin powers pair up to even ones), so
// K = ceil((3N - 2) / 2) Gauss-Legendre nodes make it exact. E has parity (-1)^(l-|m|): each G_m
// is an even and an odd sum at the positive nodes, and each output a sum over positive nodes of
// S(z) + S(-z) or S(z) - S(-z). Multiplies: evaluation 2 N^2 K / 2, products (2N-1)^2 K,
// projection N^2 K / 2, against the N^4 pair products the pairs factoring starts from.
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "zhf/codegen/kernels.h"
#include "zhf/runtime/gaunt.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/reference_rotation.h"

namespace zhf::codegen {
namespace {

using runtime::band_of;
using runtime::index;
using runtime::kPi;

// The inputs of f and g (g = f for the square).
struct Operands {
  int f_param, g_param;
  bool square() const { return f_param == g_param; }
};

std::vector<int> pairs_factoring(Graph& g, int order, Operands in) {
  const int n = order * order;
  const std::vector<runtime::GauntEntry> table = runtime::gaunt_table(order);
  const int f0 = g.scale(runtime::kInvSqrt4Pi, g.input(in.f_param, 0));
  const int g0 = in.square() ? f0 : g.scale(runtime::kInvSqrt4Pi, g.input(in.g_param, 0));
  std::vector<std::vector<std::pair<double, int>>> terms(n);
  std::map<std::pair<int, int>, int> pair_products;
  for (const runtime::GauntEntry& e : table) {
    if (e.a == 0) {  // G_0bc: delta_bc / sqrt(4 pi), folded into f0 and g0
      const int fb = g.input(in.f_param, e.b), gb = g.input(in.g_param, e.b);
      terms[e.c].push_back({1.0, e.b == 0 ? g.mul(f0, gb) : g.add(g.mul(f0, gb), g.mul(fb, g0))});
      continue;
    }
    auto [it, fresh] = pair_products.try_emplace({e.a, e.b}, -1);
    if (fresh) {
      const int fa = g.input(in.f_param, e.a), fb = g.input(in.f_param, e.b);
      const int ga = g.input(in.g_param, e.a), gb = g.input(in.g_param, e.b);
      // f_a f_b appears twice in the square's s_ab: the 2 goes into the coefficient below.
      it->second = e.a == e.b || in.square() ? g.mul(fa, gb) : g.add(g.mul(fa, gb), g.mul(fb, ga));
    }
    terms[e.c].push_back({e.a != e.b && in.square() ? 2 * e.value : e.value, it->second});
  }
  std::vector<int> h(n);
  for (int c = 0; c < n; ++c) h[c] = terms[c].empty() ? g.constant(0) : g.linear(terms[c]);
  return h;
}

// E_lm(z) / sqrt2 at z (sin theta >= 0), for every l, m of the order: y_lm without trig factor.
std::vector<double> scaled_e(int order, double z) {
  // At phi = 0 the cosine factors are 1, and E_l,-m = E_l,m.
  const double dir[3] = {std::sqrt(std::max(0.0, 1 - z * z)), 0, z};
  std::vector<double> y(order * order), e(order * order);
  runtime::eval_sh(order, dir, y.data());
  for (int l = 0; l < order; ++l)
    for (int m = -l; m <= l; ++m) e[index(l, m)] = y[index(l, std::abs(m))] / runtime::kSqrt2;
  return e;
}

std::vector<int> gauss_fourier_factoring(Graph& g, int order, Operands in) {
  const int n = order * order, top = order - 1, frequencies = 2 * order - 1;
  const int k_nodes = (3 * order - 1) / 2;  // ceil((3N - 2) / 2)
  std::vector<double> nodes, weights;
  sh::gauss_legendre(k_nodes, nodes, weights);
  // The nodes are symmetric: positive node p stands for +z_p and -z_p; odd K adds the center z = 0
  // (computed as a root, so within rounding of 0).
  std::vector<int> positive;
  auto is_center = [&](int k) { return std::abs(nodes[k]) < zhf::tolerance::kCenterNode; };
  for (int k = 0; k < k_nodes; ++k)
    if (nodes[k] > 0 || is_center(k)) positive.push_back(k);
  std::vector<std::vector<double>> e;  // per positive node
  for (int k : positive) e.push_back(scaled_e(order, is_center(k) ? 0.0 : nodes[k]));

  // values[m + top][2p + sign]: G_m / sqrt2 at +z_p (sign 0) and -z_p (sign 1); the center once.
  auto evaluate = [&](int param) {
    std::vector<std::vector<int>> values(frequencies, std::vector<int>(2 * positive.size(), -1));
    for (int m = -top; m <= top; ++m)
      for (size_t p = 0; p < positive.size(); ++p) {
        std::vector<std::pair<double, int>> even, odd;
        for (int l = std::abs(m); l < order; ++l)
          ((l - std::abs(m)) % 2 ? odd : even).push_back({e[p][index(l, m)], g.input(param, index(l, m))});
        const int ev = even.empty() ? g.constant(0) : g.linear(even);
        const int od = odd.empty() || is_center(positive[p]) ? g.constant(0) : g.linear(odd);
        values[m + top][2 * p] = g.add(ev, od);
        values[m + top][2 * p + 1] = g.sub(ev, od);
      }
    return values;
  };
  const std::vector<std::vector<int>> fv = evaluate(in.f_param);
  const std::vector<std::vector<int>> gv = in.square() ? fv : evaluate(in.g_param);

  // Frequency bins S_m3 at every node: signed sums of products.
  std::vector<std::vector<std::vector<int>>> bins(frequencies, std::vector<std::vector<int>>(2 * positive.size()));
  auto deposit = [&](int m3, int sign, int slot, int node) {
    if (std::abs(m3) > top) return;
    bins[m3 + top][slot].push_back(sign > 0 ? node : g.neg(node));
  };
  for (int m1 = -top; m1 <= top; ++m1)
    for (int m2 = in.square() ? m1 : -top; m2 <= top; ++m2)
      for (size_t slot = 0; slot < 2 * positive.size(); ++slot) {
        if (slot % 2 && is_center(positive[slot / 2])) continue;
        int p = g.mul(fv[m1 + top][slot], gv[m2 + top][slot]);
        if (in.square() && m1 != m2) p = g.add(p, p);  // (m1, m2) and (m2, m1)
        const int a = std::abs(m1), b = std::abs(m2);
        if (a == 0 || b == 0) {  // 2 G G trig: the 2 is an addition
          deposit(m1 + m2, 1, slot, g.add(p, p));
          continue;
        }
        const int sum = a + b, difference = a - b;
        if (m1 > 0 && m2 > 0) {  // 2 cos a cos b = cos(a+b) + cos(a-b)
          deposit(sum, 1, slot, p);
          deposit(std::abs(difference), 1, slot, p);
        } else if (m1 < 0 && m2 < 0) {  // 2 sin a sin b = cos(a-b) - cos(a+b)
          deposit(std::abs(difference), 1, slot, p);
          deposit(sum, -1, slot, p);
        } else {  // 2 sin a cos b = sin(a+b) + sin(a-b), sin(-d) = -sin(d), sin 0 = 0
          const int sine_first = m1 < 0 ? 1 : -1;  // which factor is the sine: sin(a-b) or sin(b-a)
          deposit(-sum, 1, slot, p);
          if (difference != 0) deposit(-std::abs(difference), sine_first * (difference > 0 ? 1 : -1), slot, p);
        }
      }
  auto total = [&](const std::vector<int>& nodes_in) {
    if (nodes_in.empty()) return g.constant(0);
    int s = nodes_in[0];
    for (size_t i = 1; i < nodes_in.size(); ++i) s = g.add(s, nodes_in[i]);
    return s;
  };

  std::vector<int> h(n);
  for (int l = 0; l < order; ++l)
    for (int m = -l; m <= l; ++m) {
      const double phi_integral = m == 0 ? 2 * kPi : kPi;
      const bool odd = (l - std::abs(m)) % 2;
      std::vector<std::pair<double, int>> terms;
      for (size_t p = 0; p < positive.size(); ++p) {
        const int k = positive[p];
        const int plus = total(bins[m + top][2 * p]);
        int folded = plus;
        if (!is_center(k)) {
          const int minus = total(bins[m + top][2 * p + 1]);
          folded = odd ? g.sub(plus, minus) : g.add(plus, minus);
        } else if (odd) {
          continue;  // E vanishes at z = 0
        }
        // e holds E / sqrt2: the projection needs E itself.
        terms.push_back({phi_integral * weights[k] * runtime::kSqrt2 * e[p][index(l, m)], folded});
      }
      h[index(l, m)] = g.linear(terms);
    }
  return h;
}

}  // namespace

const char* product_factoring_name(ProductFactoring factoring) {
  return factoring == ProductFactoring::kPairs ? "pairs" : "gauss-fourier";
}

Function product_function(int order, bool square, ProductFactoring factoring, bool condon_shortley) {
  Function f;
  f.kind = square ? KernelKind::kSquare : KernelKind::kProduct;
  f.channels = 1;
  f.member = square ? "square" : "product";
  f.name = f.member + "_order" + std::to_string(order);
  const int n = order * order;
  f.params = square ? std::vector<Param>{{"f", n, false, 1}, {"h", n, true, 1}}
                    : std::vector<Param>{{"f", n, false, 1}, {"g", n, false, 1}, {"h", n, true, 1}};
  const Operands in = square ? Operands{0, 0} : Operands{0, 1};
  const std::vector<int> odd = odd_m_indices(n);
  if (condon_shortley)
    for (int param = 0; param <= in.g_param; ++param) f.graph.negate_inputs(param, odd);
  std::vector<int> h = factoring == ProductFactoring::kPairs ? pairs_factoring(f.graph, order, in)
                                                                    : gauss_fourier_factoring(f.graph, order, in);
  f.doc = std::string(square ? "h = f^2" : "h = f g") + " projected to order " + std::to_string(order) +
          " (SH product; factoring: " + product_factoring_name(factoring) + ")";
  if (condon_shortley) {
    for (int c : odd) h[c] = f.graph.neg(h[c]);
    f.doc += "; Condon-Shortley signs ((-1)^m)";
  }
  for (int c = 0; c < n; ++c) f.outputs.push_back({square ? 1 : 2, c, h[c]});
  return f;
}

Function product_function(int order, bool square, bool condon_shortley) {
  Function pairs = product_function(order, square, ProductFactoring::kPairs, condon_shortley);
  Function gauss = product_function(order, square, ProductFactoring::kGaussFourier, condon_shortley);
  return pairs.graph.count(pairs.output_nodes()).multiplies <= gauss.graph.count(gauss.output_nodes()).multiplies ? pairs : gauss;
}

}  // namespace zhf::codegen
