#include "splat_math.h"

#include <algorithm>
#include <cmath>

#include "zhf/io/errors.h"
#include "zhf/dispatch/rotator.h"
#include "zhf/runtime/conventions.h"
#include "zhf/splat/limits.h"

namespace zhf::splat {
namespace {

namespace ply = io::ply;
using io::InputError;

// The named properties, all float or double: all present, or none (false).
template <std::size_t K>
bool group(const ply::Header& header, const std::array<const char*, K>& names, std::array<int, K>& out, const std::string& source) {
  int present = 0;
  for (std::size_t i = 0; i < K; ++i) {
    out[i] = header.find(names[i]);
    if (out[i] < 0) continue;
    ++present;
    if (!ply::is_float(header.properties[out[i]].type))
      throw InputError(source + ": property " + names[i] + " is not float or double");
  }
  if (present != 0 && present != int(K))
    throw InputError(source + ": property " + names[0] + " and its " + std::to_string(K - 1) + " companions must all be present, or none");
  return present == int(K);
}

}  // namespace

Layout layout_of(const ply::Header& header, const std::string& source) {
  Layout layout;
  if (!group<3>(header, {"x", "y", "z"}, layout.position, source)) throw InputError(source + ": no x, y, z properties");
  group<3>(header, {"nx", "ny", "nz"}, layout.normal, source);
  group<4>(header, {"rot_0", "rot_1", "rot_2", "rot_3"}, layout.rotation, source);
  group<3>(header, {"scale_0", "scale_1", "scale_2"}, layout.log_scale, source);
  const bool colour = group<3>(header, {"f_dc_0", "f_dc_1", "f_dc_2"}, layout.dc, source);
  std::size_t rest = 0;
  for (const ply::Property& p : header.properties) rest += p.name.rfind("f_rest_", 0) == 0;
  int degree = 0;
  while (degree < kMaxSplatShDegree && std::size_t(3 * ((degree + 1) * (degree + 1) - 1)) < rest) ++degree;
  if (rest != std::size_t(3 * ((degree + 1) * (degree + 1) - 1)))
    throw InputError(source + ": " + std::to_string(rest) + " f_rest properties; SH degree 1, 2, 3, 4 has 9, 24, 45, 72");
  if (rest > 0 && !colour) throw InputError(source + ": f_rest properties without f_dc_0..2");
  for (std::size_t i = 0; i < rest; ++i) {
    const std::string name = "f_rest_" + std::to_string(i);
    const int index = header.find(name);
    if (index < 0) throw InputError(source + ": " + std::to_string(rest) + " f_rest properties, but no " + name);
    if (!ply::is_float(header.properties[index].type)) throw InputError(source + ": property " + name + " is not float or double");
    layout.rest.push_back(index);
  }
  layout.opacity = header.find("opacity");
  layout.degree = colour ? degree : -1;
  for (int i : layout.position) layout.changed.push_back(i);
  for (const auto* g : {&layout.normal, &layout.log_scale})
    if ((*g)[0] >= 0) layout.changed.insert(layout.changed.end(), g->begin(), g->end());
  if (layout.rotation[0] >= 0) layout.changed.insert(layout.changed.end(), layout.rotation.begin(), layout.rotation.end());
  layout.changed.insert(layout.changed.end(), layout.rest.begin(), layout.rest.end());
  return layout;
}

// Prepared for a whole scene: the band matrices are built once (they pay from a few vectors on).
constexpr std::size_t kPreparedForScene = std::size_t(1) << 20;

SplatMath::SplatMath(const Layout& layout, const Transform& t, Orientation orientation) : layout_(layout), t_(t) {
  const runtime::Matrix3& r = t.r;
  reflection_ = runtime::determinant(r.data()) < 0;
  if (orientation == Orientation::kAxes && r[1] == 0 && r[2] == 0 && r[3] == 0 && r[5] == 0 && r[6] == 0 && r[7] == 0) {
    const double sign = reflection_ ? -1 : 1;
    flip_ = std::array<double, 3>{sign * r[0], sign * r[4], sign * r[8]};
  }
  runtime::Matrix3 proper = r;
  if (reflection_)
    for (double& x : proper) x = -x;
  turn_ = runtime::quaternion_from_rotation(proper);
  log_scale_ = std::log(t.scale);
  if (layout.degree >= 1) {
    const runtime::Convention& convention = t.convention ? *t.convention : *runtime::find_convention("3dgs");
    const runtime::Matrix3 q = convention.rotation_in_zhf_terms(r);
    const int order = layout.degree + 1;
    // An axis map moves coefficients exactly; any other q through its band matrices, built on the
    // CPU's fastest path (zhf::dispatch) once for the whole scene.
    exact_ = runtime::exact_coefficient_map(q.data(), order);
    if (!exact_) sh_ = dispatch::Rotator<double>::make(order).prepare(q.data(), kPreparedForScene);
  }
}

void SplatMath::apply_geometry(double* v) const {
  const runtime::Matrix3& r = t_.r;
  const auto& p = layout_.position;
  const double x = v[p[0]], y = v[p[1]], z = v[p[2]];
  for (int i = 0; i < 3; ++i)
    v[p[i]] = t_.scale * (r[3 * i] * x + r[3 * i + 1] * y + r[3 * i + 2] * z) + t_.translation[i];
  const auto& n = layout_.normal;
  if (n[0] >= 0) {
    const double a = v[n[0]], b = v[n[1]], c = v[n[2]];
    for (int i = 0; i < 3; ++i) v[n[i]] = r[3 * i] * a + r[3 * i + 1] * b + r[3 * i + 2] * c;
  }
  const auto& q = layout_.rotation;
  if (q[0] >= 0 && flip_) {
    for (int i = 0; i < 3; ++i) v[q[1 + i]] *= (*flip_)[i];
  } else if (q[0] >= 0) {
    // Q' = R Q, or for a reflection R Q F = (-R) Q Rz(pi): the quaternion of Rz(pi) is (0, 0, 0, 1).
    std::array<double, 4> turned = runtime::quaternion_product(turn_, {v[q[0]], v[q[1]], v[q[2]], v[q[3]]});
    if (reflection_) turned = runtime::quaternion_product(turned, {0, 0, 0, 1});
    for (int i = 0; i < 4; ++i) v[q[i]] = turned[i];
  }
  if (layout_.log_scale[0] >= 0)
    for (int i : layout_.log_scale) v[i] += log_scale_;
}

void SplatMath::apply_many(double* values, std::size_t count, std::size_t stride) const {
  for (std::size_t s = 0; s < count; ++s) apply_geometry(values + s * stride);
  if (!exact_ && !sh_) return;
  const int n2 = (layout_.degree + 1) * (layout_.degree + 1), per = n2 - 1;
  // Each splat's three channels as three vectors of n2, kShBlock splats a call.
  constexpr std::size_t kShBlock = 16, kVector = runtime::kMaxGeneratedOrder * runtime::kMaxGeneratedOrder;
  double in[3 * kShBlock * kVector], out[3 * kShBlock * kVector];
  for (std::size_t first = 0; first < count; first += kShBlock) {
    const std::size_t part = std::min(kShBlock, count - first);
    for (std::size_t s = 0; s < part; ++s)
      for (int c = 0; c < 3; ++c) {
        const double* v = values + (first + s) * stride;
        double* f = in + (3 * s + c) * n2;
        f[0] = v[layout_.dc[c]];
        for (int j = 0; j < per; ++j) f[1 + j] = v[layout_.rest[c * per + j]];
      }
    if (exact_) {
      for (std::size_t k = 0; k < 3 * part; ++k) exact_->apply(in + k * n2, out + k * n2);
    } else {
      sh_->apply(3 * part, in, out, 1);
    }
    for (std::size_t s = 0; s < part; ++s)
      for (int c = 0; c < 3; ++c) {
        double* v = values + (first + s) * stride;
        const double* g = out + (3 * s + c) * n2;
        for (int j = 0; j < per; ++j) v[layout_.rest[c * per + j]] = g[1 + j];
      }
  }
}

}  // namespace zhf::splat
