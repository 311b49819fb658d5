#include <cmath>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "zhf/candidates/candidates.h"
#include "test_support.h"
#include "test_tolerances.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/slow_reference.h"

namespace zhf::candidates {
namespace {

constexpr double kSourceResidual = zhf::tolerance::kRootResidual;
using test::kPaperLobeMatch;

TEST(Candidates, Order3CountsDerivedByHand) {
  // theta: poles (2), roots of P_2^0 (cos^2 = 1/3: 0.9553, 2.1863), P_2^1 (pi/2, also the
  // equator), P_2^2 (none) -> 5 values. phi: m=1: 0, pi, +-pi/2; m=2 adds +-pi/4, +-3pi/4
  // (sin 2phi's zeros repeat m=1's) -> 8 values. Directions: 3 x 8 + 2 poles = 26.
  const CandidateSet set = enumerate_candidates(3);
  EXPECT_EQ(set.thetas.size(), 5u);
  EXPECT_EQ(set.phis.size(), 8u);
  EXPECT_EQ(set.directions.size(), 26u);
}

TEST(Candidates, Order4CountsDerivedByHand) {
  // theta beyond order 3's: P_3^0 (cos^2 = 3/5: 0.6847, 2.4569, and pi/2), P_3^1 (cos^2 =
  // 1/5: 1.1071, 2.0344), P_3^2 (pi/2) -> 7 interior + 2 poles = 9. phi: m=3 adds
  // +-pi/3, +-2pi/3 (sin 3phi) and +-pi/6, +-5pi/6 (cos 3phi; +-pi/2 repeats) -> 16.
  // Directions: 7 x 16 + 2 = 114.
  const CandidateSet set = enumerate_candidates(4);
  EXPECT_EQ(set.thetas.size(), 9u);
  EXPECT_EQ(set.phis.size(), 16u);
  EXPECT_EQ(set.directions.size(), 114u);
}

TEST(Candidates, EveryThetaMakesItsSourcesVanish) {
  for (int order = 3; order <= 12; ++order) {
    const CandidateSet set = enumerate_candidates(order);
    for (const AngleValue& theta : set.thetas) {
      for (const std::string& source : theta.sources) {
        int k = 0, l = 0, m = 0;
        if (std::sscanf(source.c_str(), "root %d of P_%d^%d", &k, &l, &m) != 3) continue;
        const long double value = sh::slow::normalisation(l, m) *
                                  sh::slow::closed_form_legendre(l, m, theta.value);
        EXPECT_LT(std::abs(double(value)), kSourceResidual) << "order " << order << ": " << source;
      }
    }
  }
}

TEST(Candidates, EveryPhiMakesItsSourceVanish) {
  const CandidateSet set = enumerate_candidates(9);
  for (const AngleValue& phi : set.phis) {
    EXPECT_GT(phi.value, -M_PI);
    EXPECT_LE(phi.value, M_PI);
    for (const std::string& source : phi.sources) {
      char fn[4] = {0};
      int m = 1;
      if (std::sscanf(source.c_str(), "zero of %3[a-z](%d phi)", fn, &m) < 1) FAIL() << source;
      const double value = std::string(fn) == "sin" ? std::sin(m * phi.value) : std::cos(m * phi.value);
      EXPECT_LT(std::abs(value), 1e-14) << source << " at " << phi.value;
    }
  }
}

TEST(Candidates, SortedUniqueAndUnit) {
  const CandidateSet set = enumerate_candidates(8);
  for (size_t i = 1; i < set.thetas.size(); ++i) EXPECT_GT(set.thetas[i].value - set.thetas[i - 1].value, zhf::tolerance::kThetaMergeTolerance);
  for (size_t i = 1; i < set.phis.size(); ++i) EXPECT_GT(set.phis[i].value, set.phis[i - 1].value);
  for (size_t i = 0; i < set.directions.size(); ++i) {
    const double* v = set.directions[i].xyz;
    EXPECT_NEAR(v[0] * v[0] + v[1] * v[1] + v[2] * v[2], 1.0, zhf::tolerance::kExactToRounding) << "direction " << i;
    for (size_t j = 0; j < i; ++j) {
      const double* w = set.directions[j].xyz;
      ASSERT_GT(std::abs(v[0] - w[0]) + std::abs(v[1] - w[1]) + std::abs(v[2] - w[2]), 1e-9)
          << "directions " << j << " and " << i << " coincide";
    }
  }
  EXPECT_EQ(set.directions.front().xyz[2], 1.0);
  EXPECT_EQ(set.directions.back().xyz[2], -1.0);
}

TEST(Candidates, PaperLobesAreCandidates) {
  const nlohmann::json reference = test::read_json(test::data_path("paper_lobes.json"));
  int checked = 0;
  for (const auto& entry : reference.at("orders")) {
    const int order = entry.at("N");
    std::vector<CandidateSet> sets;
    for (int n = 3; n <= order; ++n) sets.push_back(enumerate_candidates(n));
    int lobe = 0;
    for (const auto& l : entry.at("lobes")) {
      const double theta = l.at("theta"), phi = l.at("phi");
      const double xyz[3] = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
      bool found = false;
      for (const CandidateSet& set : sets) found = found || find_direction(set, xyz, kPaperLobeMatch) >= 0;
      EXPECT_TRUE(found) << "order " << order << " lobe " << lobe << " (" << theta << ", " << phi << ")";
      ++lobe;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 5 + 7 + 9 + 11 + 13 + 15);
}

TEST(Candidates, RejectsOrderOutOfRange) {
  EXPECT_THROW(enumerate_candidates(2), std::invalid_argument);
  EXPECT_THROW(enumerate_candidates(65), std::invalid_argument);
}

}  // namespace
}  // namespace zhf::candidates
