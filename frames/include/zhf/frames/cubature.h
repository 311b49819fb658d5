// Cubatures: nodes and weights on the sphere that integrate every polynomial up to a degree
// exactly. The needlet frame puts each level on one, the tight-frame rotation its lobes.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "zhf/frames/designs.h"
#include "zhf/frames/limits.h"

namespace zhf::frames {

// Nodes and weights (summing to 4 pi) integrating every polynomial of degree <= `degree` exactly.
struct Cubature {
  int degree = 0;
  std::vector<Point> points;
  std::vector<double> weights;
  std::string name;  // "design t=6", "gauss 4x9"
};
// Gauss-Legendre in z (degree/2 + 1 nodes) times equally spaced phi (degree + 1): exact to
// `degree`, for any degree; about degree^2 / 2 nodes, twice a design's count.
// Throws std::invalid_argument for a degree outside 0..frames::kMaxCubatureDegree (64 Gauss-Legendre
// nodes, the most sh/'s root finder gives).
Cubature gauss_product_cubature(int degree);
// The equal-weight rule of a design of strength >= degree, read from `folder`/t_T.json (the
// smallest T that is there); the Gauss product where no shipped design is strong enough.
Cubature design_cubature(const std::string& folder, int degree);
using CubatureSource = std::function<Cubature(int degree)>;

}  // namespace zhf::frames
