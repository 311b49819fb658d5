// The needlet frame's measured properties, as the `zhf needlets` commands report them: the kernel
// tables' and the tabulated rotation's error per table size, a window's frame bounds and its
// kernels' localisation, and one level's needlet against the SH delta of its top band. Each returns
// its figures; printing and files are the caller's.
#pragma once

#include <functional>
#include <vector>

#include "zhf/frames/needlets.h"
#include "zhf/frames/windows.h"

namespace zhf::frames {

// Per table size: the worst level's kernel-table error relative to its peak, and the tabulated
// rotation's largest coefficient error against the exact path with its time, for linear [0] and
// quadratic [1] interpolation. The signal is a fixed unit-norm one, the turn fixed (zyz 0.3, 1.1,
// -0.7), so the errors are the same on every run; the times are this machine's.
struct TableSizeErrors {
  int size = 0;
  double kernel[2] = {0, 0};
  double rotation[2] = {0, 0};
  double rotation_seconds[2] = {0, 0};
};
struct TableStudy {
  double exact_seconds = 0;  // the exact path's rotation of the same signal
  std::vector<TableSizeErrors> sizes;
};
// poll() is called after each tabulated rotation, two per size (an interrupt check may throw from
// it). Cost: per size and interpolation, one table per level and one tabulated rotation.
TableStudy needlet_table_study(const NeedletFrame& frame, const std::vector<int>& sizes, const std::function<void()>& poll);

// The frame bounds of a window over bands 1..lmax: the least and the greatest sum over the levels
// of b(l / B^j)^2 (1 and 1: a tight frame). lmax >= 1.
struct WindowFrameBounds {
  double least = 0, greatest = 0;
};
WindowFrameBounds window_frame_bounds(const Window& w, int lmax);

// Level j's kernel energy outside the caps of radius k / B^j (at most pi), for each k.
std::vector<double> kernel_energy_outside_caps(const Window& w, int j, const std::vector<double>& ks);

// Level j's needlet (standard window of dilation B) against the SH delta of its top band: their
// localisation outside caps of 1, 2 and 4 half-wavelengths of the top band, and both profiles
// against theta, each over its peak, at 721 angles from 0 to 180 degrees.
struct ProfileCap {
  double cap = 0;  // radians
  Localisation needlet, delta;
};
struct ProfileSample {
  double theta = 0;  // radians
  double needlet = 0, delta = 0;
};
struct NeedletProfile {
  int first_band = 0, top_band = 0;  // the needlet's bands
  std::vector<ProfileCap> caps;
  std::vector<ProfileSample> samples;
};
NeedletProfile needlet_profile(double dilation, int j);

}  // namespace zhf::frames
