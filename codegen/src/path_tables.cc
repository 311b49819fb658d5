#include "zhf/codegen/path_tables.h"

#include <algorithm>
#include <filesystem>
#include <system_error>

#include "zhf/codegen/limits.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/runtime/band_rows.h"
#include "zhf/runtime/enum_names.h"
#include "zhf/runtime/errors.h"
#include "zhf/io/json.h"

namespace zhf::codegen {
namespace {

namespace fs = std::filesystem;
using io::json::Field;

constexpr runtime::EnumName<RotationPath> kPathNames[] = {{RotationPath::kScalar, "scalar"},
                                                           {RotationPath::kLanes, "lanes"},
                                                           {RotationPath::kBandRows, "band_rows"},
                                                           {RotationPath::kBands01, "bands01"}};

RotationPath parse_path(const Field& f) {
  RotationPath path = RotationPath::kScalar;
  runtime::parse_enum(kPathNames, f.one_of(runtime::enum_names(kPathNames)), path);
  return path;
}

// Whether a build for isa can have path p for order in the type named (lanes: where the tree has
// lanes tables, which every order with lobes may).
bool path_exists(RotationPath p, const std::string& isa, bool is_float, int order) {
  const bool avx2 = isa == "avx2" || isa == "avx512";
  switch (p) {
    case RotationPath::kScalar: return true;
    case RotationPath::kLanes: return order > runtime::kMinTableOrder;
    case RotationPath::kBandRows:
      return avx2 && is_float && order >= runtime::kBandRowsMinOrder && order <= runtime::kBandRowsMaxOrder;
    case RotationPath::kBands01: return avx2 && is_float && order == 2;
  }
  return false;
}

PathTimes parse_times(const Field& f, const std::string& isa, bool is_float, int order) {
  f.allow_only({"fastest", "ns"});
  PathTimes times;
  const Field fastest = f.member("fastest");
  times.fastest = parse_path(fastest);
  if (!path_exists(times.fastest, isa, is_float, order))
    fastest.fail(std::string(rotation_path_name(times.fastest)) + " does not exist for " + isa + ", " +
                 (is_float ? "float" : "double") + ", order " + std::to_string(order));
  const Field ns = f.member("ns");
  ns.expect(io::json::Kind::kObject);
  for (const auto& [p, name] : kPathNames)
    if (const auto t = ns.find(name)) {
      if (!path_exists(p, isa, is_float, order)) t->fail("a path that does not exist here");
      const double ns_per_rotation = t->number();
      if (!(ns_per_rotation > 0)) t->fail("must be above 0");
      times.ns.emplace_back(p, ns_per_rotation);
    }
  ns.allow_only({"scalar", "lanes", "band_rows", "bands01"});
  const bool timed = std::any_of(times.ns.begin(), times.ns.end(), [&](const auto& t) { return t.first == times.fastest; });
  if (!timed) ns.fail("has no time for the fastest path");
  return times;
}

PathTable read_table(const std::string& file, const std::string& isa) {
  const io::json::Json root = io::json::read_file(file, codegen::kMaxPathTableBytes);
  const Field top(root, file);
  top.allow_only({"format", "isa", "measured_on", "orders"});
  const Field format = top.member("format");
  if (format.string() != "zhf-paths-1") format.fail("'" + io::excerpt(format.string()) + "' is not zhf-paths-1");
  const Field isa_field = top.member("isa");
  if (isa_field.string() != isa) isa_field.fail("'" + io::excerpt(isa_field.string()) + "' in " + isa + ".json");
  PathTable table;
  table.isa = isa;
  table.file = file;
  const Field measured = top.member("measured_on");
  table.measured_on = measured.string();
  if (table.measured_on.empty() || table.measured_on.size() > codegen::kMaxPathTableNoteChars || !runtime::is_printable_text(table.measured_on))
    measured.fail("must be 1 to " + std::to_string(codegen::kMaxPathTableNoteChars) + " printable characters");
  constexpr int kOrders = runtime::kMaxGeneratedOrder - runtime::kMinGeneratedOrder + 1;
  for (const Field& entry : top.member("orders").items(1, kOrders)) {
    entry.allow_only({"order", "float", "double"});
    OrderPaths o;
    const Field order = entry.member("order");
    o.order = order.integer(runtime::kMinGeneratedOrder, runtime::kMaxGeneratedOrder);
    for (const OrderPaths& before : table.orders)
      if (before.order == o.order) order.fail("listed twice");
    o.float_paths = parse_times(entry.member("float"), isa, true, o.order);
    o.double_paths = parse_times(entry.member("double"), isa, false, o.order);
    table.orders.push_back(o);
  }
  std::sort(table.orders.begin(), table.orders.end(), [](const OrderPaths& a, const OrderPaths& b) { return a.order < b.order; });
  return table;
}

}  // namespace

const char* rotation_path_name(RotationPath path) { return runtime::enum_name(kPathNames, path); }

const std::vector<std::string>& path_table_isas() {
  static const std::vector<std::string> isas = {"avx512", "avx2", "sse2", "neon"};
  return isas;
}

std::vector<PathTable> read_path_tables(const std::string& dir) {
  std::vector<PathTable> tables;
  if (dir.empty()) return tables;
  for (const std::string& isa : path_table_isas()) {
    const fs::path file = fs::path(dir) / (isa + ".json");
    std::error_code ec;
    if (fs::exists(file, ec)) tables.push_back(read_table(file.string(), isa));
  }
  return tables;
}

RotationPath fastest_available(const PathTimes& times, bool has_lanes) {
  if (times.fastest != RotationPath::kLanes || has_lanes) return times.fastest;
  RotationPath best = RotationPath::kScalar;
  double best_ns = 0;
  for (const auto& [path, ns] : times.ns)
    if ((path != RotationPath::kLanes || has_lanes) && (best_ns == 0 || ns < best_ns)) {
      best = path;
      best_ns = ns;
    }
  return best;
}

}  // namespace zhf::codegen
