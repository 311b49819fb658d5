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

#include "test_support.h"
#include "test_tolerances.h"
#include "zhf/runtime/lanes.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/rotator.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/runtime/table_io.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/runtime/zonal.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"
#include "zhf/sh/zxzxz.h"
#include "zhf_kernels.h"

namespace zhf {
namespace {

using namespace zhf::tolerance;

struct Extreme {
  std::string name;
  sh::RotationMatrix r;
};

// The shared extreme set (sh::extreme_rotations), with the lobes of the order at hand.
std::vector<Extreme> extremes(const std::vector<Eigen::Vector3d>& lobes) {
  std::vector<Extreme> out;
  for (const auto& [name, r] : sh::extreme_rotations(lobes)) out.push_back({name, r});
  return out;
}

// rotate_lanes of a generated order with lanes tables.
template <class T>
typename runtime::KernelSet<T>::Kernel lanes_kernel(int order) {
  return gen::with_order(order, [](auto n) -> typename runtime::KernelSet<T>::Kernel {
    if constexpr (gen::kHasLanes<decltype(n)::value>) return runtime::lanes_kernels<decltype(n)::value, T>().rotate;
    return nullptr;
  });
}

using Method = std::function<void(const sh::RotationMatrix&, const Eigen::VectorXd&, Eigen::VectorXd&)>;

template <class T>
Method through(std::function<void(const T*, const T*, T*)> rotate, int channels = 1) {
  return [rotate, channels](const sh::RotationMatrix& m, const Eigen::VectorXd& f, Eigen::VectorXd& g) {
    std::vector<T> r(9), in(channels * f.size()), out(channels * f.size());
    for (int i = 0; i < 9; ++i) r[i] = static_cast<T>(m(i / 3, i % 3));
    // Channel c holds (c + 1) / channels f: the last is f, and a channel mixed up shows.
    for (int c = 0; c < channels; ++c)
      for (int i = 0; i < f.size(); ++i) in[c * f.size() + i] = static_cast<T>(f[i] * (c + 1) / channels);
    rotate(r.data(), in.data(), out.data());
    g.resize(f.size());
    for (int i = 0; i < f.size(); ++i) g[i] = out[(channels - 1) * f.size() + i];  // the last channel
  };
}

void check(const std::string& method, int order, const std::vector<Extreme>& rotations, const Method& rotate,
           double tolerance) {
  std::mt19937_64 rng(order);
  sh::Normal<> normal;
  for (const Extreme& e : rotations) {
    Eigen::VectorXd f(order * order), g;
    for (int i = 0; i < f.size(); ++i) f[i] = normal(rng);
    f.normalize();
    const Eigen::VectorXd expected = sh::apply_band_matrices(sh::ivanic_ruedenberg(e.r, order), f);
    rotate(e.r, f, g);
    Eigen::Index at = 0;
    const double error = (g - expected).cwiseAbs().maxCoeff(&at);
    EXPECT_LE(error, tolerance) << method << ", order " << order << ", rotation '" << e.name << "', band "
                                << runtime::band_of(int(at)) << ", index " << at;
  }
}

std::vector<Eigen::Vector3d> table_lobes(const runtime::LobeTable& t) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& l : t.lobes) out.emplace_back(l.xyz[0], l.xyz[1], l.xyz[2]);
  return out;
}

std::string table_path(int order) { return test::checked_in_table(order); }

