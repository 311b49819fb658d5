// The lobe table: the file every later stage (code generation, runtime, verify) reads.
//
// JSON, "format": "zhf-lobes-1":
//   order, lobe_sharing, lobes [{theta, phi, xyz [x,y,z], source}],
//   bands [{l, lobes [indices], inverse [[...]] (A_l = Y_l^-1 row-major: rows m+l, columns
//   the band's lobe positions; structural zeros exact), zeros, condition}],
//   zeros, entries, provenance {zhf_version, command, seed, generations, evaluations, ...}.
// Wall-clock time is not recorded: the same command must give the same bytes.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "zhf/optimizer/objective.h"

namespace zhf::optimizer {

inline constexpr const char* kLobeTableFormat = "zhf-lobes-1";
// Reader tolerances: stored xyz vs theta/phi, and Y_l A_l vs I.
inline constexpr double kTableDirectionTolerance = 1e-12;
inline constexpr double kTableInverseTolerance = 1e-10;
// A stored condition number may differ from the recomputed one by this fraction.
inline constexpr double kTableConditionTolerance = 0.01;

struct TableLobe {
  double theta = 0;
  double phi = 0;
  double xyz[3] = {0, 0, 0};
  std::string source;
};

struct TableBand {
  int l = 0;
  std::vector<int> lobes;
  Eigen::MatrixXd inverse;  // A_l
  int zeros = 0;
  double condition = 0;
};

struct LobeTable {
  int order = 0;
  bool lobe_sharing = true;
  std::vector<TableLobe> lobes;
  std::vector<TableBand> bands;  // l = 2..order-1
  int zeros = 0;
  int entries = 0;
  nlohmann::json provenance = nlohmann::json::object();

  double worst_condition() const;
  // Y_l[d][m+l] at the band's lobes.
  Eigen::MatrixXd band_matrix(int l) const;
};

LobeTable make_table(const LobeEvaluator& evaluator, const Genome& genes, const nlohmann::json& provenance);

nlohmann::ordered_json to_json(const LobeTable& table);

// Validates everything; throws io::InputError "<name>: <field>: <what is wrong>".
LobeTable table_from_json(const nlohmann::json& json, const std::string& name);
LobeTable read_table(const std::string& path);

}  // namespace zhf::optimizer
