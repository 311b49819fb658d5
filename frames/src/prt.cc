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

const Sphere kOneSphere{{0, 0, 0.8}, 0.5};
const Sphere kThreeSpheres[] = {{{-0.6, -0.3, 0.5}, 0.35}, {{0.5, 0.4, 0.6}, 0.3}, {{0.1, -0.7, 0.9}, 0.25}};

// Two walls of height kWallHeight in the planes x = kWall and y = kWall, the floor beyond them.
constexpr double kWall = -1.6, kWallHeight = 1.5;
bool wall_hits(double p, double w, double pz, double wz) {
  if (w >= 0) return false;
  const double s = (kWall - p) / w;
  return pz + s * wz < kWallHeight;
}

// T_p(w) without its visibility.
double unshadowed_transfer(PrtTransfer transfer, const Point& w) {
  if (w[2] <= 0) return 0;
  double brdf = 1 / kPi;
  if (transfer == PrtTransfer::kGlossy) {
    const double r = (-w[0] + w[2]) / std::sqrt(2.0);  // w . (-1, 0, 1) / sqrt2
    brdf = r <= 0 ? 0 : (kGlossyExponent + 2) / (2 * kPi) * std::pow(r, kGlossyExponent);
  }
  return brdf * w[2];
}

// The directions an occluder hides from a vertex: w . axis > cos_half (open, as ray_hits and
// wall_hits test).
struct Cap {
  Point axis;
  double cos_half;
};

// Each occluder of the scene as a cap seen from p. A sphere at distance d, radius r: the cone of
// half-angle asin(r / d) about its centre (ray_hits: along > 0 and miss^2 < r^2, i.e. along >
// sqrt(d^2 - r^2)). A wall x = kWall below height h = kWallHeight - p_z, seen from p_x > kWall:
// the ray meets it where s = (kWall - p_x) / w_x > 0 and s w_z < h, i.e., with w_x < 0,
// h w_x + (p_x - kWall) w_z < 0, which above the horizon also implies w_x < 0: a half-space.
std::vector<Cap> occluder_caps(PrtScene scene, const Point& p) {
  if (p[2] != 0) throw std::invalid_argument("the exact shading is for vertices on the ground (z = 0)");
  std::vector<Cap> caps;
  auto sphere = [&](const Sphere& s) {
    const Point d{s.centre[0] - p[0], s.centre[1] - p[1], s.centre[2] - p[2]};
    const double distance = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(distance > s.radius)) throw std::invalid_argument("the vertex is inside an occluding sphere");
    caps.push_back({{d[0] / distance, d[1] / distance, d[2] / distance}, std::sqrt(1 - (s.radius / distance) * (s.radius / distance))});
  };
  auto wall = [&](int axis) {
    const double h = kWallHeight - p[2], beyond = p[axis] - kWall, length = std::hypot(h, beyond);
    if (!(beyond > 0)) throw std::invalid_argument("the vertex is behind a wall");
    Point a{0, 0, -beyond / length};
    a[axis] = -h / length;
    caps.push_back({a, 0.0});
  };
  switch (scene) {
    case PrtScene::kOpen:
      break;
    case PrtScene::kSphere:
      sphere(kOneSphere);
      break;
    case PrtScene::kCorner:
      wall(0);
      wall(1);
      break;
    case PrtScene::kSpheres:
      for (const Sphere& s : kThreeSpheres) sphere(s);
      break;
  }
  return caps;
}

// The azimuth of a direction, in [0, 2 pi).
double azimuth(double x, double y) {
  const double phi = std::atan2(y, x);
  return phi < 0 ? phi + 2 * kPi : phi;
}

