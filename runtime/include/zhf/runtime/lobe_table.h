// Lobe tables read at run time (zhf-lobes-1 JSON, as written by `zhf optimize`).
#pragma once

#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "zhf/runtime/json_lite.h"
#include "zhf/runtime/sh_band.h"

namespace zhf::runtime {

inline constexpr int kMaxTableOrder = 32;

struct RuntimeBand {
  int l = 0;
  std::vector<int> lobes;       // positions in LobeTableData::lobes
  std::vector<double> inverse;  // A_l row-major: [(m + l) * (2l+1) + d]
};

struct LobeTableData {
  int order = 0;
  std::vector<std::array<double, 3>> lobes;
  std::vector<RuntimeBand> bands;  // l = 2..order-1
};

// Parses and checks a table; throws std::runtime_error "<name>: <field>: <problem>".
inline LobeTableData parse_lobe_table(const std::string& text, const std::string& name) {
  auto fail = [&](const std::string& field, const std::string& what) -> void {
    throw std::runtime_error(name + ": " + field + ": " + what);
  };
  json::Value root;
  try {
    root = json::parse(text);
  } catch (const std::exception& e) {
    throw std::runtime_error(name + ": " + e.what());
  }
  using Kind = json::Value::Kind;
  auto member = [&](const json::Value& v, const std::string& key, Kind kind, const std::string& field) -> const json::Value& {
    if (v.kind != Kind::kObject) fail(field, "expected an object");
    auto it = v.object.find(key);
    if (it == v.object.end()) fail(field + "." + key, "missing");
    if (it->second.kind != kind) fail(field + "." + key, "wrong type");
    return it->second;
  };
  // Integers arrive as doubles; anything non-integral or out of int range is rejected before
  // a cast could overflow.
  auto integer = [&](const json::Value& v, const std::string& field) -> int {
    if (v.kind != Kind::kNumber || !v.integral || !(std::abs(v.number) <= 1e9)) fail(field, "expected an integer");
    return static_cast<int>(v.number);
  };
  if (member(root, "format", Kind::kString, "table").string != "zhf-lobes-1")
    fail("format", "expected \"zhf-lobes-1\"");
  LobeTableData table;
  table.order = integer(member(root, "order", Kind::kNumber, "table"), "order");
  if (table.order < 2 || table.order > kMaxTableOrder)
    fail("order", "must be an integer in [2, " + std::to_string(kMaxTableOrder) + "]");
  for (const json::Value& lobe : member(root, "lobes", Kind::kArray, "table").array) {
    const json::Value& xyz = member(lobe, "xyz", Kind::kArray, "lobes[" + std::to_string(table.lobes.size()) + "]");
    if (xyz.array.size() != 3) fail("lobes[" + std::to_string(table.lobes.size()) + "].xyz", "expected 3 numbers");
    std::array<double, 3> w{};
    for (int k = 0; k < 3; ++k) {
      if (xyz.array[k].kind != Kind::kNumber) fail("lobes[" + std::to_string(table.lobes.size()) + "].xyz", "expected numbers");
      w[k] = xyz.array[k].number;
    }
    if (std::abs(w[0] * w[0] + w[1] * w[1] + w[2] * w[2] - 1) > 1e-12)
      fail("lobes[" + std::to_string(table.lobes.size()) + "].xyz", "not a unit vector");
    table.lobes.push_back(w);
  }
  const json::Value& bands = member(root, "bands", Kind::kArray, "table");
  if (static_cast<int>(bands.array.size()) != table.order - 2)
    fail("bands", "expected " + std::to_string(table.order - 2) + " bands");
  for (size_t b = 0; b < bands.array.size(); ++b) {
    const std::string field = "bands[" + std::to_string(b) + "]";
    RuntimeBand band;
    band.l = static_cast<int>(b) + 2;
    const int size = 2 * band.l + 1;
    for (const json::Value& i : member(bands.array[b], "lobes", Kind::kArray, field).array) {
      const int index = integer(i, field + ".lobes");
      if (index < 0 || index >= static_cast<int>(table.lobes.size())) fail(field + ".lobes", "index out of range");
      band.lobes.push_back(index);
    }
    if (static_cast<int>(band.lobes.size()) != size) fail(field + ".lobes", "expected " + std::to_string(size));
    const json::Value& rows = member(bands.array[b], "inverse", Kind::kArray, field);
    if (static_cast<int>(rows.array.size()) != size) fail(field + ".inverse", "expected " + std::to_string(size) + " rows");
    for (const json::Value& row : rows.array) {
      if (static_cast<int>(row.array.size()) != size) fail(field + ".inverse", "row of wrong length");
      for (const json::Value& x : row.array) {
        if (x.kind != Kind::kNumber) fail(field + ".inverse", "expected numbers");
        band.inverse.push_back(x.number);
      }
    }
    // Y_l A_l = I: the inverse must still belong to the directions.
    const BandEvaluator<double> eval(band.l);
    std::vector<double> y(size * size), row(size);
    for (int d = 0; d < size; ++d) {
      eval(table.lobes[band.lobes[d]].data(), row.data());
      for (int k = 0; k < size; ++k) y[d * size + k] = row[k];
    }
    for (int i = 0; i < size; ++i)
      for (int j = 0; j < size; ++j) {
        double dot = 0;
        for (int k = 0; k < size; ++k) dot += y[i * size + k] * band.inverse[k * size + j];
        if (std::abs(dot - (i == j ? 1.0 : 0.0)) > 1e-10) fail(field + ".inverse", "Y_l * inverse is not I: tampered table");
      }
    table.bands.push_back(std::move(band));
  }
  return table;
}

inline LobeTableData read_lobe_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_lobe_table(text.str(), path);
}

}  // namespace zhf::runtime