TEST(EveryMethod, ExtremeRotationsStayWithinEachMethodsTolerance) {
  for (int order : {2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 16, 32}) {
    if (order >= 3 && !std::ifstream(table_path(order))) continue;  // no table for this order
    const bool generated = order <= runtime::kMaxGeneratedOrder;
    const runtime::LobeTable table = order >= 3 ? runtime::read_lobe_table(table_path(order)) : runtime::lobe_free_table();
    const double condition = order >= 3 ? table.worst_condition() : 1;
    const std::vector<Extreme> rotations = extremes(table_lobes(table));
    // Generated kernels: the lobe stage their header states; the table path always runs it in double.
    const bool scalar_in_double =
        generated && gen::with_order(order, [](auto n) { return gen::Kernels<decltype(n)::value>::kLobeStage == 2; });
    const double float_tolerance = float_rotation(order, condition, scalar_in_double);
    const double table_float_tolerance = float_rotation(order, condition, true);
    // The reference against the independent projection (up to 16: the projection's cost grows
    // as N^6).
    for (const Extreme& e : order <= 16 ? rotations : std::vector<Extreme>{}) {
      const sh::BandMatrices a = sh::ivanic_ruedenberg(e.r, order), b = sh::quadrature_rotation(e.r, order);
      for (int l = 0; l < order; ++l)
        EXPECT_LE((a[l] - b[l]).cwiseAbs().maxCoeff(), kReferenceAgreement) << "reference, order " << order << ", '" << e.name << "', band " << l;
    }
    if (generated) {
      const auto rf = runtime::Rotator<float>::with(gen::scalar_kernels<float>(order));
      const auto rd = runtime::Rotator<double>::with(gen::scalar_kernels<double>(order));
      const auto fastest = runtime::Rotator<float>::with(gen::fastest_kernels<float>(order));
      check("generated float", order, rotations, through<float>([&](auto r, auto i, auto o) { rf.rotate(r, i, o); }), float_tolerance);
      check("generated double", order, rotations, through<double>([&](auto r, auto i, auto o) { rd.rotate(r, i, o); }), kDouble);
      check("generated rgb float", order, rotations, through<float>([&](auto r, auto i, auto o) { rf.rotate_rgb(r, i, o); }, 3), float_tolerance);
      check("generated batch double", order, rotations, through<double>([&](auto r, auto i, auto o) { rd.rotate_batch(1, r, i, o); }), kDouble);
      check("dense double", order, rotations, through<double>([&](auto r, auto i, auto o) { rd.dense(r).apply(i, o); }), kDouble);
      check("fastest path float", order, rotations, through<float>([&](auto r, auto i, auto o) { fastest.rotate(r, i, o); }),
            std::max(float_tolerance, kFloatRotation));
      if (order >= 3) {
        const auto lanes_f = lanes_kernel<float>(order);
        const auto lanes_d = lanes_kernel<double>(order);
        check("lanes float", order, rotations, through<float>([&](auto r, auto i, auto o) { lanes_f(r, i, o); }), float_tolerance);
        check("lanes double", order, rotations, through<double>([&](auto r, auto i, auto o) { lanes_d(r, i, o); }), kDouble);
      }
    }
    if (order >= 3) {
      const auto tf = runtime::Rotator<float>::from_table(table);
      const auto td = runtime::Rotator<double>::from_table(table);
      check("runtime table float", order, rotations, through<float>([&](auto r, auto i, auto o) { tf.rotate(r, i, o); }), table_float_tolerance);
      check("runtime table double", order, rotations, through<double>([&](auto r, auto i, auto o) { td.rotate(r, i, o); }), kDouble);
      check("runtime table rgb float", order, rotations, through<float>([&](auto r, auto i, auto o) { tf.rotate_rgb(r, i, o); }, 3),
            table_float_tolerance);
      // The lobe path itself at every order, whichever path from_table picks for this build.
      const runtime::TableRotation<float> lf(table);
      const runtime::TableRotation<double> ld(table);
      check("lobe path float", order, rotations, through<float>([&](auto r, auto i, auto o) { lf.rotate(r, i, o, 1); }), table_float_tolerance);
      check("lobe path rgb double", order, rotations, through<double>([&](auto r, auto i, auto o) { ld.rotate(r, i, o, 3); }, 3), kDouble);
      check("runtime table rgb double", order, rotations, through<double>([&](auto r, auto i, auto o) { td.rotate_rgb(r, i, o); }, 3),
            kDouble);
    }
    const sh::ZxzxzRotator<float> zf(order);
    const sh::ZxzxzRotator<double> zd(order);
    check("zxzxz float", order, rotations, through<float>([&](auto r, auto i, auto o) { zf.rotate(r, i, o); }), zxzxz_float(order));
    check("zxzxz double", order, rotations, through<double>([&](auto r, auto i, auto o) { zd.rotate(r, i, o); }), kDouble);
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
      EXPECT_LE((g - expected).cwiseAbs().maxCoeff(&at), kDouble)
          << "zonal, order " << order << ", rotation '" << e.name << "', index " << at;
    }
  }
}

}  // namespace
}  // namespace zhf
