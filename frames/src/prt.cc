#include "zhf/frames/prt.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "zhf/frames/cubature.h"
#include "zhf/frames/limits.h"
#include "zhf/frames/projection.h"
#include "zhf/runtime/parallel.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/sh/reference_rotation.h"

namespace zhf::frames {
namespace {

using runtime::kPi;
// The reference rule: Gauss-Legendre panels in z times equal steps in phi.
constexpr int kReferencePanels = 8, kReferencePanelNodes = 64, kReferencePhi = 1024;
// The projections' rule: the largest Gauss product (degree 126, 8128 nodes).
constexpr int kProjectionDegree = frames::kMaxCubatureDegree;
// The sweep of sky turns: angles k 2 pi / kSweep about a fixed skew axis.
constexpr int kSweep = 12;

struct Sphere {
  Point centre;
  double radius;
};

bool ray_hits(const Sphere& s, const Point& p, const Point& w) {
  const Point d{s.centre[0] - p[0], s.centre[1] - p[1], s.centre[2] - p[2]};
  const double along = d[0] * w[0] + d[1] * w[1] + d[2] * w[2];
  if (along <= 0) return false;
  const double miss2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - along * along;
  return miss2 < s.radius * s.radius;
}

// Two walls of height kWallHeight in the planes x = kWall and y = kWall, the floor beyond them.
constexpr double kWall = -1.6, kWallHeight = 1.5;
bool wall_hits(double p, double w, double pz, double wz) {
  if (w >= 0) return false;
  const double s = (kWall - p) / w;
  return pz + s * wz < kWallHeight;
}

Cubature reference_rule() {
  std::vector<double> x, w;
  sh::gauss_legendre(kReferencePanelNodes, x, w);
  Cubature c;
  c.name = "reference";
  for (int panel = 0; panel < kReferencePanels; ++panel) {
    const double lo = -1 + 2.0 * panel / kReferencePanels, half = 1.0 / kReferencePanels;
    for (int i = 0; i < kReferencePanelNodes; ++i) {
      const double z = lo + half * (1 + x[i]), s = std::sqrt(std::max(0.0, 1 - z * z));
      for (int k = 0; k < kReferencePhi; ++k) {
        const double phi = 2 * kPi * (k + 0.5) / kReferencePhi;
        c.points.push_back({s * std::cos(phi), s * std::sin(phi), z});
        c.weights.push_back(half * w[i] * 2 * kPi / kReferencePhi);
      }
    }
  }
  return c;
}

// Indices of the k largest |v| (ties: the lower index first).
std::vector<int> largest(const std::vector<double>& v, int k) {
  std::vector<int> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  std::partial_sort(order.begin(), order.begin() + k, order.end(), [&](int a, int b) {
    return std::abs(v[a]) != std::abs(v[b]) ? std::abs(v[a]) > std::abs(v[b]) : a < b;
  });
  order.resize(k);
  return order;
}

// The least value of SH coefficients (order N) over the nodes.
double least_value(const std::vector<double>& sh, int order, const Cubature& nodes) {
  std::vector<double> y(sh.size());
  double least = INFINITY;
  for (const Point& x : nodes.points) {
    runtime::eval_sh(order, x.data(), y.data());
    least = std::min(least, std::inner_product(sh.begin(), sh.end(), y.begin(), 0.0));
  }
  return least;
}

}  // namespace

bool parse_prt_scene(const std::string& name, PrtScene& scene) {
  if (name == "sphere") scene = PrtScene::kSphere;
  else if (name == "corner") scene = PrtScene::kCorner;
  else if (name == "spheres") scene = PrtScene::kSpheres;
  else return false;
  return true;
}

bool parse_prt_transfer(const std::string& name, PrtTransfer& transfer) {
  if (name == "diffuse") transfer = PrtTransfer::kDiffuse;
  else if (name == "glossy") transfer = PrtTransfer::kGlossy;
  else return false;
  return true;
}

std::vector<Point> prt_vertices(int side) {
  if (side < 1 || side > frames::kMaxPrtSide)
    throw std::invalid_argument("vertices per side " + std::to_string(side) + " is outside 1.." + std::to_string(frames::kMaxPrtSide));
  std::vector<Point> v;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) v.push_back({-1.5 + 3.0 * (j + 0.5) / side, -1.5 + 3.0 * (i + 0.5) / side, 0.0});
  return v;
}

