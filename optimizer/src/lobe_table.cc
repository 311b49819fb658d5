#include "zhf/optimizer/lobe_table.h"

#include <cmath>
#include <sstream>

#include <Eigen/LU>
#include <Eigen/SVD>

#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/sh/eval.h"
#include "zhf/sh/index.h"

namespace zhf::optimizer {
namespace {

std::string join(const std::vector<std::string>& parts, const char* separator) {
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i) out += (i ? separator : "") + parts[i];
  return out;
}

std::string format_number(double value) {
  std::ostringstream s;
  s.precision(3);
  s << value;
  return s.str();
}

double condition_number(const Eigen::MatrixXd& y) {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(y);
  const auto& s = svd.singularValues();
  return s(s.size() - 1) > 0 ? s(0) / s(s.size() - 1) : INFINITY;
}

// Field access that names what is missing or mistyped.
class Reader {
 public:
  explicit Reader(std::string name) : name_(std::move(name)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw io::InputError(name_ + ": " + field + ": " + what);
  }
  const nlohmann::json& at(const nlohmann::json& object, const std::string& key, const std::string& field) const {
    if (!object.is_object()) fail(field, "expected an object");
    auto it = object.find(key);
    if (it == object.end()) fail(field + (field.empty() ? "" : ".") + key, "missing");
    return *it;
  }
  double number(const nlohmann::json& value, const std::string& field) const {
    if (!value.is_number()) fail(field, "expected a number");
    const double x = value.get<double>();
    if (!std::isfinite(x)) fail(field, "not finite");
    return x;
  }
  int integer(const nlohmann::json& value, const std::string& field) const {
    if (!value.is_number_integer()) fail(field, "expected an integer");
    return value.get<int>();
  }
  const nlohmann::json& array(const nlohmann::json& value, const std::string& field, size_t size) const {
    if (!value.is_array()) fail(field, "expected an array");
    if (value.size() != size)
      fail(field, "expected " + std::to_string(size) + " entries, found " + std::to_string(value.size()));
    return value;
  }

 private:
  std::string name_;
};

}  // namespace

double LobeTable::worst_condition() const {
  double worst = 0;
  for (const TableBand& band : bands) worst = std::max(worst, band.condition);
  return worst;
}

Eigen::MatrixXd LobeTable::band_matrix(int l) const {
  const TableBand& band = bands.at(l - 2);
  Eigen::MatrixXd y(2 * l + 1, 2 * l + 1);
  std::vector<double> values(2 * l + 1);
  for (int d = 0; d < 2 * l + 1; ++d) {
    sh::eval_band(l, lobes.at(band.lobes[d]).xyz, values.data());
    for (int k = 0; k < 2 * l + 1; ++k) y(d, k) = values[k];
  }
  return y;
}

LobeTable make_table(const LobeEvaluator& evaluator, const Genome& genes, const nlohmann::json& provenance) {
  LobeTable table;
  table.order = evaluator.order();
  table.lobe_sharing = evaluator.lobe_sharing();
  for (int c : genes) {
    const candidates::Direction& d = evaluator.candidates().directions.at(c);
    TableLobe lobe;
    lobe.theta = d.theta;
    lobe.phi = d.phi;
    std::copy(d.xyz, d.xyz + 3, lobe.xyz);
    lobe.source = join(d.sources, "; ");
    table.lobes.push_back(lobe);
  }
  for (BandAnalysis& analysis : evaluator.analyze(genes)) {
    TableBand band;
    band.l = analysis.l;
    band.lobes = analysis.lobes;
    band.inverse = std::move(analysis.inverse);
    band.zeros = analysis.zeros;
    band.condition = analysis.condition;
    table.zeros += band.zeros;
    table.entries += static_cast<int>(band.inverse.size());
    table.bands.push_back(std::move(band));
  }
  table.provenance = provenance;
  return table;
}

