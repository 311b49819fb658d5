#include "zhf/io/lobe_table_writer.h"

#include "zhf/io/files.h"
#include "zhf/io/json.h"

namespace zhf::io {

nlohmann::ordered_json lobe_table_json(const runtime::LobeTable& table) {
  nlohmann::ordered_json out;
  out["format"] = runtime::kLobeTableFormat;
  out["order"] = table.order;
  out["lobe_sharing"] = table.lobe_sharing;
  nlohmann::ordered_json lobes = nlohmann::ordered_json::array();
  for (const runtime::TableLobe& lobe : table.lobes) {
    lobes.push_back({{"theta", lobe.theta},
                     {"phi", lobe.phi},
                     {"xyz", {lobe.xyz[0], lobe.xyz[1], lobe.xyz[2]}},
                     {"source", lobe.source}});
  }
  out["lobes"] = lobes;
  nlohmann::ordered_json bands = nlohmann::ordered_json::array();
  for (const runtime::TableBand& band : table.bands) {
    nlohmann::ordered_json inverse = nlohmann::ordered_json::array();
    for (int i = 0; i < band.inverse.rows; ++i) {
      nlohmann::ordered_json row = nlohmann::ordered_json::array();
      for (int j = 0; j < band.inverse.cols; ++j) {
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
  // Keys sorted (nlohmann::json's object order), so a table's bytes do not depend on who built it.
  const nlohmann::json sorted = json::parse(table.provenance, "provenance");
  out["provenance"] = nlohmann::ordered_json(sorted);
  return out;
}

std::string lobe_table_text(const runtime::LobeTable& table, const std::string& source) {
  runtime::validate_lobe_table(table, source);
  return json_text(lobe_table_json(table));
}

}  // namespace zhf::io