// The pieces [a, b] of [0, 2 pi] inside which every meridian's visible theta intervals keep their
// form: split where a cap's edge is tangent to the meridian, meets the horizon, or crosses another
// cap's edge above the horizon.
std::vector<std::pair<double, double>> phi_pieces(const std::vector<Cap>& caps) {
  std::vector<double> cuts{0, 2 * kPi};
  // On the meridian phi, w . axis = A sin(theta) + z cos(theta) with A = h cos(phi - phi_c).
  auto where = [&](double h, double phi_c, double a) {  // the phi where A = a
    if (h <= 0 || std::abs(a) > h) return;
    const double d = std::acos(std::clamp(a / h, -1.0, 1.0));
    for (double phi : {phi_c + d, phi_c - d}) cuts.push_back(std::fmod(phi + 4 * kPi, 2 * kPi));
  };
  for (const Cap& c : caps) {
    const double h = std::hypot(c.axis[0], c.axis[1]), phi_c = std::atan2(c.axis[1], c.axis[0]);
    const double k = c.cos_half, z = c.axis[2];
    if (k * k >= z * z) {  // tangency: A^2 + z^2 = k^2
      where(h, phi_c, std::sqrt(k * k - z * z));
      where(h, phi_c, -std::sqrt(k * k - z * z));
    }
    where(h, phi_c, k);  // the edge on the horizon (theta = pi / 2): A = k
  }
  // Two edges w . c1 = k1, w . c2 = k2 meet at w = a c1 + b c2 + t (c1 x c2).
  for (std::size_t i = 0; i < caps.size(); ++i)
    for (std::size_t j = i + 1; j < caps.size(); ++j) {
      const Point &c1 = caps[i].axis, &c2 = caps[j].axis;
      const double g = c1[0] * c2[0] + c1[1] * c2[1] + c1[2] * c2[2], det = 1 - g * g;
      if (!(det > 0)) continue;  // parallel axes: the edges are nested or apart, never crossing once
      const double a = (caps[i].cos_half - caps[j].cos_half * g) / det, b = (caps[j].cos_half - caps[i].cos_half * g) / det;
      const Point n{c1[1] * c2[2] - c1[2] * c2[1], c1[2] * c2[0] - c1[0] * c2[2], c1[0] * c2[1] - c1[1] * c2[0]};
      const double t2 = (1 - (a * a + b * b + 2 * a * b * g)) / det;  // |c1 x c2|^2 = det
      if (t2 < 0) continue;
      for (double t : {std::sqrt(t2), -std::sqrt(t2)}) {
        const Point w{a * c1[0] + b * c2[0] + t * n[0], a * c1[1] + b * c2[1] + t * n[1], a * c1[2] + b * c2[2] + t * n[2]};
        if (w[2] >= 0) cuts.push_back(azimuth(w[0], w[1]));
      }
    }
  std::sort(cuts.begin(), cuts.end());
  std::vector<std::pair<double, double>> pieces;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
    if (cuts[i + 1] > cuts[i]) pieces.push_back({cuts[i], cuts[i + 1]});
  return pieces;
}

// The visible theta intervals of [0, pi / 2] on the meridian (cos phi, sin phi): each cap hides
// |theta - theta_0| < acos(k / rho) where w . axis = rho cos(theta - theta_0).
// scratch: room for the next set, kept between calls so that a meridian allocates nothing.
void visible_thetas(const std::vector<Cap>& caps, double c, double s, std::vector<std::pair<double, double>>& visible,
                    std::vector<std::pair<double, double>>& scratch) {
  const double quarter = kPi / 2;
  visible.assign(1, {0.0, quarter});
  for (const Cap& cap : caps) {
    const double a = cap.axis[0] * c + cap.axis[1] * s, z = cap.axis[2], rho = std::hypot(a, z);
    if (rho <= cap.cos_half) continue;
    const double centre = std::atan2(a, z), half = std::acos(cap.cos_half / rho);
    for (double shift : {-2 * kPi, 0.0, 2 * kPi}) {
      const double lo = centre + shift - half, hi = centre + shift + half;
      if (hi <= 0 || lo >= quarter) continue;
      scratch.clear();
      for (const auto& [t0, t1] : visible) {
        if (t0 < lo) scratch.push_back({t0, std::min(t1, lo)});
        if (t1 > hi) scratch.push_back({std::max(t0, hi), t1});
      }
      visible.swap(scratch);
    }
  }
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
  if (name == "open") scene = PrtScene::kOpen;
  else if (name == "sphere") scene = PrtScene::kSphere;
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
  switch (scene) {
    case PrtScene::kOpen:
      return 1;
    case PrtScene::kSphere:
      return ray_hits(kOneSphere, p, w) ? 0 : 1;
    case PrtScene::kCorner:
      return wall_hits(p[0], w[0], p[2], w[2]) || wall_hits(p[1], w[1], p[2], w[2]) ? 0 : 1;
    case PrtScene::kSpheres:
      for (const Sphere& s : kThreeSpheres)
        if (ray_hits(s, p, w)) return 0;
      return 1;
  }
  return 1;
}

double prt_transfer(PrtScene scene, PrtTransfer transfer, const Point& p, const Point& w) {
  const double t = unshadowed_transfer(transfer, w);
  return t == 0 ? 0 : t * prt_visibility(scene, p, w);
}