nlohmann::ordered_json to_json(const LobeTable& table) {
  nlohmann::ordered_json out;
  out["format"] = kLobeTableFormat;
  out["order"] = table.order;
  out["lobe_sharing"] = table.lobe_sharing;
  nlohmann::ordered_json lobes = nlohmann::ordered_json::array();
  for (const TableLobe& lobe : table.lobes) {
    lobes.push_back({{"theta", lobe.theta},
                     {"phi", lobe.phi},
                     {"xyz", {lobe.xyz[0], lobe.xyz[1], lobe.xyz[2]}},
                     {"source", lobe.source}});
  }
  out["lobes"] = lobes;
  nlohmann::ordered_json bands = nlohmann::ordered_json::array();
  for (const TableBand& band : table.bands) {
    nlohmann::ordered_json inverse = nlohmann::ordered_json::array();
    for (int i = 0; i < band.inverse.rows(); ++i) {
      nlohmann::ordered_json row = nlohmann::ordered_json::array();
      for (int j = 0; j < band.inverse.cols(); ++j) {
        // Structural zeros are written as the integer 0 so they read back exact and stand out.
        if (band.inverse(i, j) == 0) {
          row.push_back(0);
        } else {
          row.push_back(band.inverse(i, j));
        }
      }
      inverse.push_back(row);
    }
    bands.push_back({{"l", band.l},
                     {"lobes", band.lobes},
                     {"inverse", inverse},
                     {"zeros", band.zeros},
                     {"condition", band.condition}});
  }
  out["bands"] = bands;
  out["zeros"] = table.zeros;
  out["entries"] = table.entries;
  out["provenance"] = table.provenance;
  return out;
}

