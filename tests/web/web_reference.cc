// Writes what the WebAssembly module's tests (tests/web/*.test.mjs) hold it to: inputs, their
// rotations by the independent reference (runtime/band_recurrence.h in long double, as
// test::worst_against_recurrence), and the tolerance the native tests use for each order and type
// (test::rotation_tolerance). Orders 1..16: the generated orders and run-time ones; one rotation for
// many vectors, one per vector, in zhf's convention and others; 3D Gaussian Splatting splats of
// degree 0..4 in their convention. Inputs are float values (each vector of unit norm), so the float
// and double paths rotate the same numbers.
// Usage: web_reference OUT.json
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "test_support.h"
#include "zhf/runtime/band_recurrence.h"
#include "zhf/runtime/conventions.h"
#include "zhf/sh/random.h"
#include "zhf/sh/rotation_matrix.h"

namespace {

using zhf::runtime::Matrix3;

constexpr int kMaxOrder = 16;
constexpr int kVectors = 12;
constexpr int kSplats = 20;

// count vectors of order^2 float values, each of unit norm.
std::vector<double> unit_vectors(int order, int count, std::mt19937_64& rng) {
  zhf::sh::Normal<> normal;
  const int n = order * order;
  std::vector<double> v(std::size_t(count) * n);
  for (int k = 0; k < count; ++k) {
    double norm = 0;
    for (int i = 0; i < n; ++i) norm += (v[k * n + i] = normal(rng)) * v[k * n + i];
    for (int i = 0; i < n; ++i) v[k * n + i] = double(float(v[k * n + i] / std::sqrt(norm)));
  }
  return v;
}

// f rotated by r (zhf's terms) through the long-double recurrence.
std::vector<double> rotated(const Matrix3& r, int order, const double* f) {
  const auto bands = zhf::runtime::recurrence_band_matrices<long double>(r.data(), order);
  std::vector<double> out(std::size_t(order) * order);
  for (int l = 0; l < order; ++l)
    for (int i = 0; i < 2 * l + 1; ++i) {
      long double sum = 0;
      for (int j = 0; j < 2 * l + 1; ++j) sum += bands[l][i * (2 * l + 1) + j] * f[l * l + j];
      out[l * l + i] = double(sum);
    }
  return out;
}

Matrix3 random_rotation(std::mt19937_64& rng) { return zhf::sh::to_array(zhf::sh::random_rotation(rng)); }

const zhf::runtime::Convention& convention(const char* name) { return *zhf::runtime::find_convention(name); }

nlohmann::json tolerances(int order) {
  return {{"float", zhf::test::rotation_tolerance<float>(order)}, {"double", zhf::test::rotation_tolerance<double>(order)}};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: web_reference OUT.json\n");
    return 2;
  }
  std::mt19937_64 rng(69);
  nlohmann::json cases = nlohmann::json::array();
  for (int order = 1; order <= kMaxOrder; ++order) {
    const int n = order * order;
    for (const char* name : {"zhf", "3dgs", "y-up-rh"}) {
      if (order > 4 && std::string(name) != "zhf") continue;  // conventions at the small orders
      const zhf::runtime::Convention& c = convention(name);
      const Matrix3 shared = random_rotation(rng);
      const std::vector<double> in = unit_vectors(order, kVectors, rng);
      std::vector<double> each_rotations, out_shared, out_each;
      for (int v = 0; v < kVectors; ++v) {
        const std::vector<double> a = rotated(c.rotation_in_zhf_terms(shared), order, &in[std::size_t(v) * n]);
        out_shared.insert(out_shared.end(), a.begin(), a.end());
        const Matrix3 r = random_rotation(rng);  // rounded to float by the float test, as the native tests do
        each_rotations.insert(each_rotations.end(), r.begin(), r.end());
        const std::vector<double> b = rotated(c.rotation_in_zhf_terms(r), order, &in[std::size_t(v) * n]);
        out_each.insert(out_each.end(), b.begin(), b.end());
      }
      cases.push_back({{"order", order}, {"convention", name}, {"tolerance", tolerances(order)}, {"rotation", shared},
                       {"coefficients", in}, {"rotated", out_shared}, {"rotations", each_rotations}, {"rotated_each", out_each}});
    }
  }
  nlohmann::json splats = nlohmann::json::array();
  for (int degree = 0; degree <= 4; ++degree) {
    const int order = degree + 1, rest = order * order - 1;
    const Matrix3 r = random_rotation(rng);
    const Matrix3 q = convention("3dgs").rotation_in_zhf_terms(r);
    const std::vector<double> channels = unit_vectors(order, 3 * kSplats, rng);
    std::vector<double> in, out;
    for (int s = 0; s < kSplats; ++s) {
      // The splat's three channels, each a unit vector, in the .ply's layout.
      std::vector<std::vector<double>> turned;
      for (int c = 0; c < 3; ++c) turned.push_back(rotated(q, order, &channels[std::size_t(3 * s + c) * order * order]));
      for (int c = 0; c < 3; ++c) in.push_back(channels[std::size_t(3 * s + c) * order * order]);
      for (int c = 0; c < 3; ++c) out.push_back(turned[c][0]);
      for (int c = 0; c < 3; ++c)
        for (int i = 1; i <= rest; ++i) {
          in.push_back(channels[std::size_t(3 * s + c) * order * order + i]);
          out.push_back(turned[c][i]);
        }
    }
    splats.push_back({{"degree", degree}, {"tolerance", tolerances(order)}, {"rotation", r}, {"splats", in}, {"rotated", out}});
  }
  std::ofstream file(argv[1]);
  file << nlohmann::json{{"cases", cases}, {"splats", splats}}.dump();
  return file ? 0 : 1;
}
