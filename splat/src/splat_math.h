// One splat's transform on the values of its properties (scene.h says what changes and how),
// and where those properties sit in a PLY header: what every format's path shares.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "zhf/dispatch/rotator.h"
#include "zhf/io/ply.h"
#include "zhf/runtime/orthogonal.h"
#include "zhf/splat/scene.h"

namespace zhf::splat {

// Where the transformed properties are (indices into the header's properties; -1: absent).
struct Layout {
  std::array<int, 3> position{-1, -1, -1}, normal{-1, -1, -1}, dc{-1, -1, -1}, log_scale{-1, -1, -1};
  std::array<int, 4> rotation{-1, -1, -1, -1};  // w, x, y, z
  int opacity = -1;                              // a logit; never transformed
  std::vector<int> rest;                         // f_rest_0..K-1, channel-major (K / 3 per channel)
  int degree = -1;
  std::vector<int> changed;  // every property a transform may change
};

// Throws io::InputError "<source>: ..." for a layout no transform can use.
Layout layout_of(const io::ply::Header& header, const std::string& source);

// How orientations turn: kTurn, Q' = R Q (R Q F for a reflection), the scene moved; kAxes, a
// change of axes: for a signed diagonal R (a file's axes flipped) Q' = D Q D with D = det(R) R,
// the quaternion's components flipped as the reference .spz library does, so a round trip is
// exact; any other R as kTurn. Both give the same covariance.
enum class Orientation { kTurn, kAxes };

class SplatMath {
 public:
  SplatMath(const Layout& layout, const Transform& t, Orientation orientation = Orientation::kTurn);
  // One splat's property values, transformed in place.
  void apply(double* values) const { apply_many(values, 1, 0); }
  // count splats' values, splat s at values + s * stride: the SH of several splats go through
  // zhf::dispatch's path in one call (the rotation's product, the most of a splat's arithmetic).
  void apply_many(double* values, std::size_t count, std::size_t stride) const;

 private:
  const Layout& layout_;
  const Transform& t_;
  bool reflection_ = false;
  std::optional<std::array<double, 3>> flip_;  // kAxes with a signed diagonal: D's diagonal
  std::array<double, 4> turn_{};
  double log_scale_ = 0;
  std::optional<runtime::CoefficientMap> exact_;
  std::optional<dispatch::PreparedTransform<double>> sh_;
  void apply_geometry(double* values) const;
};

}  // namespace zhf::splat