LobeTable table_from_json(const nlohmann::json& json, const std::string& name) {
  const Reader r(name);
  LobeTable table;
  const nlohmann::json& format = r.at(json, "format", "");
  if (!format.is_string() || format.get<std::string>() != kLobeTableFormat)
    r.fail("format", std::string("expected \"") + kLobeTableFormat + "\", found " + format.dump());
  table.order = r.integer(r.at(json, "order", ""), "order");
  if (table.order < 2 || table.order > sh::kMaxOrder)
    r.fail("order", std::to_string(table.order) + " is outside [2, " + std::to_string(sh::kMaxOrder) + "]");
  const nlohmann::json& sharing = r.at(json, "lobe_sharing", "");
  if (!sharing.is_boolean()) r.fail("lobe_sharing", "expected true or false");
  table.lobe_sharing = sharing.get<bool>();

  // Order 2 has no lobe bands; its table is empty but valid (band 1 rotates as a vector).
  const int lobe_total = table.order < 3 ? 0 : lobe_count(table.order, table.lobe_sharing);
  const nlohmann::json& lobes = r.array(r.at(json, "lobes", ""), "lobes", lobe_total);
  for (size_t i = 0; i < lobes.size(); ++i) {
    const std::string field = "lobes[" + std::to_string(i) + "]";
    TableLobe lobe;
    lobe.theta = r.number(r.at(lobes[i], "theta", field), field + ".theta");
    lobe.phi = r.number(r.at(lobes[i], "phi", field), field + ".phi");
    const nlohmann::json& xyz = r.array(r.at(lobes[i], "xyz", field), field + ".xyz", 3);
    for (int k = 0; k < 3; ++k) lobe.xyz[k] = r.number(xyz[k], field + ".xyz[" + std::to_string(k) + "]");
    const nlohmann::json& source = r.at(lobes[i], "source", field);
    if (!source.is_string()) r.fail(field + ".source", "expected a string");
    lobe.source = source.get<std::string>();
    double expected[3];
    sh::direction_from_angles(lobe.theta, lobe.phi, expected);
    double gap = 0;
    for (int k = 0; k < 3; ++k) gap = std::max(gap, std::abs(expected[k] - lobe.xyz[k]));
    if (gap > kTableDirectionTolerance)
      r.fail(field + ".xyz", "disagrees with theta/phi by " + format_number(gap) + " (tolerance 1e-12)");
    table.lobes.push_back(lobe);
  }

  const int band_total = std::max(0, table.order - 2);
  const nlohmann::json& bands = r.array(r.at(json, "bands", ""), "bands", band_total);
  for (int b = 0; b < band_total; ++b) {
    const int l = b + 2;
    const int size = 2 * l + 1;
    const std::string field = "bands[" + std::to_string(b) + "]";
    TableBand band;
    band.l = r.integer(r.at(bands[b], "l", field), field + ".l");
    if (band.l != l) r.fail(field + ".l", "expected " + std::to_string(l) + ", found " + std::to_string(band.l));
    const nlohmann::json& indices = r.array(r.at(bands[b], "lobes", field), field + ".lobes", size);
    for (int d = 0; d < size; ++d) {
      const int index = r.integer(indices[d], field + ".lobes[" + std::to_string(d) + "]");
      if (index != lobe_index(l, d, table.lobe_sharing))
        r.fail(field + ".lobes[" + std::to_string(d) + "]",
               "expected lobe " + std::to_string(lobe_index(l, d, table.lobe_sharing)) + ", found " +
                   std::to_string(index));
      band.lobes.push_back(index);
    }
    const nlohmann::json& rows = r.array(r.at(bands[b], "inverse", field), field + ".inverse", size);
    band.inverse.resize(size, size);
    int zeros = 0;
    for (int i = 0; i < size; ++i) {
      const std::string row_field = field + ".inverse[" + std::to_string(i) + "]";
      const nlohmann::json& row = r.array(rows[i], row_field, size);
      for (int j = 0; j < size; ++j) {
        band.inverse(i, j) = r.number(row[j], row_field + "[" + std::to_string(j) + "]");
        if (band.inverse(i, j) == 0) ++zeros;
      }
    }
    band.zeros = r.integer(r.at(bands[b], "zeros", field), field + ".zeros");
    if (band.zeros != zeros)
      r.fail(field + ".zeros", "says " + std::to_string(band.zeros) + " but the inverse has " + std::to_string(zeros));
    band.condition = r.number(r.at(bands[b], "condition", field), field + ".condition");
    table.bands.push_back(std::move(band));
    table.zeros += zeros;
    table.entries += size * size;
  }
  // Directions and inverses must still belong together (a tampered table fails here).
  for (TableBand& band : table.bands) {
    const std::string field = "bands[" + std::to_string(band.l - 2) + "]";
    const Eigen::MatrixXd y = table.band_matrix(band.l);
    const double condition = condition_number(y);
    if (!(condition <= kSingularCondition))
      r.fail(field, "lobe matrix Y_" + std::to_string(band.l) + " is near-singular (condition " +
                        format_number(condition) + ", limit " + format_number(kSingularCondition) + ")");
    const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(y.rows(), y.cols());
    const double residual = (y * band.inverse - identity).cwiseAbs().maxCoeff();
    if (!(residual <= kTableInverseTolerance))
      r.fail(field + ".inverse", "Y_" + std::to_string(band.l) + " * inverse differs from I by " +
                                     format_number(residual) + " (tolerance 1e-10): directions and inverse disagree");
    if (std::abs(condition - band.condition) > kTableConditionTolerance * condition)
      r.fail(field + ".condition", "says " + format_number(band.condition) + " but the lobes give " +
                                       format_number(condition));
  }
  if (r.integer(r.at(json, "zeros", ""), "zeros") != table.zeros)
    r.fail("zeros", "does not equal the sum over bands (" + std::to_string(table.zeros) + ")");
  if (r.integer(r.at(json, "entries", ""), "entries") != table.entries)
    r.fail("entries", "does not equal the sum over bands (" + std::to_string(table.entries) + ")");
  const nlohmann::json& provenance = r.at(json, "provenance", "");
  if (!provenance.is_object()) r.fail("provenance", "expected an object");
  table.provenance = provenance;
  return table;
}

LobeTable read_table(const std::string& path) { return table_from_json(io::read_json_file(path), path); }

}  // namespace zhf::optimizer
