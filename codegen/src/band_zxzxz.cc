#include "band_zxzxz.h"

#include <utility>

#include "zhf/runtime/tolerances.h"

namespace zhf::codegen {
namespace {

// c[m] = cos(m t), s[m] = sin(m t), m <= top: even m by doubling m/2, (c - s)(c + s) and 2cs; odd
// m by adding t to m - 1. Error ~m eps however close t is to 0 or pi; the cheaper Chebyshev
// recurrence x_m = 2 cos t x_{m-1} - x_{m-2} amplifies cos t's rounding by m^2 there, past float's
// tolerance at order 5.
void multiples(Graph& g, int cos_t, int sin_t, int top, std::vector<int>& c, std::vector<int>& s) {
  c = {g.constant(1), cos_t};
  s = {g.constant(0), sin_t};
  for (int m = 2; m <= top; ++m) {
    if (m % 2 == 0) {
      const int ch = c[m / 2], sh = s[m / 2], cs = g.mul(ch, sh);
      c.push_back(g.mul(g.sub(ch, sh), g.add(ch, sh)));
      s.push_back(g.add(cs, cs));
    } else {
      c.push_back(g.sub(g.mul(c[m - 1], cos_t), g.mul(s[m - 1], sin_t)));
      s.push_back(g.add(g.mul(s[m - 1], cos_t), g.mul(c[m - 1], sin_t)));
    }
  }
}

// Band l (v[m + l]) turned about z: g(phi) = f(phi - t) sends the (m, -m) weights (x, y) to
// (x cos mt - y sin mt, x sin mt + y cos mt).
std::vector<int> turn(Graph& g, int l, const std::vector<int>& c, const std::vector<int>& s, std::vector<int> v) {
  for (int m = 1; m <= l; ++m) {
    const int x = v[l + m], y = v[l - m];
    v[l + m] = g.sub(g.mul(c[m], x), g.mul(s[m], y));
    v[l - m] = g.add(g.mul(s[m], x), g.mul(c[m], y));
  }
  return v;
}

// X_l v or X_l^T v, X_l = D_l(Rx(+90 deg)), whose exact zeros and units the graph folds away.
std::vector<int> quarter_turn(Graph& g, int l, const Eigen::MatrixXd& x, const std::vector<int>& v, bool transpose) {
  std::vector<int> out(2 * l + 1);
  for (int i = 0; i < 2 * l + 1; ++i) {
    std::vector<std::pair<double, int>> terms;
    for (int j = 0; j < 2 * l + 1; ++j) terms.push_back({transpose ? x(j, i) : x(i, j), v[j]});
    out[i] = g.linear(terms);
  }
  return out;
}

}  // namespace

EulerTurns euler_turns(Graph& g, const std::vector<bool>& bands) {
  EulerTurns t;
  int top = 0;
  for (int l = 0; l < int(bands.size()); ++l)
    if (bands[l]) top = l;
  if (top == 0) return t;
  auto r = [&](int i, int j) { return g.input(0, 3 * i + j); };
  // (cos a, sin a) sin b = (R_02, R_12); below kGimbalLockSine2 any a works: a = 0.
  const int column2 = g.add(g.mul(r(0, 2), r(0, 2)), g.mul(r(1, 2), r(1, 2)));
  const int unlocked = g.sub(column2, g.constant(runtime::tolerance::kGimbalLockSine2));
  const int inverse = g.rsqrt(g.select_positive(unlocked, column2, g.constant(1)));
  const int cos_a = g.select_positive(unlocked, g.mul(r(0, 2), inverse), g.constant(1));
  const int sin_a = g.select_positive(unlocked, g.mul(r(1, 2), inverse), g.constant(0));
  const int sin_b = g.mul(column2, inverse);
  // Rz(-a) R = Ry(b) Rz(g), whose middle row is (sin g, cos g, 0).
  const int sin_g = g.sub(g.mul(cos_a, r(1, 0)), g.mul(sin_a, r(0, 0)));
  const int cos_g = g.sub(g.mul(cos_a, r(1, 1)), g.mul(sin_a, r(0, 1)));
  multiples(g, cos_a, sin_a, top, t.cos_a, t.sin_a);
  multiples(g, r(2, 2), sin_b, top, t.cos_b, t.sin_b);
  multiples(g, cos_g, sin_g, top, t.cos_g, t.sin_g);
  return t;
}

std::vector<int> zxzxz_band(Graph& g, int l, const EulerTurns& t, const Eigen::MatrixXd& x, std::vector<int> v) {
  v = turn(g, l, t.cos_g, t.sin_g, v);
  v = quarter_turn(g, l, x, v, /*transpose=*/false);
  v = turn(g, l, t.cos_b, t.sin_b, v);
  v = quarter_turn(g, l, x, v, /*transpose=*/true);
  return turn(g, l, t.cos_a, t.sin_a, v);
}

}  // namespace zhf::codegen
