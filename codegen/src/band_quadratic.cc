#include "band_quadratic.h"

#include "band_lobes.h"

namespace zhf::codegen {

// M from f:
//   M_xy = f_-2, M_yz = f_-1, M_xz = f_1, M_xx = f_2 - f_0/sqrt3, M_yy = -f_2 - f_0/sqrt3, M_zz = 2 f_0/sqrt3
// (y_2^-2 = K xy, y_2^-1 = K yz, y_2^1 = K xz, y_2^2 = K (x^2 - y^2)/2, y_2^0 = K (3z^2 - 1)/(2 sqrt3)).
// M'_ij = r_i . (M r_j), r_i the rows of R. Five entries suffice, all from M r_1 and M r_2: M'_xy,
// M'_yy, M'_yz, M'_xz, M'_zz, with M'_xx = -M'_yy - M'_zz (R orthogonal keeps the trace 0), so
// f'_2 = (M'_xx - M'_yy)/2 = -M'_yy - M'_zz/2 and f'_0 = (sqrt3/2) M'_zz.
std::vector<int> quadratic_band(Graph& g, const std::vector<int>& v) {
  const double inverse_sqrt3 = 0.57735026918962576451, half_sqrt3 = 0.86602540378443864676;
  const int t = g.scale(inverse_sqrt3, v[2]);
  const int m[3][3] = {{g.sub(v[4], t), v[0], v[3]}, {v[0], g.linear({{-1.0, v[4]}, {-1.0, t}}), v[1]}, {v[3], v[1], g.add(t, t)}};
  auto r = [&](int i, int j) { return g.input(0, 3 * i + j); };
  auto m_times_row = [&](int j) {
    Vec3 p;
    for (int a = 0; a < 3; ++a) p.c[a] = g.linear({{1.0, g.mul(m[a][0], r(j, 0))}, {1.0, g.mul(m[a][1], r(j, 1))}, {1.0, g.mul(m[a][2], r(j, 2))}});
    return p;
  };
  auto entry = [&](int i, const Vec3& p) {
    return g.linear({{1.0, g.mul(r(i, 0), p.c[0])}, {1.0, g.mul(r(i, 1), p.c[1])}, {1.0, g.mul(r(i, 2), p.c[2])}});
  };
  const Vec3 p1 = m_times_row(1), p2 = m_times_row(2);
  const int yy = entry(1, p1), zz = entry(2, p2);
  return {entry(0, p1), entry(1, p2), g.scale(half_sqrt3, zz), entry(0, p2), g.linear({{-1.0, yy}, {-0.5, zz}})};
}

}  // namespace zhf::codegen
