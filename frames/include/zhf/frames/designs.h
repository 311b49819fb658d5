// Spherical t-designs: M points whose equal-weight average integrates every polynomial of degree
// <= t over the sphere exactly, i.e. sum_i y_l^m(x_i) = 0 for 1 <= l <= t. Found by minimising the
// design energy E = sum_{1<=l<=t} sum_m (sum_i y_l^m(x_i))^2 with nlopt's L-BFGS from spiral starts,
// then polished by Levenberg-Marquardt on the residual vector itself to the rounding floor.
// Antipodal sets (x and -x) need only the even bands: half the points, a third fewer equations.
// Tetrahedral sets (whole orbits of the 12 rotations of the chiral tetrahedral group) leave only
// the group's invariant harmonics, about (t+1)^2 / 12 of them: Levenberg-Marquardt on the orbits'
// generators alone, from random directions, a few dozen to a few hundred parameters.
//
// Accuracy: a design is accepted when its residual, max_{l,m} |sum_i y_l^m(x_i)| / M, is at most
// runtime::tolerance::kDesignResidual (1e-14). Cost per start: O(M t^2) per energy evaluation and gradient, O(M^3) per
// Levenberg-Marquardt step (M ~ t^2 / 2).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>
#include "zhf/runtime/limits.h"
#include "zhf/runtime/tolerances.h"

namespace zhf::frames {

using Point = std::array<double, 3>;


// max over 1 <= l <= t and m of |sum_i y_l^m(x_i)| / M.
double design_residual(const std::vector<Point>& points, int t);

// The smallest point counts known for t = 1..21 (Hardin and Sloane's library; Womersley's
// symmetric designs do better at t = 19 (192) and t = 21 (234)), and Womersley's efficient count
// ceil((t+1)^2 / 2) + 1 for any t.
int best_known_count(int t);
int efficient_count(int t);
// Antipodal designs (x and -x both in the set: every odd band vanishes): the smallest even count
// whose free parameters, 2 (M/2) - 3, match the equations of the even bands 2..t. Womersley's
// symmetric designs reach it (t = 19: 192, t = 21: 234).
int symmetric_count(int t);
// Sets of whole orbits of the chiral tetrahedral group (12 rotations): only the group's invariant
// harmonics can be non-zero, so the smallest multiple of 12 whose free parameters (2 per orbit)
// match their count. Hardin and Sloane's counts at even t = 12..20; 2 to 6 below the efficient
// count at larger even t.
int tetrahedral_count(int t);

// What zhf designs searches by default: the smallest known count for t <= 10; antipodal sets for
// odd t = 11..31 (the smallest known count up to 21, Womersley's at 19 and 21, the symmetric count
// above); tetrahedral sets for even t >= 12 (the smallest known count up to 20) and odd t >= 33.
struct DesignChoice {
  int points = 0;
  bool symmetric = false;
  bool tetrahedral = false;
};
DesignChoice default_design(int t);

struct DesignSearch {
  int t = 0;
  int points = 0;            // M
  int starts = 32;           // tried in order; the first that converges wins
  std::uint64_t seed = 1;
  int threads = 1;           // starts run in parallel; the result does not depend on this
  bool symmetric = false;    // antipodal pairs (points even)
  bool tetrahedral = false;  // whole orbits of the chiral tetrahedral group (points a multiple of 12)
  std::function<bool()> interrupted;  // checked between starts
  std::function<void(int)> progress;  // told how many starts were tried, between starts
};

struct Design {
  int t = 0;
  std::vector<Point> points;
  double residual = 1;       // design_residual
  int start = -1;            // which start converged (-1: none did; points are the best found)
};

// Throws std::invalid_argument for t outside 1..runtime::kMaxDesignStrength or a count below 2.
Design search_design(const DesignSearch& search);

// Point sets in files: a JSON array of [x, y, z], or an object with "points" such (a design file,
// "format": "zhf-design-1"). Nonzero finite vectors, normalised; up to runtime::kMaxDesignPoints of them, files up
// to runtime::kMaxTableBytes. Throws runtime::InputError naming the file and entry.
std::vector<Point> read_points(const std::string& path);
inline constexpr const char* kDesignFormat = "zhf-design-1";

}  // namespace zhf::frames
