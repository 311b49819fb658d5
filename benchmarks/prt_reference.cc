// The convergence of zhf needlets prt's exact reference (frames::prt_exact_shading), and what the
// quadrature it replaced missed: for every built-in scene and transfer under the sun and sky, on
// an 8 x 8 grid of its vertices, the largest change of a vertex's shading from the reference at
// half the step it uses (0.05 rad), relative to the shadings' RMS, at steps 0.8 .. 0.1;
// then the old rule's (8 Gauss-Legendre panels of 64 nodes in z, 1024 equal steps in phi: 524 288
// directions, visibility sampled) largest and RMS error against the reference.
//   zhf_prt_reference [--side 8]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "zhf/frames/prt.h"
#include "zhf/runtime/parallel.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/sh/reference_rotation.h"

namespace {

using zhf::frames::Point;
using zhf::frames::PrtScene;
using zhf::frames::PrtTransfer;
using zhf::runtime::kPi;

// The old reference: Gauss-Legendre panels in z times equal steps in phi, visibility sampled.
double old_rule(PrtScene scene, PrtTransfer transfer, const Point& p) {
  constexpr int kPanels = 8, kNodes = 64, kPhi = 1024;
  std::vector<double> x, w;
  zhf::sh::gauss_legendre(kNodes, x, w);
  double sum = 0;
  for (int panel = 0; panel < kPanels; ++panel) {
    const double lo = -1 + 2.0 * panel / kPanels, half = 1.0 / kPanels;
    for (int i = 0; i < kNodes; ++i) {
      const double z = lo + half * (1 + x[i]), s = std::sqrt(std::max(0.0, 1 - z * z));
      for (int k = 0; k < kPhi; ++k) {
        const double phi = 2 * kPi * (k + 0.5) / kPhi;
        const Point d{s * std::cos(phi), s * std::sin(phi), z};
        sum += half * w[i] * 2 * kPi / kPhi * zhf::frames::sun_and_sky(d) * zhf::frames::prt_transfer(scene, transfer, p, d);
      }
    }
  }
  return sum;
}

}  // namespace

int main(int argc, char** argv) {
  int side = 8;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--side") == 0 && i + 1 < argc) {
      side = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: zhf_prt_reference [--side 1..64]\n");
      return 2;
    }
  }
  const std::vector<Point> vertices = zhf::frames::prt_vertices(side);
  const int count = static_cast<int>(vertices.size());
  const double steps[] = {0.8, 0.4, 0.2, 0.1}, finest = zhf::frames::kPrtExactStep / 2;
  std::printf("exact reference: %d x %d vertices, sun and sky; per step, the largest |shading - shading at step %g| over the "
              "shadings' RMS (the step used: %g, %d nodes a panel)\n\n",
              side, side, finest, zhf::frames::kPrtExactStep, zhf::frames::kPrtExactNodes);
  std::printf("| scene, transfer | shading RMS |");
  for (double s : steps) std::printf(" step %g |", s);
  std::printf(" old rule: largest / RMS error |\n| --- | --- |");
  for (std::size_t i = 0; i < std::size(steps); ++i) std::printf(" --- |");
  std::printf(" --- |\n");
  const char* scene_names[] = {"open", "sphere", "corner", "spheres"};
  for (const PrtScene scene : {PrtScene::kSphere, PrtScene::kCorner, PrtScene::kSpheres})
    for (const PrtTransfer transfer : {PrtTransfer::kDiffuse, PrtTransfer::kGlossy}) {
      auto shade = [&](double step) {
        std::vector<double> v(count);
        zhf::runtime::parallel_for(count, 0, [&](int i) {
          v[i] = zhf::frames::prt_exact_shading(scene, transfer, zhf::frames::sun_and_sky, vertices[i], step);
        });
        return v;
      };
      const std::vector<double> best = shade(finest);
      double square = 0;
      for (double b : best) square += b * b;
      const double rms = std::sqrt(square / count);
      std::printf("| %s, %s | %.4f |", scene_names[static_cast<int>(scene)], transfer == PrtTransfer::kDiffuse ? "diffuse" : "glossy", rms);
      for (double step : steps) {
        const std::vector<double> v = shade(step);
        double largest = 0;
        for (int i = 0; i < count; ++i) largest = std::max(largest, std::abs(v[i] - best[i]));
        std::printf(" %.1e |", largest / rms);
      }
      std::vector<double> old(count);
      zhf::runtime::parallel_for(count, 0, [&](int i) { old[i] = old_rule(scene, transfer, vertices[i]); });
      double largest = 0, old_square = 0;
      for (int i = 0; i < count; ++i) {
        largest = std::max(largest, std::abs(old[i] - best[i]));
        old_square += (old[i] - best[i]) * (old[i] - best[i]);
      }
      std::printf(" %.1e / %.1e |\n", largest / rms, std::sqrt(old_square / count) / rms);
      std::fflush(stdout);
    }
  return 0;
}
