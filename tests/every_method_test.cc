// Every extreme rotation through every rotation method of the project, each method against the
// Ivanic-Ruedenberg reference within its named tolerance; the reference itself against the
// independent quadrature projection. Failure messages name method, order, rotation, index.
#include <cmath>
#include <fstream>
#include <functional>
#include <random>
#include <string>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "zhf/codegen/kernels.h"
#include "zhf/optimizer/lobe_table.h"
#include "zhf/runtime/lanes.h"
#include "zhf/runtime/rotator.h"
#include "zhf/runtime/zonal.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/index.h"
#include "zhf/sh/zxzxz.h"
#include "zhf/verify/verify.h"

namespace zhf {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDoubleTolerance = 1e-12;          // every double method
constexpr double kReferenceAgreement = 1e-13;      // Ivanic-Ruedenberg vs quadrature projection

struct Extreme {
  std::string name;
  sh::Matrix3 r;
};

// The fixed set of the issue: identity, half turns about the axes and diagonals, gimbal lock
// for Euler-based methods, tiny turns, and rotations carrying a lobe onto a pole or onto
// another lobe (table lobes of the order at hand).
std::vector<Extreme> extremes(const std::vector<Eigen::Vector3d>& lobes) {
  std::vector<Extreme> out = {
      {"identity", sh::Matrix3::Identity()},
      {"180 about x", sh::rotation_about_axis(Eigen::Vector3d::UnitX(), kPi)},
      {"180 about y", sh::rotation_about_axis(Eigen::Vector3d::UnitY(), kPi)},
      {"180 about z", sh::rotation_about_axis(Eigen::Vector3d::UnitZ(), kPi)},
      {"180 about (1,1,0)", sh::rotation_about_axis(Eigen::Vector3d(1, 1, 0), kPi)},
      {"180 about (1,1,1)", sh::rotation_about_axis(Eigen::Vector3d(1, 1, 1), kPi)},
      {"zyz beta=0", sh::rotation_from_zyz(0.4, 0.0, -1.3)},
      {"zyz beta=pi", sh::rotation_from_zyz(0.4, kPi, -1.3)},
      {"zyz beta=1e-9", sh::rotation_from_zyz(2.0, 1e-9, 0.5)},
      {"1e-8 rad", sh::rotation_about_axis(Eigen::Vector3d(0.3, -0.2, 0.9), 1e-8)},
      {"1e-8 rad about z", sh::rotation_about_axis(Eigen::Vector3d::UnitZ(), 1e-8)},
  };
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  for (size_t d = 0; d < lobes.size() && d < 2; ++d) {
    const Eigen::Vector3d axis = lobes[d].cross(z);
    if (axis.norm() > 1e-12)
      out.push_back({"lobe " + std::to_string(d) + " onto the pole", sh::rotation_about_axis(axis, std::acos(lobes[d].dot(z)))});
  }
  if (lobes.size() >= 2) {
    const Eigen::Vector3d axis = lobes[0].cross(lobes[1]);
    if (axis.norm() > 1e-12)
      out.push_back({"lobe 0 onto lobe 1", sh::rotation_about_axis(axis, std::acos(std::clamp(lobes[0].dot(lobes[1]), -1.0, 1.0)))});
  }
  return out;
}

using Method = std::function<void(const sh::Matrix3&, const Eigen::VectorXd&, Eigen::VectorXd&)>;

template <class T>
Method through(std::function<void(const T*, const T*, T*)> rotate, int channels = 1) {
  return [rotate, channels](const sh::Matrix3& m, const Eigen::VectorXd& f, Eigen::VectorXd& g) {
    std::vector<T> r(9), in(channels * f.size()), out(channels * f.size());
    for (int i = 0; i < 9; ++i) r[i] = static_cast<T>(m(i / 3, i % 3));
    for (int c = 0; c < channels; ++c)
      for (int i = 0; i < f.size(); ++i) in[c * f.size() + i] = static_cast<T>(f[i]);
    rotate(r.data(), in.data(), out.data());
    g.resize(f.size());
    for (int i = 0; i < f.size(); ++i) g[i] = out[(channels - 1) * f.size() + i];  // the last channel
  };
}

void check(const std::string& method, int order, const std::vector<Extreme>& rotations, const Method& rotate,
           double tolerance) {
  std::mt19937_64 rng(order);
  std::normal_distribution<double> normal;
  for (const Extreme& e : rotations) {
    Eigen::VectorXd f(order * order), g;
    for (int i = 0; i < f.size(); ++i) f[i] = normal(rng);
    f.normalize();
    const Eigen::VectorXd expected = sh::apply_band_matrices(sh::ivanic_ruedenberg(e.r, order), f);
    rotate(e.r, f, g);
    Eigen::Index at = 0;
    const double error = (g - expected).cwiseAbs().maxCoeff(&at);
    EXPECT_LE(error, tolerance) << method << ", order " << order << ", rotation '" << e.name << "', band "
                                << sh::band_of(int(at)) << ", index " << at;
  }
}

std::vector<Eigen::Vector3d> table_lobes(const runtime::LobeTableData& t) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& l : t.lobes) out.emplace_back(l[0], l[1], l[2]);
  return out;
}