double prt_visibility(PrtScene scene, const Point& p, const Point& w) {
  static const Sphere one{{0, 0, 0.8}, 0.5};
  static const Sphere three[] = {{{-0.6, -0.3, 0.5}, 0.35}, {{0.5, 0.4, 0.6}, 0.3}, {{0.1, -0.7, 0.9}, 0.25}};
  switch (scene) {
    case PrtScene::kSphere:
      return ray_hits(one, p, w) ? 0 : 1;
    case PrtScene::kCorner:
      return wall_hits(p[0], w[0], p[2], w[2]) || wall_hits(p[1], w[1], p[2], w[2]) ? 0 : 1;
    case PrtScene::kSpheres:
      for (const Sphere& s : three)
        if (ray_hits(s, p, w)) return 0;
      return 1;
  }
  return 1;
}

double prt_transfer(PrtScene scene, PrtTransfer transfer, const Point& p, const Point& w) {
  if (w[2] <= 0) return 0;
  double brdf = 1 / kPi;
  if (transfer == PrtTransfer::kGlossy) {
    const double r = (-w[0] + w[2]) / std::sqrt(2.0);  // w . (-1, 0, 1) / sqrt2
    brdf = r <= 0 ? 0 : (kGlossyExponent + 2) / (2 * kPi) * std::pow(r, kGlossyExponent);
  }
  return brdf == 0 ? 0 : brdf * w[2] * prt_visibility(scene, p, w);
}

Radiance equirectangular_sky(int width, int height, std::shared_ptr<const std::vector<float>> rgb) {
  return [width, height, rgb](const Point& w) {
    const double theta = std::acos(std::clamp(w[2], -1.0, 1.0)), phi = std::atan2(w[1], w[0]) + (w[1] < 0 ? 2 * runtime::kPi : 0.0);
    const int row = std::min(height - 1, static_cast<int>(theta / runtime::kPi * height));
    const int column = std::min(width - 1, static_cast<int>(phi / (2 * runtime::kPi) * width));
    const float* pixel = &(*rgb)[3 * (static_cast<std::size_t>(row) * width + column)];
    return 0.2126 * pixel[0] + 0.7152 * pixel[1] + 0.0722 * pixel[2];
  };
}

double sun_and_sky(const Point& w) {
  static const double n = std::sqrt(0.5 * 0.5 + 0.3 * 0.3 + 0.8 * 0.8);
  const double cosine = (0.5 * w[0] + 0.3 * w[1] + 0.8 * w[2]) / n;
  return (w[2] >= 0 ? 0.25 + 0.75 * w[2] : 0.15) + 40 * std::exp(300 * (cosine - 1));
}

