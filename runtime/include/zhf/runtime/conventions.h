// Other systems' SH conventions, converted at the edges; the core stays in zhf's
// (docs/conventions.md, where each preset's source is cited). A convention is two facts:
//  - its sign pattern: with the Condon-Shortley phase, coefficient (l, m) is (-1)^m times zhf's.
//    That basis is zhf's evaluated at (-x, -y, z), i.e. K = Rz(pi), an exact coefficient map.
//  - its frame: the system's coordinates u are zhf's w = P u, P a signed permutation (y up,
//    left-handed axes).
// So the system's f(u) = sum c_i y_i(K u), and in zhf's axes its coefficients are those of
// f(P^T w): the transform by M = P K (orthogonal.h); back again by M^T.
//
// A rotation R written in the system's own axes and applied to the system's own coefficients is
// K R K in zhf's terms: the frame cancels, only the sign pattern is left. A rotation written in
// zhf's axes is M^T R M.
#pragma once

#include <array>
#include <string>
#include <string_view>

#include "zhf/runtime/rotation.h"

namespace zhf::runtime {

struct Convention {
  std::string_view name;
  bool condon_shortley;  // coefficient (l, m) carries (-1)^m
  Matrix3 frame;         // P: zhf's w = P u
  std::string_view systems;

  // K: Rz(pi) with the Condon-Shortley sign pattern, else the identity.
  Matrix3 sign_rotation() const {
    return condon_shortley ? Matrix3{-1, 0, 0, 0, -1, 0, 0, 0, 1} : kIdentity;
  }
  // M = P K: the system's coefficients -> zhf's, in zhf's axes.
  Matrix3 to_zhf() const { return multiply(frame, sign_rotation()); }
  // M^T: zhf's coefficients -> the system's.
  Matrix3 from_zhf() const { return transpose(to_zhf()); }
  // K R K: a rotation in the system's axes, on the system's coefficients, as zhf rotates them.
  Matrix3 rotation_in_zhf_terms(const Matrix3& r) const {
    return multiply(multiply(sign_rotation(), r), sign_rotation());
  }
};

inline const std::array<Convention, 5>& conventions() {
  static const std::array<Convention, 5> presets{{
      {"zhf", false, kIdentity, "zhf; Sloan's and Filament's real SH without the phase"},
      {"condon-shortley", true, kIdentity, "the real SH with the Condon-Shortley phase (-1)^m"},
      {"3dgs", true, kIdentity, "3D Gaussian Splatting .ply files: graphdeco's sh_utils.py, gsplat, PlayCanvas"},
      // y up, right-handed: zhf's (x, y, z) = (x, -z, y) of the system's.
      {"y-up-rh", false, {1, 0, 0, 0, 0, -1, 0, 1, 0}, "axes of glTF and three.js (y up, right-handed)"},
      // y up, left-handed: zhf's (x, y, z) = (x, z, y) of the system's.
      {"y-up-lh", false, {1, 0, 0, 0, 0, 1, 0, 1, 0}, "axes of Unity (y up, left-handed)"},
  }};
  return presets;
}

// The preset of that name, or nullptr.
inline const Convention* find_convention(std::string_view name) {
  for (const Convention& c : conventions())
    if (c.name == name) return &c;
  return nullptr;
}

// The preset names, comma-separated, for messages and --help.
inline std::string convention_names() {
  std::string names;
  for (const Convention& c : conventions()) names += (names.empty() ? "" : ", ") + std::string(c.name);
  return names;
}

}  // namespace zhf::runtime
