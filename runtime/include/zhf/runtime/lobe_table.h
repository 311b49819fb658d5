// The lobe table: what every stage after the search reads (code generation, verify, the
// benchmarks, the runtime's table path). This header holds its type and its one validator, and
// includes no reader: table_io.h reads it from JSON, io/lobe_table_writer.h writes it.
//
// JSON, "format": "zhf-lobes-1":
//   order, lobe_sharing,
//   lobes [{theta, phi, xyz [x, y, z] (unit), source (which functions vanish there)}],
//   bands [{l, lobes [indices], inverse [[...]] (A_l = Y_l^-1 row-major: rows m+l, columns the
//           band's lobe positions; structural zeros exact), zeros, condition}]  for l = 2..order-1,
//   zeros, entries, provenance {zhf_version, command, seed, ...}.
// With lobe sharing band l uses lobes 0..2l of one list of 2N-1; without, each band has its own
// 2l+1 lobes (N^2 - 4 in all). Order 2 has no lobe bands: its table is empty but valid.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "zhf/runtime/errors.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/runtime/tolerances.h"

namespace zhf::runtime {

inline constexpr const char* kLobeTableFormat = "zhf-lobes-1";

// A small dense matrix, row-major.
struct Matrix {
  int rows = 0, cols = 0;
  std::vector<double> values;

  Matrix() = default;
  Matrix(int r, int c) : rows(r), cols(c), values(std::size_t(r) * c, 0.0) {}
  double& operator()(int i, int j) { return values[std::size_t(i) * cols + j]; }
  double operator()(int i, int j) const { return values[std::size_t(i) * cols + j]; }
};

struct TableLobe {
  double theta = 0, phi = 0;
  std::array<double, 3> xyz{};
  std::string source;
};

struct TableBand {
  int l = 0;
  std::vector<int> lobes;  // positions in LobeTable::lobes
  Matrix inverse;          // A_l: rows m + l, columns the band's lobe positions
  int zeros = 0;           // exact zeros of A_l
  double condition = 0;    // 2-norm condition number of Y_l
};

struct LobeTable {
  int order = 0;
  bool lobe_sharing = true;
  std::vector<TableLobe> lobes;
  std::vector<TableBand> bands;  // l = 2..order-1
  int zeros = 0, entries = 0;    // summed over bands
  // What made the table (zhf version, the command, the search's figures): one JSON object as
  // compact text. The tools build it with their JSON writer; table_io.h's reader checks it.
  std::string provenance = "{}";

  double worst_condition() const {
    double worst = 0;
    for (const TableBand& band : bands) worst = std::max(worst, band.condition);
    return worst;
  }
};

// The lobe-sharing rule: how many lobes an order has, and which one is lobe d of band l.
inline int lobe_count(int order, bool lobe_sharing) {
  if (order < 3) return 0;
  return lobe_sharing ? 2 * order - 1 : order * order - 4;
}
inline int lobe_index(int l, int d, bool lobe_sharing) { return lobe_sharing ? d : l * l - 4 + d; }

// Y_l[d][m + l] = y_l^m(w_d) at the directions given.
inline Matrix band_matrix(int l, const std::vector<std::array<double, 3>>& directions) {
  const int size = band_size(l);
  Matrix y(size, size);
  for (int d = 0; d < size; ++d) eval_band(l, directions[d].data(), &y.values[std::size_t(d) * size]);
  return y;
}
// Y_l at the table's lobes for band l.
inline Matrix band_matrix(const LobeTable& table, int l) {
  std::vector<std::array<double, 3>> directions;
  for (int index : table.bands.at(l - 2).lobes) directions.push_back(table.lobes.at(index).xyz);
  return band_matrix(l, directions);
}

// Singular values of a square matrix, descending, by one-sided Jacobi rotations (Hestenes):
// columns are rotated pairwise until orthogonal; their norms are then the singular values, each
// to high relative accuracy. Cost: a few sweeps of n^3 for n <= 63.
inline std::vector<double> singular_values(Matrix a) {
  const int n = a.cols, m = a.rows;
  for (int sweep = 0; sweep < 60; ++sweep) {
    bool rotated = false;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) {
        double alpha = 0, beta = 0, gamma = 0;
        for (int i = 0; i < m; ++i) {
          alpha += a(i, p) * a(i, p);
          beta += a(i, q) * a(i, q);
          gamma += a(i, p) * a(i, q);
        }
        if (!(std::abs(gamma) > tolerance::kJacobiOrthogonal * std::sqrt(alpha * beta))) continue;
        rotated = true;
        const double zeta = (beta - alpha) / (2 * gamma);
        const double t = (zeta >= 0 ? 1.0 : -1.0) / (std::abs(zeta) + std::sqrt(1 + zeta * zeta));
        const double c = 1 / std::sqrt(1 + t * t), s = c * t;
        for (int i = 0; i < m; ++i) {
          const double x = a(i, p), y = a(i, q);
          a(i, p) = c * x - s * y;
          a(i, q) = s * x + c * y;
        }
      }
    if (!rotated) break;
  }
  std::vector<double> sigma(n);
  for (int j = 0; j < n; ++j) {
    double norm = 0;
    for (int i = 0; i < m; ++i) norm += a(i, j) * a(i, j);
    sigma[j] = std::sqrt(norm);
  }
  std::sort(sigma.begin(), sigma.end(), [](double x, double y) { return x > y; });
  return sigma;
}