PrtReport prt_experiment(const NeedletFrame& frame, PrtScene scene, PrtTransfer transfer, const Radiance& sky, int side,
                         const std::vector<int>& kept, int table_size, const std::function<void(int, int)>& checkpoint,
                         int threads) {
  const std::vector<Point> vertices = prt_vertices(side);
  const int order = frame.band_limit() + 1, n_sh = order * order, n_frame = frame.size();
  for (int k : kept)
    if (k < 1 || k > n_frame) throw std::invalid_argument("K " + std::to_string(k) + " is outside 1.." + std::to_string(n_frame));
  const int count = static_cast<int>(vertices.size());
  threads = runtime::worker_count(threads);
  PrtReport report;
  report.vertices = count;
  report.sh_coefficients = n_sh;
  report.needlet_coefficients = n_frame;

  // Exact shading on the reference rule.
  const Cubature reference = reference_rule();
  std::vector<double> sky_at(reference.points.size());
  for (std::size_t i = 0; i < sky_at.size(); ++i) sky_at[i] = sky(reference.points[i]);
  std::vector<double> exact(count);
  for (int first = 0; first < count; first += threads) {
    if (checkpoint) checkpoint(first, count);
    runtime::parallel_for(std::min(threads, count - first), threads, [&](int b) {
      const Point& p = vertices[first + b];
      double sum = 0;
      for (std::size_t i = 0; i < sky_at.size(); ++i) sum += reference.weights[i] * sky_at[i] * prt_transfer(scene, transfer, p, reference.points[i]);
      exact[first + b] = sum;
    });
  }
  double exact_square = 0, exact_largest = 0;
  for (double e : exact) exact_square += e * e, exact_largest = std::max(exact_largest, std::abs(e));
  report.exact_rms = std::sqrt(exact_square / count);
  report.vertex_positions = vertices;
  report.exact = exact;

  // SH of the sky and of every vertex's transfer; needlets from those.
  const Cubature nodes = gauss_product_cubature(kProjectionDegree);
  std::vector<double> sky_values(nodes.points.size()), transfer_values(nodes.points.size() * count);
  for (std::size_t i = 0; i < nodes.points.size(); ++i) {
    sky_values[i] = sky(nodes.points[i]);
    for (int v = 0; v < count; ++v) transfer_values[i * count + v] = prt_transfer(scene, transfer, vertices[v], nodes.points[i]);
  }
  if (checkpoint) checkpoint(count, count);
  const std::vector<double> sky_sh = project_samples(nodes, sky_values, 1, order)[0];
  const std::vector<std::vector<double>> transfer_sh = project_samples(nodes, transfer_values, count, order);
  const std::vector<double> sky_beta = frame.analyze(sky_sh);
  std::vector<std::vector<double>> transfer_beta(count);
  runtime::parallel_for(count, threads, [&](int v) { transfer_beta[v] = frame.analyze(transfer_sh[v]); });
  report.sky_min = *std::min_element(sky_values.begin(), sky_values.end());

  std::vector<int> ks = kept;
  ks.push_back(n_frame);
  for (int k : ks) {
    if (checkpoint) checkpoint(count, count);
    PrtRow row;
    row.kept = k;
    int bands = 1;  // SH keeps whole bands: the most with bands^2 <= K
    while (bands < order && (bands + 1) * (bands + 1) <= k) ++bands;
    double sh_square = 0, needlet_square = 0;
    for (int v = 0; v < count; ++v) {
      double sh = 0, needlet = 0;
      for (int i = 0; i < bands * bands; ++i) sh += sky_sh[i] * transfer_sh[v][i];
      for (int i : largest(transfer_beta[v], k)) needlet += sky_beta[i] * transfer_beta[v][i];
      row.sh.push_back(sh);
      row.needlet.push_back(needlet);
      sh_square += (sh - exact[v]) * (sh - exact[v]);
      needlet_square += (needlet - exact[v]) * (needlet - exact[v]);
      row.sh_worst = std::max(row.sh_worst, std::abs(sh - exact[v]) / exact_largest);
      row.needlet_worst = std::max(row.needlet_worst, std::abs(needlet - exact[v]) / exact_largest);
      if (k == n_frame) report.parseval_gap = std::max(report.parseval_gap, std::abs(needlet - sh) / report.exact_rms);
    }
    row.sh_rms = std::sqrt(sh_square / count) / report.exact_rms;
    row.needlet_rms = std::sqrt(needlet_square / count) / report.exact_rms;
    std::vector<double> truncated(sky_sh.begin(), sky_sh.begin() + bands * bands);
    row.sh_sky_min = least_value(truncated, bands, nodes);
    std::vector<double> sparse(n_frame, 0.0);
    for (int i : largest(sky_beta, k)) sparse[i] = sky_beta[i];
    row.needlet_sky_min = least_value(frame.synthesize(sparse), order, nodes);
    report.rows.push_back(row);
  }

  // The sweep of turns.
  const TabulatedNeedletRotation tabulated(frame, table_size, Interpolation::kLinear);
  const std::vector<NeedletLevel>& levels = frame.levels();
  auto level_energy = [&](const std::vector<double>& beta, const NeedletLevel& level) {
    double e = 0;
    for (std::size_t i = 0; i < level.cubature.points.size(); ++i) e += beta[level.offset + i] * beta[level.offset + i];
    return e;
  };
  report.level_energy_change.assign(levels.size(), 0.0);
  report.kept_energy_least.assign(kept.size(), INFINITY);
  report.kept_energy_greatest.assign(kept.size(), 0.0);
  const double total = std::inner_product(sky_beta.begin(), sky_beta.end(), sky_beta.begin(), 0.0);
  const double axis_length = std::sqrt(1.0 + 4.0 + 9.0), axis[3] = {1 / axis_length, 2 / axis_length, 3 / axis_length};
  for (int step = 1; step <= kSweep; ++step) {
    if (checkpoint) checkpoint(count, count);
    const runtime::Matrix3 r = runtime::rotation_about_unit_axis(axis, 2 * kPi * step / kSweep);
    const std::vector<double> turned = tabulated.rotate(sky_beta, r), exact_turn = frame.rotate_exact(sky_beta, r);
    for (std::size_t l = 0; l < levels.size(); ++l) {
      const double before = level_energy(sky_beta, levels[l]);
      if (before > 0) report.level_energy_change[l] = std::max(report.level_energy_change[l], std::abs(level_energy(turned, levels[l]) - before) / before);
    }
    for (std::size_t i = 0; i < kept.size(); ++i) {
      double held = 0;
      for (int c : largest(exact_turn, kept[i])) held += exact_turn[c] * exact_turn[c];
      report.kept_energy_least[i] = std::min(report.kept_energy_least[i], held / total);
      report.kept_energy_greatest[i] = std::max(report.kept_energy_greatest[i], held / total);
    }
  }
  return report;
}

}  // namespace zhf::frames
