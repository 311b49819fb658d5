// The suite's report: its JSON (zhf-bench-1), read back for --from, and its table.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <tuple>

#include "zhf/bench/suite.h"
#include "zhf/io/files.h"
#include "zhf/io/json.h"
#include "zhf/bench/limits.h"
#include "zhf/runtime/limits.h"

namespace zhf::bench {

nlohmann::ordered_json SuiteReport::to_json() const {
  nlohmann::ordered_json j;
  j["format"] = "zhf-bench-1";
  j["cpu"] = cpu;
  j["compiler"] = compiler;
  j["flags"] = flags;
  j["date"] = date;
  j["notes"] = notes;
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const Row& r : rows) {
    nlohmann::ordered_json x = {{"method", r.method},   {"scenario", r.scenario}, {"precision", r.precision},
                                {"variant", r.variant}, {"order", r.order},       {"ns_median", r.ns_median},
                                {"ns_min", r.ns_min},   {"ns_max", r.ns_max}};
    // What was not measured (a conversion alone has no error) is left out.
    if (std::isfinite(r.max_error)) x["max_error"] = r.max_error;
    if (std::isfinite(r.rms_error)) x["rms_error"] = r.rms_error;
    if (std::isfinite(r.worst_unit_error)) x["worst_unit_error"] = r.worst_unit_error;
    if (r.multiplies >= 0) x["multiplies"] = r.multiplies, x["adds"] = r.adds;
    list.push_back(x);
  }
  j["rows"] = list;
  return j;
}

SuiteReport read_report(const std::string& path) {
  const io::json::Json root = io::json::read_file(path, kMaxReportBytes);
  const io::json::Field top(root, path);
  if (top.member("format").string() != "zhf-bench-1") top.member("format").fail("expected \"zhf-bench-1\"");
  SuiteReport report;
  report.cpu = top.member("cpu").string();
  report.compiler = top.member("compiler").string();
  report.flags = top.member("flags").string();
  report.date = top.member("date").string();
  for (const io::json::Field& note : top.member("notes").items(0, kMaxReportNotes)) report.notes.push_back(note.string());
  for (const io::json::Field& row : top.member("rows").items(0, kMaxReportRows)) {
    Row r;
    r.method = row.member("method").string();
    r.scenario = row.member("scenario").string();
    r.precision = row.member("precision").string();
    r.variant = row.member("variant").string();
    r.order = row.member("order").integer(1, runtime::kMaxShOrder);
    r.ns_median = row.member("ns_median").number(0, 1e300);
    r.ns_min = row.member("ns_min").number(0, 1e300);
    r.ns_max = row.member("ns_max").number(0, 1e300);
    const auto optional = [&](const char* name) { return row.find(name) ? row.member(name).number() : NAN; };
    r.max_error = optional("max_error");
    r.rms_error = optional("rms_error");
    r.worst_unit_error = optional("worst_unit_error");
    if (row.find("multiplies")) {
      r.multiplies = row.member("multiplies").integer(0LL, kMaxReportOps);
      r.adds = row.member("adds").integer(0LL, kMaxReportOps);
    }
    report.rows.push_back(std::move(r));
  }
  return report;
}

std::string SuiteReport::table() const {
  std::ostringstream out;
  char line[300];
  std::snprintf(line, sizeof line, "%-7s %5s  %-20s %-6s %-36s %10s %21s %10s %10s %10s %13s\n", "scenario", "order",
                "method", "prec", "variant", "ns/vector", "[min, max]", "max err", "RMS err", "worst unit", "mults/adds");
  out << line;
  std::vector<Row> sorted = rows;
  std::stable_sort(sorted.begin(), sorted.end(), [](const Row& a, const Row& b) {
    return std::tie(a.scenario, a.order) < std::tie(b.scenario, b.order);
  });
  for (const Row& r : sorted) {
    const std::string ops = r.multiplies >= 0 ? std::to_string(r.multiplies) + "/" + std::to_string(r.adds) : "-";
    char range[64];
    std::snprintf(range, sizeof range, "[%.1f, %.1f]", r.ns_min, r.ns_max);
    char worst[16] = "-";
    if (!std::isnan(r.worst_unit_error)) std::snprintf(worst, sizeof worst, "%.2e", r.worst_unit_error);
    std::snprintf(line, sizeof line, "%-8s %5d  %-20s %-6s %-36s %10.1f %21s %10.2e %10.2e %10s %13s\n",
                  r.scenario.c_str(), r.order, r.method.c_str(), r.precision.c_str(), r.variant.c_str(), r.ns_median,
                  range, r.max_error, r.rms_error, worst, ops.c_str());
    out << line;
  }
  // Per scenario and order: the fastest float method, and its lead over the next method.
  out << "\nfastest per scenario and order (float methods; ratio = runner-up time / winner time):\n";
  std::map<std::pair<std::string, int>, std::vector<const Row*>> groups;
  for (const Row& r : rows)
    if (r.precision == "float" && r.variant.rfind("pruned", 0) != 0 && r.variant != kAllFloatVariant) groups[{r.scenario, r.order}].push_back(&r);
  for (auto& [key, group] : groups) {
    std::sort(group.begin(), group.end(), [](const Row* a, const Row* b) { return a->ns_median < b->ns_median; });
    const Row* best = group.front();
    const Row* next = nullptr;
    for (const Row* r : group)
      if (r->method != best->method) {
        next = r;
        break;
      }
    std::snprintf(line, sizeof line, "  %-7s N=%-2d %s%s%s %.1f ns", key.first.c_str(), key.second, best->method.c_str(),
                  best->variant.empty() ? "" : " (", best->variant.empty() ? "" : (best->variant + ")").c_str(), best->ns_median);
    out << line;
    if (next) {
      std::snprintf(line, sizeof line, ", %.2fx ahead of %s%s", next->ns_median / best->ns_median, next->method.c_str(),
                    next->variant.empty() ? "" : (" (" + next->variant + ")").c_str());
      out << line;
    }
    out << "\n";
  }
  for (const std::string& n : notes) out << "note: " << n << "\n";
  return out.str();
}

}  // namespace zhf::bench
