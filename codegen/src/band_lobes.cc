#include "band_lobes.h"

#include <algorithm>
#include <cmath>

#include "zhf/runtime/rotation.h"
#include "zhf/runtime/tolerances.h"

namespace zhf::codegen {

std::vector<int> band_sums(Graph& g, const runtime::Matrix& inverse, bool transpose, int base) {
  std::vector<int> sums;
  for (int i = 0; i < inverse.rows; ++i) {
    std::vector<std::pair<double, int>> terms;
    for (int k = 0; k < inverse.rows; ++k) terms.push_back({transpose ? inverse(k, i) : inverse(i, k), g.input(0, base + k)});
    sums.push_back(g.linear(terms));
  }
  return sums;
}

Legendre::Legendre(int order) : sigma(order, std::vector<double>(order, 0.0)) {
  using K = runtime::LegendreCoefficients<>;
  double q_mm = runtime::kInvSqrt4Pi;
  for (int m = 0; m < order; ++m) {
    if (m > 0) q_mm *= K::diagonal(m);
    sigma[m][m] = q_mm;
    if (m + 1 < order) sigma[m + 1][m] = K::subdiagonal(m) * q_mm;
    for (int l = m + 2; l < order; ++l) sigma[l][m] = K::a(l, m) * sigma[l - 1][m];
  }
}

double Legendre::c(int l, int m, double r2) const {
  return runtime::LegendreCoefficients<>::b(l, m) * r2 * sigma[l - 2][m] / sigma[l - 1][m];
}

double Legendre::output_scale(int l, int m) const { return (m == 0 ? 1.0 : runtime::kSqrt2) * sigma[l][std::abs(m)]; }

std::vector<int> homogeneous_sh(Graph& g, const Vec3& v, double r2, int order, const std::vector<bool>& bands,
                                const Legendre& legendre) {
  std::vector<int> out(runtime::coefficient_count(order), -1);
  const int x = v.c[0], y = v.c[1], z = v.c[2];
  int top = -1;
  for (int l = 0; l < order; ++l)
    if (bands[l]) top = l;
  int c_m = g.constant(1), s_m = g.constant(0);
  for (int m = 0; m <= top; ++m) {
    if (m == 1) {
      c_m = x;
      s_m = y;
    } else if (m == 2) {
      c_m = g.mul(g.sub(x, y), g.add(x, y));  // x^2 - y^2
      const int xy = g.mul(x, y);
      s_m = g.add(xy, xy);                    // 2xy
    } else if (m > 2) {
      const int c_next = g.sub(g.mul(x, c_m), g.mul(y, s_m));
      s_m = g.add(g.mul(x, s_m), g.mul(y, c_m));
      c_m = c_next;
    }
    int q_prev = -1, q = g.constant(1);
    for (int l = m; l <= top; ++l) {
      if (l == m + 1) {
        q_prev = q;
        q = z;
      } else if (l > m + 1) {
        const int next = g.sub(g.mul(z, q), g.scale(legendre.c(l, m, r2), q_prev));
        q_prev = q;
        q = next;
      }
      if (!bands[l]) continue;
      if (m == 0) {
        out[runtime::index(l, 0)] = q;
      } else {
        out[runtime::index(l, m)] = g.mul(q, c_m);
        out[runtime::index(l, -m)] = g.mul(q, s_m);
      }
    }
  }
  return out;
}

void scale_lobe(const double w[3], double u[3]) {
  double largest = 0, smallest = INFINITY;
  for (int k = 0; k < 3; ++k) {
    const double a = std::abs(w[k]);
    if (a == 0) continue;
    largest = std::max(largest, a);
    smallest = std::min(smallest, a);
  }
  // All nonzero components equal in magnitude: scale them to exactly +-1; otherwise make
  // the largest one +-1 (one column of R then needs no multiply).
  const bool equal = largest - smallest <= runtime::tolerance::kExactEntry * largest;
  for (int k = 0; k < 3; ++k) {
    if (w[k] == 0) {
      u[k] = 0;
    } else if (equal) {
      u[k] = w[k] > 0 ? 1.0 : -1.0;
    } else {
      u[k] = w[k] / largest;
    }
  }
}

double norm2(const double u[3]) { return u[0] * u[0] + u[1] * u[1] + u[2] * u[2]; }

Vec3 rotated_lobe(Graph& g, const std::vector<int>& r, const double u[3], bool transpose) {
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    std::vector<std::pair<double, int>> terms;
    for (int j = 0; j < 3; ++j) terms.push_back({u[j], r[transpose ? 3 * j + i : 3 * i + j]});
    v.c[i] = g.linear(terms);
  }
  return v;
}

std::vector<int> orthonormalized_rotation(Graph& g) {
  std::vector<int> gram(9);  // R^T R
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      std::vector<std::pair<double, int>> terms;
      for (int k = 0; k < 3; ++k) terms.push_back({1.0, g.mul(g.input(0, 3 * k + i), g.input(0, 3 * k + j))});
      gram[3 * i + j] = gram[3 * j + i] = g.linear(terms);
    }
  std::vector<int> step(9);  // (3 I - R^T R) / 2
  for (int i = 0; i < 9; ++i)
    step[i] = i % 4 == 0 ? g.sub(g.constant(1.5), g.scale(0.5, gram[i])) : g.scale(-0.5, gram[i]);
  std::vector<int> q(9);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      std::vector<std::pair<double, int>> terms;
      for (int k = 0; k < 3; ++k) terms.push_back({1.0, g.mul(g.input(0, 3 * i + k), step[3 * k + j])});
      q[3 * i + j] = g.linear(terms);
    }
  return q;
}

}  // namespace zhf::codegen
