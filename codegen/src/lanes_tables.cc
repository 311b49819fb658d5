#include "zhf/codegen/lanes_tables.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "c_family_printer.h"
#include "zhf/codegen/float_model.h"
#include "zhf/optimizer/conditioned.h"

namespace zhf::codegen {

double lanes_float_error_model(const optimizer::LobeTable& table) {
  double worst = 0;
  for (const optimizer::TableBand& band : table.bands)
    worst = std::max(worst, optimizer::band_amplification(table.band_matrix(band.l)));
  return kFloatEpsilon * (table.order - 1) * worst;
}

LanesStage lanes_stage(const optimizer::LobeTable& table) {
  const double model = lanes_float_error_model(table);
  if (kLanesFloatMargin * model <= kFloatRotationTarget) return LanesStage::kFloat;
  if (kLanesLobesInDoubleMargin * model <= kFloatRotationTarget) return LanesStage::kLobesInDouble;
  return LanesStage::kDouble;
}

EmittedFile emit_lanes_tables(const optimizer::LobeTable& table, const std::string& command,
                              const std::string& table_path) {
  const int n = table.order;
  const int lobes = 2 * n - 1;
  const std::string suffix = "Order" + std::to_string(n);
  auto number = [](double v) { return format_literal(v, LanguageConfig{}, Precision::kDouble); };
  std::ostringstream out;
  out << banner("//", command, {}) << "//   (none: constants only, read by runtime/lanes.h)\n";
  out << "#pragma once\n\nnamespace zhf::gen {\n\n";
  out << "// Lobe directions w_d for the lobe-parallel rotation (runtime/lanes.h) at order " << n << ", from\n";
  out << "// " << table_path << ";\n";
  if (table.provenance.contains("command"))
    out << "// made by: " << table.provenance["command"].get<std::string>() << "\n";
  out << "// Continuous directions (not SH zeros) minimising the float error amplification\n";
  out << "// a_l = sqrt((2l+1)/4pi) ||A_l||_2 with lobe sharing (band l uses lobes 0..2l). a_l per band:";
  for (const optimizer::TableBand& band : table.bands) {
    char text[16];
    std::snprintf(text, sizeof text, " %.3f", optimizer::band_amplification(table.band_matrix(band.l)));
    out << text;
  }
  const LanesStage stage = lanes_stage(table);
  const char* kStageText[] = {"everything in float",
                              "lobes rotated in double, SH evaluation and sums in float",
                              "R projected and the whole lobe stage in double"};
  char model[512];
  std::snprintf(model, sizeof model,
                ".\n// Float error model eps_f (N - 1) a_max = %.2g; with margins %.2g (all float) and %.3g (lobes\n"
                "// in double) against the 1e-6 target: %s.\n",
                lanes_float_error_model(table), kLanesFloatMargin, kLanesLobesInDoubleMargin,
                kStageText[static_cast<int>(stage)]);
  out << model;
  out << "inline constexpr int kLanesStage" << suffix << " = " << static_cast<int>(stage)
      << ";  // 0 float, 1 lobes in double, 2 double\n";
  out << "inline constexpr double kLanesLobes" << suffix << "[" << lobes << "][3] = {\n";
  for (int d = 0; d < lobes; ++d) {
    const auto& w = table.lobes[d].xyz;
    out << "    {" << number(w[0]) << ", " << number(w[1]) << ", " << number(w[2]) << "}" << (d + 1 < lobes ? "," : "")
        << "  // w_" << d << "\n";
  }
  out << "};\n\n";
  out << "// kLanesInverse" << suffix << "[l - 2][m + l][d] = A_l = Y_l^-1, Y_l[d][m + l] = y_l^m(w_d), dense (no\n";
  out << "// structural zeros); zero beyond 2l + 1 rows and columns. Double, from the table's inverse.\n";
  out << "inline constexpr double kLanesInverse" << suffix << "[" << n - 2 << "][" << lobes << "][" << lobes << "] = {\n";
  for (const optimizer::TableBand& band : table.bands) {
    out << "    {  // l = " << band.l << "\n";
    for (int row = 0; row < lobes; ++row) {
      out << "        {";
      for (int d = 0; d < lobes; ++d) {
        const bool inside = row < band.inverse.rows() && d < band.inverse.cols();
        out << (d ? ", " : "") << (inside ? number(band.inverse(row, d)) : "0.0");
      }
      out << "}" << (row + 1 < lobes ? "," : "") << "\n";
    }
    out << "    }" << (band.l + 1 < n ? "," : "") << "\n";
  }
  out << "};\n\n}  // namespace zhf::gen\n";
  return {"zhf_lanes_order" + std::to_string(n) + ".h", out.str(), {}};
}

}  // namespace zhf::codegen