std::string table_path(int order) {
  return std::string(ZHF_SOURCE_DIR) + "/generated/lobes/order_" + std::to_string(order) + ".json";
}

TEST(EveryMethod, ExtremeRotationsStayWithinEachMethodsTolerance) {
  for (int order : {2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 16, 32}) {
    if (order >= 3 && !std::ifstream(table_path(order))) continue;  // no table for this order
    const bool generated = order <= runtime::kMaxGeneratedOrder;
    runtime::LobeTableData table;
    double condition = 1;
    if (order >= 3) {
      table = runtime::read_lobe_table(table_path(order));
      condition = optimizer::read_table(table_path(order)).worst_condition();
    }
    const std::vector<Extreme> rotations = extremes(table_lobes(table));
    // Generated kernels: the lobe stage where `auto` put it; the table path always runs it in double.
    const double float_tolerance =
        order < 3 ? verify::kFloatRotationTolerance
                  : verify::float_rotation_tolerance(order, condition, codegen::float_needs_wide_lobes(optimizer::read_table(table_path(order))));
    const double table_float_tolerance = order < 3 ? verify::kFloatRotationTolerance : verify::float_rotation_tolerance(order, condition, true);
    // The reference against the independent projection (up to 16: the projection's cost grows
    // as N^6).
    for (const Extreme& e : order <= 16 ? rotations : std::vector<Extreme>{}) {
      const sh::BandMatrices a = sh::ivanic_ruedenberg(e.r, order), b = sh::quadrature_rotation(e.r, order);
      for (int l = 0; l < order; ++l)
        EXPECT_LE((a[l] - b[l]).cwiseAbs().maxCoeff(), kReferenceAgreement) << "reference, order " << order << ", '" << e.name << "', band " << l;
    }
    if (generated) {
      const auto rf = runtime::Rotator<float>::generated(order);
      const auto rd = runtime::Rotator<double>::generated(order);
      check("generated float", order, rotations, through<float>([&](auto r, auto i, auto o) { rf.rotate(r, i, o); }), float_tolerance);
      check("generated double", order, rotations, through<double>([&](auto r, auto i, auto o) { rd.rotate(r, i, o); }), kDoubleTolerance);
      check("generated rgb float", order, rotations, through<float>([&](auto r, auto i, auto o) { rf.rotate_rgb(r, i, o); }, 3), float_tolerance);
      check("generated batch double", order, rotations, through<double>([&](auto r, auto i, auto o) { rd.rotate_batch(1, r, i, o); }), kDoubleTolerance);
      check("dense double", order, rotations, through<double>([&](auto r, auto i, auto o) { rd.dense(r).apply(i, o); }), kDoubleTolerance);
      if (order >= 3) {
        const auto lanes_f = runtime::lanes_kernel<float>(order);
        const auto lanes_d = runtime::lanes_kernel<double>(order);
        check("lanes float", order, rotations, through<float>([&](auto r, auto i, auto o) { lanes_f(r, i, o); }), float_tolerance);
        check("lanes double", order, rotations, through<double>([&](auto r, auto i, auto o) { lanes_d(r, i, o); }), kDoubleTolerance);
      }
    }
    if (order >= 3) {
      const auto tf = runtime::Rotator<float>::from_table(table);
      const auto td = runtime::Rotator<double>::from_table(table);
      check("runtime table float", order, rotations, through<float>([&](auto r, auto i, auto o) { tf.rotate(r, i, o); }), table_float_tolerance);
      check("runtime table double", order, rotations, through<double>([&](auto r, auto i, auto o) { td.rotate(r, i, o); }), kDoubleTolerance);
    }
    const sh::ZxzxzRotator<float> zf(order);
    const sh::ZxzxzRotator<double> zd(order);
    check("zxzxz float", order, rotations, through<float>([&](auto r, auto i, auto o) { zf.rotate(r, i, o); }), verify::zxzxz_float_tolerance(order));
    check("zxzxz double", order, rotations, through<double>([&](auto r, auto i, auto o) { zd.rotate(r, i, o); }), kDoubleTolerance);
  }
}

// The zonal fast path on the same rotations: a zonal function rotated by re-evaluation.
TEST(EveryMethod, ZonalFastPathOnExtremeRotations) {
  for (int order : {2, 5, 8, 16}) {
    const runtime::ZonalRotator<double> zonal(order);
    const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.4, 0.5).normalized();
    std::vector<double> weights(order);
    for (int l = 0; l < order; ++l) weights[l] = 1.0 / (l + 1);
    Eigen::VectorXd f(order * order), g(order * order);
    zonal.project(axis.data(), weights.data(), f.data());
    for (const Extreme& e : extremes({axis})) {
      zonal.rotate(e.r.data(), axis.data(), weights.data(), g.data());
      const Eigen::VectorXd expected = sh::apply_band_matrices(sh::ivanic_ruedenberg(e.r, order), f);
      Eigen::Index at = 0;
      EXPECT_LE((g - expected).cwiseAbs().maxCoeff(&at), kDoubleTolerance)
          << "zonal, order " << order << ", rotation '" << e.name << "', index " << at;
    }
  }
}

}  // namespace
}  // namespace zhf
