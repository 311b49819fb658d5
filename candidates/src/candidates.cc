#include "zhf/candidates/candidates.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>

#include "zhf/candidates/limits.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/legendre.h"

namespace zhf::candidates {
namespace {

using runtime::kPi;

std::string legendre_name(int l, int m) { return "P_" + std::to_string(l) + "^" + std::to_string(m); }

void add_theta(std::vector<AngleValue>& thetas, double value, const std::string& source) {
  for (AngleValue& existing : thetas) {
    if (std::abs(existing.value - value) <= zhf::tolerance::kThetaMergeTolerance) {
      existing.sources.push_back(source);
      return;
    }
  }
  thetas.push_back({value, {source}});
}

}  // namespace

std::vector<std::pair<PiFraction, std::string>> phi_zeros(int max_m) {
  std::vector<std::pair<PiFraction, std::string>> zeros;
  for (int m = 1; m <= max_m; ++m) {
    // sin(m phi) = 0 at phi = k pi / m; cos(m phi) = 0 at phi = (2k+1) pi / (2m).
    for (int kind = 0; kind < 2; ++kind) {
      const bool is_sin = kind == 0;
      for (int k = 0; k < 2 * m; ++k) {
        int num = is_sin ? 2 * k : 2 * k + 1;
        int den = 2 * m;
        // Wrap num/den into (-1, 1].
        num %= 2 * den;
        if (num > den) num -= 2 * den;
        const int g = std::gcd(std::abs(num), den);
        const PiFraction f{num / g, den / g};
        const std::string source = std::string("zero of ") + (is_sin ? "sin(" : "cos(") +
                                   (m == 1 ? std::string() : std::to_string(m) + " ") + "phi)";
        zeros.push_back({f, source});
      }
    }
  }
  return zeros;
}

CandidateSet enumerate_candidates(int order) {
  if (order < candidates::kMinSearchOrder || order > candidates::kMaxSearchOrder) {
    throw std::invalid_argument("order " + std::to_string(order) + " is outside [" + std::to_string(candidates::kMinSearchOrder) +
                                ", " + std::to_string(candidates::kMaxSearchOrder) + "]");
  }
  CandidateSet set;
  set.order = order;

  add_theta(set.thetas, 0.0, "north pole");
  add_theta(set.thetas, kPi / 2, "equator (root 1 of P_1^0)");
  add_theta(set.thetas, kPi, "south pole");
  for (int l = 2; l < order; ++l) {
    for (int m = 0; m <= l; ++m) {
      const std::vector<double> roots = sh::legendre_roots_theta(l, m);
      for (size_t k = 0; k < roots.size(); ++k) {
        add_theta(set.thetas, roots[k], "root " + std::to_string(k + 1) + " of " + legendre_name(l, m));
      }
    }
  }
  std::stable_sort(set.thetas.begin(), set.thetas.end(),
                   [](const AngleValue& a, const AngleValue& b) { return a.value < b.value; });

  // Exact rational dedup of phi, ordered by value.
  std::map<std::pair<int, int>, std::vector<std::string>> by_fraction;
  std::vector<PiFraction> fractions;
  for (const auto& [fraction, source] : phi_zeros(order - 1)) {
    auto key = std::make_pair(fraction.num, fraction.den);
    if (by_fraction.find(key) == by_fraction.end()) fractions.push_back(fraction);
    by_fraction[key].push_back(source);
  }
  std::sort(fractions.begin(), fractions.end(), [](const PiFraction& a, const PiFraction& b) {
    return static_cast<long>(a.num) * b.den < static_cast<long>(b.num) * a.den;
  });
  for (const PiFraction& f : fractions) {
    set.phis.push_back({kPi * f.num / f.den, by_fraction[{f.num, f.den}]});
  }

  auto make_direction = [&](int theta_index, int phi_index) {
    const AngleValue& theta = set.thetas[theta_index];
    const double phi = phi_index < 0 ? 0.0 : set.phis[phi_index].value;
    const std::vector<std::string> no_sources;
    const std::vector<std::string>& phi_sources = phi_index < 0 ? no_sources : set.phis[phi_index].sources;
    Direction d;
    d.theta = theta.value;
    d.phi = phi;
    d.theta_index = theta_index;
    d.phi_index = phi_index;
    runtime::direction_from_angles(d.theta, d.phi, d.xyz);
    // cos(pi/2) and friends come out as ~6e-17; the true component is exactly zero.
    for (double& c : d.xyz)
      if (std::abs(c) < zhf::tolerance::kSnapToZero) c = 0.0;
    d.sources = theta.sources;
    d.sources.insert(d.sources.end(), phi_sources.begin(), phi_sources.end());
    return d;
  };
  for (int t = 0; t < static_cast<int>(set.thetas.size()); ++t) {
    const bool pole = set.thetas[t].value == 0.0 || set.thetas[t].value == kPi;
    if (pole) {
      set.directions.push_back(make_direction(t, -1));
      continue;
    }
    for (int p = 0; p < static_cast<int>(set.phis.size()); ++p) set.directions.push_back(make_direction(t, p));
  }
  return set;
}

nlohmann::ordered_json to_json(const CandidateSet& set) {
  nlohmann::ordered_json out;
  out["format"] = "zhf-candidates-1";
  out["order"] = set.order;
  out["theta_merge_tolerance"] = zhf::tolerance::kThetaMergeTolerance;
  auto values = [](const std::vector<AngleValue>& list) {
    nlohmann::ordered_json array = nlohmann::ordered_json::array();
    for (const AngleValue& v : list) array.push_back({{"value", v.value}, {"sources", v.sources}});
    return array;
  };
  out["theta_values"] = values(set.thetas);
  out["phi_values"] = values(set.phis);
  nlohmann::ordered_json directions = nlohmann::ordered_json::array();
  for (const Direction& d : set.directions) {
    directions.push_back({{"theta", d.theta},
                          {"phi", d.phi},
                          {"xyz", {d.xyz[0], d.xyz[1], d.xyz[2]}},
                          {"sources", d.sources}});
  }
  out["directions"] = directions;
  return out;
}

int find_direction(const CandidateSet& set, const double xyz[3], double max_distance) {
  int best = -1;
  double best_distance = max_distance;
  for (size_t i = 0; i < set.directions.size(); ++i) {
    const double* c = set.directions[i].xyz;
    const double d = std::sqrt((c[0] - xyz[0]) * (c[0] - xyz[0]) + (c[1] - xyz[1]) * (c[1] - xyz[1]) +
                               (c[2] - xyz[2]) * (c[2] - xyz[2]));
    if (d <= best_distance) {
      best_distance = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

}  // namespace zhf::candidates
