// Other partitions of the bands than the standard needlet window (needlets.h), side by side:
// the windows themselves, how close their squares come to summing to 1 over the levels (a tight
// frame needs exactly 1), and how local each level's kernel is on the sphere.
//
//   standard  b(x) = sqrt(phi(x / B) - phi(x)), phi from the C-infinity bump (needlets.h).
//   spline    the same construction with phi from the cubic B-spline: psi(u) = the integral of
//             the centred cubic B-spline M up to 2u (M on [-2, 2], unit mass), a piecewise
//             quartic step, C^3 where the bump's is C-infinity. Bands per level as the standard;
//             the squares telescope to 1 exactly.
//   mexican   b(x) = x^(2p) exp(-x^2) (Geller and Mayeli's Mexican needlets of order p): every
//             band at every level, Gaussian tails in l instead of compact support, and a frame
//             that is not tight: sum_j b^2(l / B^j) over all integers j lies between two bounds
//             A <= B' that the report states.
//
// Level j's kernel is K_j(t) = sum_l b(l / B^j) L_l(t), L_l(t) = (2l+1)/(4 pi) P_l(t), centred on
// a direction; its energy is |K_j|^2 = sum_l b^2 (2l+1) / (4 pi).
#pragma once

#include <string>
#include <vector>

#include "zhf/frames/limits.h"
#include "zhf/frames/needlets.h"

namespace zhf::frames {

enum class WindowKind { kStandard, kSpline, kMexican };

// "standard", "spline", "mexican", or false.
bool parse_window_kind(const std::string& name, WindowKind& kind);
const char* window_kind_name(WindowKind kind);

struct Window {
  WindowKind kind = WindowKind::kStandard;
  double dilation = 2;  // B in [frames::kMinDilation, frames::kMaxDilation]
  int order = 1;        // mexican: p in 1..frames::kMaxMexicanOrder
};

// The cubic B-spline step: 0 for u <= -1, 1 for u >= 1, psi(u) + psi(-u) = 1. Exact to rounding.
double spline_step(double u);

// b(x) for x >= 0. Throws std::invalid_argument for a dilation or order out of range.
double window_value(const Window& w, double x);

// The levels j (any integer) at which band l's window is not negligible: b > 0 for the compact
// windows, b^2 above zhf::tolerance::kWindowNegligible of the sum's for the Mexican one.
struct LevelRange {
  int first, last;
};
LevelRange levels_of_band(const Window& w, int l);
// The bands l >= 1 of level j, the same way.
struct BandRange {
  int first, last;
};
BandRange bands_of_level(const Window& w, int j);

// Every non-negligible b(l / B^j) for bands l = 1..lmax, level by level (j from the least that
// reaches band 1), band by band. Throws std::invalid_argument for lmax outside
// 0..frames::kMaxNeedletBand.
std::vector<WindowValue> window_values(const Window& w, int lmax);

// sum over the levels of b^2(l / B^j), band l >= 1: 1 for standard and spline.
double window_square_sum(const Window& w, int l);

// The fraction of level j's kernel energy outside the cap of angular radius `radius` (radians,
// in (0, pi]) around its centre: needlets.h's localisation() of K_j. Levels reaching past
// frames::kMaxProfileBand are refused (std::invalid_argument). Cost: O(n^2) for the n bands.
double kernel_energy_outside(const Window& w, int j, double radius);

}  // namespace zhf::frames