// The 2-norm condition number of Y_l; infinity for a singular (or non-finite) matrix.
inline double condition_number(const Matrix& y) {
  const std::vector<double> s = singular_values(y);
  return s.back() > 0 && std::isfinite(s.front()) ? s.front() / s.back() : INFINITY;
}

// How much A_l = Y_l^-1 amplifies rounding in the samples it multiplies:
//   a_l = |row of Y_l| / sigma_min(Y_l) = sqrt((2l+1)/4pi) ||A_l||_2   (1 for an orthogonal Y_l),
// since every row of Y_l has that norm (addition theorem).
inline double band_amplification(const Matrix& y) {
  const double row_norm = std::sqrt(y.rows / (4 * kPi));
  const double smallest = singular_values(y).back();
  return smallest > 0 ? row_norm / smallest : INFINITY;
}


// kShape: what using a table safely needs (its order in range, the shape for its order and
// sharing, each band's lobes as the sharing rule says, finite numbers, unit lobes). kFull adds
// what makes it the table of its lobes: xyz agreeing with theta/phi, Y_l A_l = I, the stated
// zeros and conditions, no near-singular band.
enum class TableCheck { kShape, kFull };

// The one validator. Throws InputError "<source>: <field>: <problem>". Cost of kFull: one SVD and
// one product per band (about 0.1 s at order 32); kShape is linear in the table's size.
inline void validate_lobe_table(const LobeTable& table, const std::string& source, TableCheck check = TableCheck::kFull) {
  const bool full = check == TableCheck::kFull;
  auto fail = [&](const std::string& field, const std::string& what) { throw InputError(source + ": " + field + ": " + what); };
  if (table.order < kMinTableOrder || table.order > kMaxTableOrder)
    fail("order", "must be " + std::to_string(kMinTableOrder) + ".." + std::to_string(kMaxTableOrder) + " (got " +
                      std::to_string(table.order) + ")");
  const int lobe_total = lobe_count(table.order, table.lobe_sharing);
  if (static_cast<int>(table.lobes.size()) != lobe_total)
    fail("lobes", "expected " + std::to_string(lobe_total) + " entries, found " + std::to_string(table.lobes.size()));
  for (std::size_t i = 0; i < table.lobes.size(); ++i) {
    const std::string field = "lobes[" + std::to_string(i) + "]";
    const TableLobe& lobe = table.lobes[i];
    const auto& w = lobe.xyz;
    for (double x : {lobe.theta, lobe.phi, w[0], w[1], w[2]})
      if (!std::isfinite(x)) fail(field, "not finite");
    if (!(std::abs(w[0] * w[0] + w[1] * w[1] + w[2] * w[2] - 1) <= tolerance::kTableDirection))
      fail(field + ".xyz", "not a unit vector");
    if (!full) continue;
    double expected[3];
    direction_from_angles(lobe.theta, lobe.phi, expected);
    double gap = 0;
    for (int k = 0; k < 3; ++k) gap = std::max(gap, std::abs(expected[k] - w[k]));
    if (!(gap <= tolerance::kTableDirection))
      fail(field + ".xyz", "disagrees with theta/phi by " + format_number(gap) + " (tolerance " + format_number(tolerance::kTableDirection) + ")");
    if (!is_printable_text(lobe.source))
      fail(field + ".source", "control characters and backslashes are not allowed ('" + excerpt(lobe.source) + "')");
  }
  const int band_total = std::max(0, table.order - 2);
  if (static_cast<int>(table.bands.size()) != band_total)
    fail("bands", "expected " + std::to_string(band_total) + " entries, found " + std::to_string(table.bands.size()));
  int zeros_total = 0, entries_total = 0;
  for (int b = 0; b < band_total; ++b) {
    const TableBand& band = table.bands[b];
    const int l = b + 2, size = band_size(l);
    const std::string field = "bands[" + std::to_string(b) + "]";
    if (band.l != l) fail(field + ".l", "expected " + std::to_string(l) + ", found " + std::to_string(band.l));
    if (static_cast<int>(band.lobes.size()) != size)
      fail(field + ".lobes", "expected " + std::to_string(size) + " entries, found " + std::to_string(band.lobes.size()));
    for (int d = 0; d < size; ++d)
      if (band.lobes[d] != lobe_index(l, d, table.lobe_sharing) || band.lobes[d] >= lobe_total)
        fail(field + ".lobes[" + std::to_string(d) + "]", "expected lobe " + std::to_string(lobe_index(l, d, table.lobe_sharing)) +
                                                               ", found " + std::to_string(band.lobes[d]));
    if (band.inverse.rows != size || band.inverse.cols != size || band.inverse.values.size() != std::size_t(size) * size)
      fail(field + ".inverse", "expected " + std::to_string(size) + " x " + std::to_string(size));
    int zeros = 0;
    for (double a : band.inverse.values) {
      if (!std::isfinite(a)) fail(field + ".inverse", "not finite");
      zeros += a == 0;
    }
    zeros_total += zeros;
    entries_total += size * size;
    if (!full) continue;
    if (band.zeros != zeros)
      fail(field + ".zeros", "says " + std::to_string(band.zeros) + " but the inverse has " + std::to_string(zeros));
    if (!std::isfinite(band.condition)) fail(field + ".condition", "not finite");
    // Directions and inverse must still belong together (a tampered table fails here).
    const Matrix y = band_matrix(table, l);
    const double condition = condition_number(y);
    if (!(condition <= tolerance::kSingularCondition))
      fail(field, "lobe matrix Y_" + std::to_string(l) + " is near-singular (condition " + format_number(condition) +
                      ", limit " + format_number(tolerance::kSingularCondition) + ")");
    double residual = 0;
    for (int i = 0; i < size; ++i)
      for (int j = 0; j < size; ++j) {
        double dot = 0;
        for (int k = 0; k < size; ++k) dot += y(i, k) * band.inverse(k, j);
        residual = std::max(residual, std::abs(dot - (i == j ? 1.0 : 0.0)));
      }
    if (!(residual <= tolerance::kTableInverse))
      fail(field + ".inverse", "Y_" + std::to_string(l) + " * inverse differs from I by " + format_number(residual) +
                                   " (tolerance " + format_number(tolerance::kTableInverse) + "): directions and inverse disagree");
    if (!(std::abs(condition - band.condition) <= tolerance::kTableConditionRelative * condition))
      fail(field + ".condition", "says " + format_number(band.condition) + " but the lobes give " +
                                     format_number(condition));
  }
  if (!full) return;
  if (table.zeros != zeros_total) fail("zeros", "does not equal the sum over bands (" + std::to_string(zeros_total) + ")");
  if (table.entries != entries_total) fail("entries", "does not equal the sum over bands (" + std::to_string(entries_total) + ")");
  if (table.provenance.size() < 2 || table.provenance.front() != '{' || table.provenance.back() != '}')
    fail("provenance", "expected a JSON object");
}

// The empty table of an order without lobe bands (order 2).
inline LobeTable lobe_free_table(int order = 2) {
  LobeTable table;
  table.order = order;
  return table;
}

}  // namespace zhf::runtime