double prt_exact_shading(PrtScene scene, PrtTransfer transfer, const Radiance& sky, const Point& p, double step) {
  if (!(step > 0 && step <= 1)) throw std::invalid_argument("the exact shading's step must be in (0, 1]");
  const std::vector<Cap> caps = occluder_caps(scene, p);
  std::vector<double> x, w;
  sh::gauss_legendre(kPrtExactNodes, x, w);
  for (double& v : x) v = 0.5 * (v + 1);  // nodes and weights on [0, 1]
  for (double& v : w) v *= 0.5;
  std::vector<std::pair<double, double>> visible, scratch;
  double total = 0;
  for (const auto& [a, b] : phi_pieces(caps)) {
    const int panels = static_cast<int>(std::ceil(1.5 * (b - a) / step));
    for (int panel = 0; panel < panels; ++panel)
      for (int i = 0; i < kPrtExactNodes; ++i) {
        const double u = (panel + x[i]) / panels, phi = a + (b - a) * u * u * (3 - 2 * u);
        const double phi_weight = (b - a) * 6 * u * (1 - u) * w[i] / panels;
        const double c = std::cos(phi), s = std::sin(phi);
        visible_thetas(caps, c, s, visible, scratch);
        double inner = 0;
        for (const auto& [t0, t1] : visible) {
          const int theta_panels = static_cast<int>(std::ceil((t1 - t0) / step));
          const double width = (t1 - t0) / theta_panels;
          for (int tp = 0; tp < theta_panels; ++tp)
            for (int j = 0; j < kPrtExactNodes; ++j) {
              const double theta = t0 + width * (tp + x[j]), st = std::sin(theta);
              const Point dir{st * c, st * s, std::cos(theta)};
              const double t = unshadowed_transfer(transfer, dir);
              if (t != 0) inner += width * w[j] * st * t * sky(dir);
            }
        }
        total += phi_weight * inner;
      }
  }
  return total;
}

int prt_bytes_whole_bands(int coefficients) { return kPrtValueBytes * coefficients; }

int prt_bytes_largest(int kept, int of) { return kept * (kPrtValueBytes + (of <= 256 ? 1 : of <= 65536 ? 2 : 4)); }

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

  // Exact shading, a vertex per thread.
  std::vector<double> exact(count);
  for (int first = 0; first < count; first += threads) {
    if (checkpoint) checkpoint(first, count);
    runtime::parallel_for(std::min(threads, count - first), threads,
                          [&](int b) { exact[first + b] = prt_exact_shading(scene, transfer, sky, vertices[first + b]); });
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
    const int best = std::min(k, n_sh);
    row.sh_bytes = prt_bytes_whole_bands(bands * bands);
    row.sh_best_bytes = prt_bytes_largest(best, n_sh);
    row.needlet_bytes = prt_bytes_largest(k, n_frame);
    double sh_square = 0, sh_best_square = 0, needlet_square = 0;
    for (int v = 0; v < count; ++v) {
      double sh = 0, sh_best = 0, needlet = 0;
      for (int i = 0; i < bands * bands; ++i) sh += sky_sh[i] * transfer_sh[v][i];
      for (int i : largest(transfer_sh[v], best)) sh_best += sky_sh[i] * transfer_sh[v][i];
      for (int i : largest(transfer_beta[v], k)) needlet += sky_beta[i] * transfer_beta[v][i];
      row.sh.push_back(sh);
      row.sh_best.push_back(sh_best);
      row.needlet.push_back(needlet);
      sh_square += (sh - exact[v]) * (sh - exact[v]);
      sh_best_square += (sh_best - exact[v]) * (sh_best - exact[v]);
      needlet_square += (needlet - exact[v]) * (needlet - exact[v]);
      row.sh_worst = std::max(row.sh_worst, std::abs(sh - exact[v]) / exact_largest);
      row.sh_best_worst = std::max(row.sh_best_worst, std::abs(sh_best - exact[v]) / exact_largest);
      row.needlet_worst = std::max(row.needlet_worst, std::abs(needlet - exact[v]) / exact_largest);
      if (k == n_frame) report.parseval_gap = std::max(report.parseval_gap, std::abs(needlet - sh) / report.exact_rms);
    }
    row.sh_rms = std::sqrt(sh_square / count) / report.exact_rms;
    row.sh_best_rms = std::sqrt(sh_best_square / count) / report.exact_rms;
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
