#include "zhf/frames/cubature.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <sys/stat.h>

#include "zhf/frames/limits.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/sh/reference_rotation.h"

namespace zhf::frames {
namespace {

bool is_file(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

}  // namespace

Cubature gauss_product_cubature(int degree) {
  if (degree < 0 || degree > frames::kMaxCubatureDegree)
    throw std::invalid_argument("cubature degree must be 0.." + std::to_string(frames::kMaxCubatureDegree) + " (got " + std::to_string(degree) + ")");
  const int nz = degree / 2 + 1, nphi = degree + 1;
  std::vector<double> z, wz;
  sh::gauss_legendre(nz, z, wz);
  Cubature c;
  c.degree = degree;
  c.name = "gauss " + std::to_string(nz) + "x" + std::to_string(nphi);
  for (int i = 0; i < nz; ++i) {
    const double s = std::sqrt(std::max(0.0, 1 - z[i] * z[i]));
    for (int k = 0; k < nphi; ++k) {
      const double phi = 2 * runtime::kPi * k / nphi;
      c.points.push_back({s * std::cos(phi), s * std::sin(phi), z[i]});
      c.weights.push_back(wz[i] * 2 * runtime::kPi / nphi);
    }
  }
  return c;
}

Cubature design_cubature(const std::string& folder, int degree) {
  for (int t = std::max(degree, 1); t <= frames::kMaxDesignStrength; ++t) {
    const std::string path = design_path(folder, t);
    if (!is_file(path)) continue;
    Cubature c;
    c.degree = t;
    c.name = "design t=" + std::to_string(t);
    c.points = read_points(path);
    c.weights.assign(c.points.size(), 4 * runtime::kPi / c.points.size());
    return c;
  }
  return gauss_product_cubature(degree);
}

}  // namespace zhf::frames
