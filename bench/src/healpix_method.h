// HEALPix rotate_alm (Debian's libhealpix-cxx-dev) as an outside reference point: complex
// coefficients with the Condon-Shortley phase, converted from and to zhf's real SH at the edges.
#pragma once

#include <memory>

namespace zhf::bench {

class HealpixRotator {
 public:
  explicit HealpixRotator(int order);
  ~HealpixRotator();
  // Real SH in, real SH out, through rotate_alm.
  void rotate(const double r[9], const double* in, double* out) const;
  // The two conversions alone (no rotation), to report their cost separately.
  void convert_only(const double r[9], const double* in, double* out) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace zhf::bench
