// Spherical t-designs and frames (frames/): the shipped designs checked by a path that shares no
// code with the search (monomials integrated in long double against their closed form), the
// search's determinism, and frame bounds against what designs and lobe tables must give.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"
#include "test_tolerances.h"
#include "zhf/frames/designs.h"
#include "zhf/frames/frame.h"
#include "zhf/frames/limits.h"
#include "zhf/runtime/table_io.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"

namespace zhf::frames {
namespace {

namespace fs = std::filesystem;
constexpr long double kPi = 3.14159265358979323846264338327950288L;

// int over the sphere of x^a y^b z^c: 2 G((a+1)/2) G((b+1)/2) G((c+1)/2) / G((a+b+c+3)/2), zero
// when any power is odd.
long double monomial_integral(int a, int b, int c) {
  if (a % 2 || b % 2 || c % 2) return 0;
  return 2 * std::tgamma((a + 1) / 2.0L) * std::tgamma((b + 1) / 2.0L) * std::tgamma((c + 1) / 2.0L) / std::tgamma((a + b + c + 3) / 2.0L);
}

long double power(long double x, int k) {
  long double p = 1;
  for (int i = 0; i < k; ++i) p *= x;
  return p;
}

// The equal-weight rule of the points for x^a y^b z^c.
long double rule(const std::vector<Point>& points, int a, int b, int c) {
  long double sum = 0;
  for (const Point& p : points) sum += power(p[0], a) * power(p[1], b) * power(p[2], c);
  return 4 * kPi * sum / points.size();
}

// Every monomial of degree <= t, and a random polynomial of degree t, against the closed form.
void expect_exact_to_degree(const std::vector<Point>& points, int t, std::mt19937_64& rng, sh::Normal<>& normal) {
  long double random_rule = 0, random_exact = 0;
  for (int a = 0; a <= t; ++a)
    for (int b = 0; a + b <= t; ++b)
      for (int c = 0; a + b + c <= t; ++c) {
        const long double got = rule(points, a, b, c), exact = monomial_integral(a, b, c);
        EXPECT_NEAR(double(got), double(exact), zhf::tolerance::kDesignQuadrature) << "t " << t << ", x^" << a << " y^" << b << " z^" << c;
        const double w = normal(rng);
        random_rule += w * got;
        random_exact += w * exact;
      }
  EXPECT_NEAR(double(random_rule), double(random_exact), 10 * zhf::tolerance::kDesignQuadrature) << "t " << t;
}

TEST(Designs, ShippedDesignsIntegrateEveryPolynomialOfTheirDegree) {
  std::mt19937_64 rng(9);
  sh::Normal<> normal;
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(test::source_path("generated/designs"))) {
    const nlohmann::json j = test::read_json(entry.path().string());
    const int t = j.at("t");
    const std::vector<Point> points = read_points(entry.path().string());
    ASSERT_EQ(points.size(), j.at("count").get<size_t>()) << entry.path();
    EXPECT_LE(design_residual(points, t), zhf::tolerance::kDesignResidual) << "t " << t;
    if (t <= 21) {
      EXPECT_LE(points.size(), static_cast<size_t>(best_known_count(t))) << "t " << t << ": more points than the best known";
    }
    if (j.at("symmetric")) {
      for (size_t i = 0; i < points.size() / 2; ++i)
        for (int c = 0; c < 3; ++c) ASSERT_EQ(points[i][c], -points[i + points.size() / 2][c]) << "t " << t << ", point " << i;
    }
    expect_exact_to_degree(points, t, rng, normal);
    ++checked;
  }
  EXPECT_GE(checked, 21);
}

TEST(Designs, SearchIsDeterministicWhateverTheThreads) {
  DesignSearch s;
  s.t = 8;
  s.points = 36;
  s.starts = 8;
  s.seed = 3;
  s.threads = 1;
  const Design one = search_design(s);
  s.threads = 3;
  const Design three = search_design(s);
  ASSERT_GE(one.start, 0);
  EXPECT_EQ(one.start, three.start);
  ASSERT_EQ(one.points.size(), three.points.size());
  for (size_t i = 0; i < one.points.size(); ++i) EXPECT_EQ(one.points[i], three.points[i]) << "point " << i;
  s.symmetry = Symmetry::kAntipodal;
  s.t = 9;
  s.points = symmetric_count(9);  // 48, the smallest known count
  const Design antipodal = search_design(s);
  ASSERT_GE(antipodal.start, 0);
  EXPECT_LE(design_residual(antipodal.points, 9), zhf::tolerance::kDesignResidual);
}

// The search on 1 and on 2 threads (the same design expected), and that design checked by every
// monomial of degree <= t in long double, independently of the search.
Design search_on_one_and_two_threads(DesignSearch s) {
  s.threads = 1;
  const Design one = search_design(s);
  s.threads = 2;
  const Design two = search_design(s);
  EXPECT_EQ(one.start, two.start);
  EXPECT_EQ(one.points, two.points);
  EXPECT_LE(design_residual(one.points, s.t), zhf::tolerance::kDesignResidual);
  std::mt19937_64 rng(9);
  sh::Normal<> normal;
  expect_exact_to_degree(one.points, s.t, rng, normal);
  return one;
}

TEST(Designs, TetrahedralSetsReachTheSmallestKnownCountsAtEvenStrengths) {
  for (int t = 12; t <= 20; t += 2) EXPECT_EQ(tetrahedral_count(t), best_known_count(t)) << "t " << t;
  EXPECT_LT(tetrahedral_count(50), efficient_count(50));
  DesignSearch s;
  s.t = 12;
  s.points = 84;
  s.symmetry = Symmetry::kTetrahedral;
  s.starts = 16;
  const Design one = search_on_one_and_two_threads(s);
  ASSERT_GE(one.start, 0);
  // The set is whole orbits: the half turn about z and the third turn about (1, 1, 1) map it to itself.
  for (const Point& p : one.points) {
    const Point half{-p[0], -p[1], p[2]}, third{p[2], p[0], p[1]};
    int found = 0;
    for (const Point& q : one.points) found += (q == half) + (q == third);
    EXPECT_EQ(found, 2);
  }
  s.points = 90;
  EXPECT_THROW(search_design(s), std::invalid_argument);  // not whole orbits
}

// The turn by 120 degrees about z maps the set to itself (up to the rounding of its sine).
void expect_threefold(const std::vector<Point>& points) {
  const double c = -0.5, sn = std::sqrt(3.0) / 2;
  for (const Point& p : points) {
    const Point turned{c * p[0] - sn * p[1], sn * p[0] + c * p[1], p[2]};
    double nearest = 1;
    for (const Point& q : points) nearest = std::min(nearest, std::hypot(q[0] - turned[0], q[1] - turned[1], q[2] - turned[2]));
    EXPECT_LE(nearest, zhf::tolerance::kExactToRounding);
  }
}

TEST(Designs, ThreefoldSetsAreWholeOrbitsAndExact) {
  DesignSearch s;
  s.t = 17;
  s.points = threefold_count(17);  // 162, one below the efficient count
  EXPECT_LT(s.points, efficient_count(17));
  s.symmetry = Symmetry::kThreefold;
  s.starts = 16;
  const Design one = search_on_one_and_two_threads(s);
  ASSERT_GE(one.start, 0);
  expect_threefold(one.points);
}

// Antipodal threefold orbits (6 points each) at t = 23: 276 points, 2 below the antipodal count.
// The set is its first half and that half's negatives, and the turn by 120 degrees about z maps it
// to itself; one orbit fewer has fewer parameters than invariants (the whole set turns freely
// about z) and finds nothing.
TEST(Designs, AntipodalThreefoldSetsAreWholeOrbitsAndExact) {
  DesignSearch s;
  s.t = 23;
  s.points = antipodal_threefold_count(23);
  EXPECT_EQ(s.points, 276);
  EXPECT_LT(s.points, symmetric_count(23));
  s.symmetry = Symmetry::kAntipodalThreefold;
  s.starts = 16;
  const Design one = search_on_one_and_two_threads(s);
  ASSERT_GE(one.start, 0);
  const std::size_t half = one.points.size() / 2;
  for (std::size_t i = 0; i < half; ++i)
    for (int k = 0; k < 3; ++k) ASSERT_EQ(one.points[i + half][k], -one.points[i][k]) << "point " << i;
  expect_threefold(one.points);
  s.points -= 6;
  s.starts = 4;
  EXPECT_LT(search_design(s).start, 0);
}

// The default never takes more points than the smallest known count (t <= 21), zhf's antipodal
// construction (its count, symmetric_count, is reached from t = 19 on; below that the smallest
// known counts are smaller than antipodal searches reach) or the efficient count, at every t.
TEST(Designs, DefaultCountsNeverExceedTheAntipodalTheBestKnownOrTheEfficientCount) {
  for (int t = 1; t <= frames::kMaxDesignStrength; ++t) {
    const DesignChoice choice = default_design(t);
    EXPECT_EQ(choice.points % orbit_size(choice.symmetry), 0) << "t " << t;
    if (t <= 21) {
      EXPECT_LE(choice.points, best_known_count(t)) << "t " << t;
    }
    if (t >= 19) {
      EXPECT_LE(choice.points, symmetric_count(t)) << "t " << t;
    }
    if (t > 10) {
      EXPECT_LE(choice.points, efficient_count(t)) << "t " << t;
    }
  }
  EXPECT_EQ(default_design(39).symmetry, Symmetry::kAntipodalThreefold);  // 780 points, antipodal 782, threefold 801
  EXPECT_EQ(default_design(39).points, 780);
  EXPECT_EQ(default_design(49).symmetry, Symmetry::kAntipodal);  // 1228 points, antipodal threefold 1230
  EXPECT_EQ(default_design(40).symmetry, Symmetry::kTetrahedral);
  // A symmetry asked for without a count: the default's count where the symmetry is the default's,
  // otherwise its own.
  for (int t = 1; t <= frames::kMaxDesignStrength; ++t)
    EXPECT_EQ(symmetry_count(default_design(t).symmetry, t), default_design(t).points) << "t " << t;
  EXPECT_EQ(symmetry_count(Symmetry::kAntipodal, 12), 94);  // an antipodal 12-design is a 13-design
  EXPECT_EQ(symmetry_count(Symmetry::kAntipodalThreefold, 25), 330);
  EXPECT_EQ(symmetry_count(Symmetry::kTetrahedral, 31), tetrahedral_count(31));
  EXPECT_EQ(symmetry_count(Symmetry::kThreefold, 39), 801);
}

// docs/frames.md's table of the default count for every t, held to the code.
TEST(Designs, TheDocumentedCountsAreTheDefaults) {
  std::istringstream doc(test::read_text(test::source_path("docs/frames.md")));
  const std::string header = "| t | M (zhf) | symmetry | antipodal M | best known M (t <= 21) or efficient count |";
  std::string line;
  while (std::getline(doc, line) && line != header) {
  }
  ASSERT_EQ(line, header) << "docs/frames.md has no table of counts";
  std::getline(doc, line);  // | --- | ...
  int t = 0;
  while (std::getline(doc, line) && !line.empty()) {
    ++t;
    const DesignChoice choice = default_design(t);
    const int best = best_known_count(t);
    const std::string expected = "| " + std::to_string(t) + " | " + std::to_string(choice.points) + " | " + symmetry_name(choice.symmetry) +
                                 " | " + std::to_string(symmetric_count(t)) + " | " + std::to_string(best > 0 ? best : efficient_count(t)) + " |";
    EXPECT_EQ(line, expected) << "t " << t;
  }
  EXPECT_EQ(t, frames::kMaxDesignStrength);
}

TEST(Designs, RefusesWhatItCannotSearch) {
  DesignSearch s;
  s.points = 10;
  for (int t : {0, frames::kMaxDesignStrength + 1}) {
    s.t = t;
    EXPECT_THROW(search_design(s), std::invalid_argument) << t;
  }
  s.t = 3;
  s.points = 1;
  EXPECT_THROW(search_design(s), std::invalid_argument);
  s.points = 7;
  s.symmetry = Symmetry::kAntipodal;
  EXPECT_THROW(search_design(s), std::invalid_argument);
  s.symmetry = Symmetry::kThreefold;
  s.points = 10;
  EXPECT_THROW(search_design(s), std::invalid_argument);  // not whole orbits of 3
  s.symmetry = Symmetry::kAntipodalThreefold;
  s.points = 9;
  EXPECT_THROW(search_design(s), std::invalid_argument);  // not whole orbits of 6
}

TEST(Frames, DesignsMakeTightFramesUpToHalfTheirStrength) {
  for (int t : {2, 4, 7, 10, 15}) {
    const std::vector<Point> d = read_points(design_path(test::source_path("generated/designs"), t));
    const FrameBounds tight = frame_bounds(d, 0, t / 2);
    EXPECT_TRUE(tight.tight()) << "t " << t << ": A " << tight.lower << ", B " << tight.upper;
    EXPECT_NEAR(tight.lower, d.size() / (4 * double(kPi)), 1e-12 * tight.upper) << "t " << t;
    // Scaled by sqrt(4 pi / M): Parseval.
    std::vector<Point> same = d;
    const FrameBounds one_band = frame_bounds(same, t / 2, t / 2);
    EXPECT_TRUE(one_band.tight()) << "t " << t;
    EXPECT_NEAR(one_band.condition(), 1.0, zhf::tolerance::kTightFrame) << "t " << t;
  }
}

TEST(Frames, LobeTablesAreFramesWithTheirConditionNumbers) {
  for (int order : {4, 6, 8, 12}) {
    const runtime::LobeTable table = runtime::read_lobe_table(test::checked_in_table(order));
    for (const runtime::TableBand& band : table.bands) {
      std::vector<Point> lobes;
      for (int d : band.lobes) lobes.push_back({table.lobes[d].xyz[0], table.lobes[d].xyz[1], table.lobes[d].xyz[2]});
      const FrameBounds b = frame_bounds(lobes, band.l, band.l);
      EXPECT_NEAR(b.condition(), band.condition, zhf::tolerance::kTableConditionRelative * band.condition)
          << "order " << order << ", band " << band.l;
      EXPECT_EQ(b.redundancy(), 1.0);
    }
  }
  // Too few directions span nothing: not a frame.
  const FrameBounds thin = frame_bounds({{0, 0, 1}, {1, 0, 0}}, 2, 2);
  EXPECT_FALSE(thin.frame());
  EXPECT_THROW(frame_bounds({}, 0, 1), std::invalid_argument);
  EXPECT_THROW(frame_bounds({{0, 0, 1}}, 3, 2), std::invalid_argument);
}

}  // namespace
}  // namespace zhf::frames
