// Candidate lobe directions for an order N: directions at which band-l SH basis functions
// vanish, which is where sparse inverses A_l = Y_l^-1 come from.
//
// theta: roots of P_l^m(cos theta), 2 <= l <= N-1, 0 <= m <= l, plus the poles and the
//        equator (the root of P_1^0).
// phi:   zeros of sin(m phi) and cos(m phi), 1 <= m <= N-1, wrapped to (-pi, pi].
// A direction is a (theta, phi) pair with theta strictly between the poles; each pole is
// one direction (phi = 0), whatever phi it is written with.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include "zhf/candidates/limits.h"

namespace zhf::candidates {


struct AngleValue {
  double value = 0;
  std::vector<std::string> sources;  // e.g. "root 2 of P_7^2", "zero of cos(3 phi)"
};

struct Direction {
  double theta = 0;
  double phi = 0;
  double xyz[3] = {0, 0, 0};
  int theta_index = 0;  // into CandidateSet::thetas
  int phi_index = -1;   // into CandidateSet::phis; -1 at the poles
  std::vector<std::string> sources;  // theta's sources then phi's
};

struct CandidateSet {
  int order = 0;
  std::vector<AngleValue> thetas;      // ascending, poles and equator included
  std::vector<AngleValue> phis;        // ascending in (-pi, pi]
  std::vector<Direction> directions;   // north pole, theta-major rows, south pole
};

// Throws std::invalid_argument naming the order when it is outside
// [candidates::kMinSearchOrder, candidates::kMaxSearchOrder].
CandidateSet enumerate_candidates(int order);

// Exact phi zeros as reduced fractions num/den of pi in (-1, 1].
struct PiFraction {
  int num = 0;
  int den = 1;
};
std::vector<std::pair<PiFraction, std::string>> phi_zeros(int max_m);

nlohmann::ordered_json to_json(const CandidateSet& set);

// Index of the candidate within max_distance of xyz (Euclidean), or -1.
int find_direction(const CandidateSet& set, const double xyz[3], double max_distance);

}  // namespace zhf::candidates
