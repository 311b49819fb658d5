// Lobe tables in and out of files: the one reader (JSON, "format": "zhf-lobes-1", described in
// lobe_table.h and docs/formats.md) and the one place a table's file name is made. The table type
// and its validator are in lobe_table.h, which reads nothing; io/lobe_table_writer.h writes.
#pragma once

#include <string>
#include <string_view>

#include "zhf/runtime/errors.h"
#include "zhf/runtime/json.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/lobe_table.h"
#include "zhf/runtime/read_file.h"

namespace zhf::runtime {

// Which table of an order: the sparsity search's lobes, or the lobe-parallel kernel's.
enum class TableKind { kLobes, kLanes };

// "order_N.json" or "lanes_order_N.json", in dir when dir is not empty: every table path is made
// here (order_in_file_name reads the order back).
inline std::string table_path(const std::string& dir, int order, TableKind kind = TableKind::kLobes) {
  const std::string name = std::string(kind == TableKind::kLanes ? "lanes_" : "") + "order_" + std::to_string(order) + ".json";
  if (dir.empty()) return name;
  return dir.back() == '/' ? dir + name : dir + "/" + name;
}

// The order a file name states: N for ".../order_N.json" or ".../lanes_order_N.json", else 0.
inline int order_in_file_name(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  std::string_view name(path);
  name.remove_prefix(slash == std::string::npos ? 0 : slash + 1);
  if (name.substr(0, 6) == "lanes_") name.remove_prefix(6);
  if (name.substr(0, 6) != "order_" || name.size() < 12 || name.substr(name.size() - 5) != ".json") return 0;
  const std::string_view digits = name.substr(6, name.size() - 11);
  int order = 0;
  for (char c : digits) {
    if (c < '0' || c > '9' || order > 1000) return 0;
    order = order * 10 + (c - '0');
  }
  return order;
}

// Parses and validates a table. expected_order > 0 also requires that order (a file named
// order_N.json holds order N).
inline LobeTable parse_lobe_table(std::string_view text, const std::string& source, int expected_order = 0) {
  const json::Value root = json::parse(text, source);
  const json::Field top(root, source);
  top.allow_only({"format", "order", "lobe_sharing", "lobes", "bands", "zeros", "entries", "provenance"});
  const json::Field format = top.member("format");
  if (format.string() != kLobeTableFormat)
    format.fail(std::string("expected \"") + kLobeTableFormat + "\", found \"" + excerpt(format.string()) + "\"");
  LobeTable table;
  table.order = top.member("order").integer(kMinTableOrder, kMaxTableOrder);
  if (expected_order > 0 && table.order != expected_order)
    top.member("order").fail("is " + std::to_string(table.order) + ", but order " + std::to_string(expected_order) +
                             " was expected (a file order_N.json holds order N)");
  table.lobe_sharing = top.member("lobe_sharing").boolean();
  const int lobe_total = lobe_count(table.order, table.lobe_sharing);
  for (const json::Field& lobe : top.member("lobes").items(lobe_total)) {
    lobe.allow_only({"theta", "phi", "xyz", "source"});
    TableLobe t;
    t.theta = lobe.member("theta").number();
    t.phi = lobe.member("phi").number();
    const std::vector<json::Field> xyz = lobe.member("xyz").items(3);
    for (int k = 0; k < 3; ++k) t.xyz[k] = xyz[k].number();
    t.source = lobe.member("source").string();
    table.lobes.push_back(std::move(t));
  }
  const std::vector<json::Field> bands = top.member("bands").items(std::max(0, table.order - 2));
  long long stored = 0;  // entries of the stored inverses: the bound of the zero and entry counts
  for (std::size_t b = 0; b < bands.size(); ++b) {
    const json::Field& band = bands[b];
    band.allow_only({"l", "lobes", "inverse", "zeros", "condition"});
    const int size = band_size(int(b) + 2);
    stored += static_cast<long long>(size) * size;
    TableBand t;
    t.l = band.member("l").integer(2, kMaxTableOrder - 1);
    for (const json::Field& index : band.member("lobes").items(size)) t.lobes.push_back(index.integer(0, lobe_total - 1));
    t.inverse = Matrix(size, size);
    const std::vector<json::Field> rows = band.member("inverse").items(size);
    for (int i = 0; i < size; ++i) {
      const std::vector<json::Field> row = rows[i].items(size);
      for (int j = 0; j < size; ++j) t.inverse(i, j) = row[j].number();
    }
    t.zeros = band.member("zeros").integer(0, size * size);
    t.condition = band.member("condition").number();
    table.bands.push_back(std::move(t));
  }
  table.zeros = static_cast<int>(top.member("zeros").integer(0LL, stored));
  table.entries = static_cast<int>(top.member("entries").integer(0LL, stored));
  const json::Field provenance = top.member("provenance");
  provenance.expect(json::Value::Kind::kObject);
  table.provenance = json::compact_text(provenance.value());
  validate_lobe_table(table, source);
  return table;
}

// Reads, parses and validates the table at path (at most kMaxTableBytes); a file named
// order_N.json must hold order N.
inline LobeTable read_lobe_table(const std::string& path, int expected_order = 0) {
  const int named = order_in_file_name(path);
  if (expected_order > 0 && named > 0 && named != expected_order)
    throw InputError(path + ": the file name says order " + std::to_string(named) + ", order " +
                     std::to_string(expected_order) + " was asked for");
  return parse_lobe_table(read_file(path, kMaxTableBytes), path, expected_order > 0 ? expected_order : named);
}

// The command recorded in a table's provenance, or "".
inline std::string provenance_command(const LobeTable& table) {
  const json::Value provenance = json::parse(table.provenance, "provenance");
  const json::Value* command = provenance.find("command");
  return command && command->kind == json::Value::Kind::kString ? command->text : std::string();
}

}  // namespace zhf::runtime
