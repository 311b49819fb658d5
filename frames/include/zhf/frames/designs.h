// Spherical t-designs: M points whose equal-weight average integrates every polynomial of degree
// <= t over the sphere exactly, i.e. sum_i y_l^m(x_i) = 0 for 1 <= l <= t. Found by minimising the
// design energy E = sum_{1<=l<=t} sum_m (sum_i y_l^m(x_i))^2 with nlopt's L-BFGS from spiral starts,
// then polished by Levenberg-Marquardt on the residual vector itself to the rounding floor.
// Antipodal sets (x and -x) need only the even bands: half the points, a third fewer equations.
// Sets of whole orbits of a group (the 12 rotations of the chiral tetrahedral group, the 3 turns
// about z by 120 degrees, or those turns and x -> -x) leave only the group's invariant harmonics,
// about (t+1)^2 / |G| of them: Levenberg-Marquardt on the orbits' generators alone, from random
// directions, on the residual's coordinates in an orthonormal basis of those harmonics.
//
// Accuracy: a design is accepted when its residual, max_{l,m} |sum_i y_l^m(x_i)| / M, is at most
// zhf::tolerance::kDesignResidual (1e-14). Cost per start: O(M t^2) per energy evaluation and gradient, O(M^3) per
// Levenberg-Marquardt step (M ~ t^2 / 2; for orbits O(M t^2 / |G| + M t^3 / |G|^2 + (M / |G|)^3),
// and the basis once, O(|G| t^3) for the band matrices and O(t^4) for their eigenvectors).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>
#include "zhf/frames/limits.h"
#include "zhf/runtime/limits.h"
#include "zhf/tolerances/tolerances.h"

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
// The same for the 3 turns about z (orbits of 3): at most the efficient count for every t >= 11,
// 3 below the tetrahedral count at odd t = 39, 43, 51, ...
int threefold_count(int t);
// The same for orbits of 6: the three turns and x -> -x (only the even bands' harmonics with
// 3 | m remain). At most the antipodal count at every odd t from 11.
int antipodal_threefold_count(int t);

// The symmetry a search keeps: free points, antipodal pairs (x and -x: odd bands vanish, half the
// unknowns), or whole orbits of the tetrahedral group, the threefold turns, or the threefold turns
// and x -> -x.
enum class Symmetry { kFree, kAntipodal, kTetrahedral, kThreefold, kAntipodalThreefold };
int orbit_size(Symmetry symmetry);  // 1, 2, 12, 3, 6: the count is a multiple of it
// "free", "antipodal", "tetrahedral", "threefold", "antipodal threefold".
const char* symmetry_name(Symmetry symmetry);

// What zhf designs searches by default: the smallest known count for t <= 10; antipodal sets for
// odd t = 11..21 (the smallest known count, Womersley's at 19 and 21); whole orbits for even
// t >= 12, tetrahedral unless the threefold count is smaller (the smallest known count at even t up
// to 20), and for odd t >= 23 antipodal threefold orbits, or antipodal sets where those need fewer
// points (t = 25, 37, ..., 97: 2 fewer). Never above the smallest known count (t <= 21), the
// antipodal count (t >= 19) or the efficient count (t >= 11).
struct DesignChoice {
  int points = 0;
  Symmetry symmetry = Symmetry::kFree;
};
DesignChoice default_design(int t);
// The count a search of this symmetry takes at t when none is given: the default's where the
// default has this symmetry, otherwise the symmetry's own (its invariants' count; the antipodal
// count for antipodal sets; the efficient count for free sets).
int symmetry_count(Symmetry symmetry, int t);

struct DesignSearch {
  int t = 0;
  int points = 0;            // M
  int starts = 32;           // tried in order; the first that converges wins
  std::uint64_t seed = 1;
  int threads = 1;           // starts run in parallel; the result does not depend on this
  Symmetry symmetry = Symmetry::kFree;  // points a multiple of orbit_size(symmetry)
  std::function<bool()> interrupted;  // checked between starts, and within orbit searches (basis, steps)
  std::function<void(int)> progress;  // told how many starts were tried, between starts
};

struct Design {
  int t = 0;
  std::vector<Point> points;
  double residual = 1;       // design_residual
  int start = -1;            // which start converged (-1: none did; points are the best found)
};

// Throws std::invalid_argument for t outside 1..frames::kMaxDesignStrength, a count below 2 or
// not whole orbits.
Design search_design(const DesignSearch& search);

// Point sets in files: a JSON array of [x, y, z], or an object with "points" such (a design file,
// "format": "zhf-design-1"). Nonzero finite vectors, normalised; up to frames::kMaxDesignPoints of them, files up
// to runtime::kMaxTableBytes. Throws runtime::InputError naming the file and entry.
std::vector<Point> read_points(const std::string& path);
inline constexpr const char* kDesignFormat = "zhf-design-1";
// A design of strength t in a folder of designs (generated/designs): folder/t_T.json.
inline std::string design_path(const std::string& folder, int t) { return folder + "/t_" + std::to_string(t) + ".json"; }

}  // namespace zhf::frames
