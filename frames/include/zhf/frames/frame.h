// Frames of zonal lobes. A set of unit directions w_1..w_M and a band range lmin..lmax give the
// lobes e_i(w) = sum_{l in range} sum_m y_l^m(w_i) y_l^m(w), and the analysis operator
// Phi f = (<e_i, f>)_i = (f(w_i))_i on the functions of those bands (dimension D = sum (2l+1)).
// The frame bounds A <= B are the extreme eigenvalues of the frame operator S = Phi^T Phi
// (D x D); the set is a frame when A > 0, tight when A = B, Parseval tight when A = B = 1 (a
// tight frame scaled by 1/sqrt(A) is Parseval). The Gram matrix Phi Phi^T (M x M) holds
// <e_i, e_j> = sum_l (2l+1)/(4 pi) P_l(w_i . w_j). Redundancy M / D; condition sqrt(B / A), which
// for one band and 2l+1 lobes is the lobe table's condition number of Y_l.
//
// A t-design with t >= 2 lmax makes S = (M / 4 pi) I on any band range up to lmax (the products
// y y' have degree <= t): a tight frame with A = M / 4 pi.
// Cost: O(M D^2 + D^3). Accuracy: eigenvalues to ~1e-15 B.
#pragma once

#include <vector>

#include "zhf/frames/designs.h"
#include "zhf/frames/limits.h"
#include "zhf/tolerances/tolerances.h"

namespace zhf::frames {


struct FrameBounds {
  int lmin = 0, lmax = 0;
  int directions = 0;       // M
  int dimension = 0;        // D
  double lower = 0, upper = 0;  // A, B
  bool frame() const { return lower > zhf::tolerance::kSpanning * upper; }
  bool tight() const { return upper > 0 && (upper - lower) <= zhf::tolerance::kTightFrame * upper; }
  bool parseval() const;
  double redundancy() const { return double(directions) / dimension; }
  double condition() const;  // sqrt(B / A); infinite when not a frame
};

// Throws std::invalid_argument for an empty set or a band range outside 0..frames::kMaxFrameBand.
FrameBounds frame_bounds(const std::vector<Point>& directions, int lmin, int lmax);

}  // namespace zhf::frames
