#include "c_family_printer.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "zhf/runtime/table_io.h"
#include "zhf/runtime/tolerances.h"

namespace zhf::codegen {
namespace {

// Bytes of each plane per tile of the batch loop: two cache lines, whose sequential reads keep the
// prefetcher ahead when all planes share one cache set (one line per tile left the batch 3x
// slower at order 3 on planes 4096 floats apart); at order 8, 17.5 KiB of local blocks.
constexpr int kBatchTileBytes = 128;

std::string shortest(double value, Precision precision) {
  char buffer[64];
  if (precision == Precision::kFloat) {
    const float f = static_cast<float>(value);
    for (int digits = 1; digits <= 9; ++digits) {
      std::snprintf(buffer, sizeof buffer, "%.*g", digits, static_cast<double>(f));
      if (std::strtof(buffer, nullptr) == f) break;
    }
  } else {
    for (int digits = 1; digits <= 17; ++digits) {
      std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
      if (std::strtod(buffer, nullptr) == value) break;
    }
  }
  std::string text = buffer;
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

class Printer {
 public:
  Printer(const Function& f, const LanguageConfig& c, Precision p) : f_(f), c_(c), wide_(widened(c)), p_(p) {}

  std::string print(OpCount& ops) {
    std::ostringstream out;
    out << "// " << f_.name << ": " << f_.doc << ".\n";
    out << c_.function_prefix << (c_.wgsl ? "fn " : "void ") << f_.name << "(" << signature() << ") {\n";
    std::string indent = "  ";
    const std::vector<int> outputs = f_.output_nodes();
    const std::vector<int> live = f_.graph.live(outputs);
    if (!c_.wide_declaration.empty())
      for (int i : live)
        if (f_.graph.node(i).wide) {
          out << indent << c_.wide_declaration << "\n";
          break;
        }
    if (f_.batch) {
      open_tiles(out);
      indent = "      ";
    }
    for (int i : live) {
      const Node& n = f_.graph.node(i);
      if (n.op == Op::kInput || n.op == Op::kConst) continue;
      const int lanes = scalarized(n) ? n.lanes : 1;
      for (int lane = 0; lane < lanes; ++lane) {
        const std::string name = temp(i, scalarized(n) ? lane : -1);
        if (c_.wgsl) out << indent << "let " << name << ": " << type_of(n, n.wide) << " = ";
        else out << indent << c_.temp_qualifier << type_of(n, n.wide) << " " << name << " = ";
        out << expression(n, scalarized(n) ? lane : -1) << ";\n";
        if (n.op == Op::kMul) ++ops.multiplies;
        else if (n.op == Op::kRsqrt || n.op == Op::kSelect) ++ops.others;
        else ++ops.adds;
      }
    }
    for (const Output& o : f_.outputs) {
      const Node& n = f_.graph.node(o.node);
      const Param& param = f_.params[o.param];
      if (param.channels > 1 && c_.planar_channels) {
        for (int lane = 0; lane < param.channels; ++lane)
          out << indent << access(o.param, o.element, lane) << " = " << operand(o.node, n.lanes > 1 ? lane : -1, false) << ";\n";
      } else {
        out << indent << access(o.param, o.element, -1) << " = " << operand(o.node, -1, false) << ";\n";
      }
    }
    if (f_.batch) close_tiles(out);
    out << "}\n";
    return out.str();
  }

 private:
  bool scalarized(const Node& n) const { return n.lanes > 1 && c_.vector_stem.empty(); }
  // The type of a value of n's lanes computed wide or not.
  std::string type_of(const Node& n, bool wide) const {
    const LanguageConfig& c = wide ? wide_ : c_;
    return n.lanes > 1 && !c.vector_stem.empty() ? vector_type_name(c, n.lanes) : c.scalar;
  }
  static std::string temp(int i, int lane) {
    return "t" + std::to_string(i) + (lane < 0 ? "" : std::string("_") + "rgba"[lane]);
  }

  std::string signature() const { return print_parameters(f_, c_); }

  // The batch loop runs tile by tile: each input plane's part is first copied into a local block
  // and the outputs are copied out of one, so the 3 + 2 N^2 streams never compete for a cache set
  // (planes a power of two apart all map to the same sets: up to 8x slower), and the loop over a
  // tile, on local arrays of fixed shape, can run across SIMD lanes. Every loop has a constant
  // trip count, so the copies stay inline: the last tile ends at count, redoing vectors of the
  // tile before it, and a batch shorter than a tile runs as one tile padded with zeros.
  void open_tiles(std::ostream& out) const {
    const std::string& T = c_.scalar;
    out << "  constexpr std::size_t kTile = sizeof(" << T << ") <= 8 ? " << kBatchTileBytes << " / sizeof(" << T << ") : 16;\n"
        << "  if (count < kTile) {\n";
    for (const Param& p : f_.params)
      out << "    " << T << " " << p.name << "_padded[" << p.size << " * kTile]" << (p.output ? "" : " = {}") << ";\n";
    for (const Param& p : f_.params)
      if (!p.output) out << copy_planes(p.size, p.name + "_padded[k * kTile + v]", p.name + "[k * count + v]", "count");
    out << "    " << f_.name << "(kTile";
    for (const Param& p : f_.params) out << ", " << p.name << "_padded";
    out << ");\n";
    for (const Param& p : f_.params)
      if (p.output) out << copy_planes(p.size, p.name + "[k * count + v]", p.name + "_padded[k * kTile + v]", "count");
    out << "    return;\n"
        << "  }\n"
        << "  for (std::size_t first = 0; first < count; first += kTile) {\n"
        << "    const std::size_t start = first + kTile <= count ? first : count - kTile;\n";
    for (const Param& p : f_.params) out << "    " << T << " " << p.name << "_tile[" << p.size << "][kTile];\n";
    for (const Param& p : f_.params)
      if (!p.output) out << copy_planes(p.size, p.name + "_tile[k][v]", p.name + "[k * count + start + v]", "kTile");
    out << "    for (std::size_t v = 0; v < kTile; ++v) {\n";
  }
  void close_tiles(std::ostream& out) const {
    out << "    }\n";
    for (const Param& p : f_.params)
      if (p.output) out << copy_planes(p.size, p.name + "[k * count + start + v]", p.name + "_tile[k][v]", "kTile");
    out << "  }\n";
  }
  static std::string copy_planes(int planes, const std::string& to, const std::string& from, const std::string& values) {
    return "    for (std::size_t k = 0; k < " + std::to_string(planes) + "; ++k)\n      for (std::size_t v = 0; v < " + values +
           "; ++v) " + to + " = " + from + ";\n";
  }

  std::string access(int param, int element, int lane) const {
    const Param& p = f_.params[param];
    if (f_.batch) return p.name + "_tile[" + std::to_string(element) + "][v]";
    if (c_.wgsl && p.output) return "(*" + p.name + ")[" + std::to_string(element) + "]";
    if (p.channels > 1 && c_.planar_channels) return p.name + "[" + std::to_string(lane) + "][" + std::to_string(element) + "]";
    return p.name + "[" + std::to_string(element) + "]";
  }

  // Node i as an operand of a computation (or a store, wide = false) of the given width:
  // converted when the widths differ and the language's types do.
  std::string operand(int i, int lane, bool wide) const {
    const Node& n = f_.graph.node(i);
    if (n.op == Op::kConst) return format_literal(n.value, wide ? wide_ : c_, wide ? Precision::kDouble : p_);
    const std::string text =
        n.op == Op::kInput ? access(n.param, n.element, n.lanes > 1 ? lane : -1) : temp(i, scalarized(n) ? lane : -1);
    const bool input_wide = n.op == Op::kInput ? false : n.wide;
    if (input_wide == wide || wide_.scalar == c_.scalar) return text;
    Node value = n;
    if (scalarized(n)) value.lanes = 1;
    return type_of(value, wide) + "(" + text + ")";
  }

  std::string expression(const Node& n, int lane) const {
    switch (n.op) {
      case Op::kAdd: return operand(n.a, lane, n.wide) + " + " + operand(n.b, lane, n.wide);
      case Op::kSub: return operand(n.a, lane, n.wide) + " - " + operand(n.b, lane, n.wide);
      case Op::kMul: return operand(n.a, lane, n.wide) + " * " + operand(n.b, lane, n.wide);
      case Op::kNeg: return "-" + operand(n.a, lane, n.wide);
      case Op::kRsqrt: return c_.reciprocal_sqrt + "(" + operand(n.a, lane, n.wide) + ")";
      case Op::kSelect:
        if (c_.wgsl)
          return "select(" + operand(n.c, lane, n.wide) + ", " + operand(n.b, lane, n.wide) + ", " + operand(n.a, -1, n.wide) +
                 " > " + format_literal(0.0, n.wide ? wide_ : c_, n.wide ? Precision::kDouble : p_) + ")";
        if (!c_.select_positive.empty())
          return c_.select_positive + "(" + operand(n.a, -1, n.wide) + ", " + operand(n.b, lane, n.wide) + ", " +
                 operand(n.c, lane, n.wide) + ")";
        return operand(n.a, -1, n.wide) + " > " + format_literal(0.0, n.wide ? wide_ : c_, n.wide ? Precision::kDouble : p_) +
               " ? " + operand(n.b, lane, n.wide) + " : " + operand(n.c, lane, n.wide);
      default: return "";
    }
  }

  const Function& f_;
  const LanguageConfig& c_;
  const LanguageConfig wide_;
  Precision p_;
};

}  // namespace

std::string print_parameters(const Function& function, const LanguageConfig& c) {
  std::string s;
  if (function.batch) s += "std::size_t count, ";
  for (size_t k = 0; k < function.params.size(); ++k) {
    const Param& p = function.params[k];
    if (k) s += ", ";
    if (function.batch) {
      // Distinct arrays: without the promise the compiler cannot run the loop across SIMD lanes
      // (it would need an overlap check for every pair of the 3 + 2 N^2 streams).
      s += (p.output ? "" : "const ") + c.scalar + "* __restrict " + p.name;
      continue;
    }
    if (c.wgsl) {
      const std::string array = "array<" + (p.channels > 1 ? vector_type_name(c, p.channels) : c.scalar) + ", " + std::to_string(p.size) + ">";
      s += p.name + ": " + (p.output ? "ptr<function, " + array + ">" : array);
      continue;
    }
    s += p.output ? c.output_array_qualifier : c.input_array_qualifier;
    if (p.channels > 1 && !c.vector_stem.empty()) {
      s += c.vector_stem + std::to_string(p.channels) + " " + p.name + "[" + std::to_string(p.size) + "]";
    } else if (p.channels > 1) {
      s += c.scalar + " " + p.name + "[" + std::to_string(p.channels) + "][" + std::to_string(p.size) + "]";
    } else {
      s += c.scalar + " " + p.name + "[" + std::to_string(p.size) + "]";
    }
  }
  return s;
}

std::string vector_type_name(const LanguageConfig& config, int lanes) {
  return config.wgsl ? config.vector_stem + std::to_string(lanes) + "<" + config.scalar + ">" : config.vector_stem + std::to_string(lanes);
}

std::string print_arguments(const Function& function) {
  std::string s = function.batch ? "count" : "";
  for (const Param& p : function.params) s += (s.empty() ? "" : ", ") + p.name;
  return s;
}

std::string print_functions(const Module& module, const LanguageConfig& config, Precision precision,
                            std::vector<EmittedFunction>& functions) {
  std::string body;
  for (const Function& f : module.functions) {
    if (f.batch && !config.batch) continue;
    EmittedFunction emitted{f.name, f.kind, f.channels, {}};
    body += "\n" + print_function(f, config, precision, emitted.ops);
    functions.push_back(emitted);
  }
  return body;
}

std::string comment_text(const std::string& text) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out;
  for (char ch : text) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c < 0x7f && c != '\\' && c != '%') {
      out += ch;
    } else {
      out += '%';
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  return out;
}

std::string commented(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& line : lines) out += "// " + comment_text(line) + "\n";
  return out;
}

std::string lobe_values(const Module& module, const LanguageConfig& config, Precision precision,
                        const std::string& row_open, const std::string& row_close) {
  std::string out;
  for (size_t d = 0; d < module.lobes.size(); ++d) {
    out += "    " + row_open;
    for (int k = 0; k < 3; ++k) out += (k ? ", " : "") + format_literal(module.lobes[d].unit[k], config, precision);
    out += row_close + (d + 1 < module.lobes.size() ? "," : "") + "  // w_" + std::to_string(d) + "\n";
  }
  return out;
}

std::string format_literal(double value, const LanguageConfig& config, Precision precision) {
  if (config.wrap_literals_in_type) return config.scalar + "(" + shortest(value, Precision::kDouble) + ")";
  return shortest(value, precision) + config.literal_suffix;
}

LanguageConfig widened(const LanguageConfig& config) {
  LanguageConfig wide = config;
  if (config.wide_scalar.empty()) return wide;
  wide.scalar = config.wide_scalar;
  wide.vector_stem = config.vector_stem.empty() ? "" : config.wide_vector_stem;
  wide.literal_suffix = config.wide_literal_suffix;
  return wide;
}

std::string print_function(const Function& function, const LanguageConfig& config, Precision precision,
                           OpCount& ops) {
  ops = OpCount{};
  return Printer(function, config, precision).print(ops);
}

std::string banner(const std::string& command, const std::vector<EmittedFunction>& functions) {
  std::ostringstream out;
  out << "// Generated by zhf " << ZHF_VERSION << ": " << comment_text(command) << "\n";
  out << "// Do not edit: change the generator or the lobe table and run `zhf generate`.\n";
  out << "// Operations per call (multiplies, adds; a vector operation counts once):\n";
  for (const EmittedFunction& f : functions)
    out << "//   " << f.name << ": " << f.ops.multiplies << " multiplies, " << f.ops.adds << " adds"
        << (f.ops.others ? ", " + std::to_string(f.ops.others) + " square roots and selections" : "") << "\n";
  return out.str();
}

std::vector<std::string> lobe_derivation(const Module& module, const EmitOptions& options, runtime::LobeStage stage) {
  std::vector<std::string> lines;
  if (module.lobes.empty()) {
    lines.push_back("Order " + std::to_string(module.order) + " has no lobe bands: band 0 is copied, band 1 rotates as a 3-vector.");
    return lines;
  }
  lines.push_back("Lobe directions w_d (unit vectors) for order " + std::to_string(module.order) + ", from " +
                  options.table_path + ";");
  if (const std::string command = runtime::provenance_command(module.table); !command.empty()) lines.push_back("made by: " + command);
  lines.push_back(std::string("lobe sharing: ") + (module.table.lobe_sharing ? "band l uses lobes 0..2l" : "each band has its own lobes") +
                  "; " + std::to_string(module.table.zeros) + " of " + std::to_string(module.table.entries) +
                  " entries of A_l = Y_l^-1 are structural zeros.");
  lines.push_back("The rotations evaluate SH at R u_d, u_d = w_d rescaled so its components are +-1 where possible,");
  lines.push_back("with A_l's column d scaled by |u_d|^-l (band-l SH are homogeneous of degree l) and each");
  lines.push_back("output's normalisation applied once after the sum over lobes.");
  char model[32];
  std::snprintf(model, sizeof model, "%.2g", runtime::tolerance::float_lobe_error_model(module.order, module.table.worst_condition()));
  const std::string float_model = std::string("the float error model eps_f (N-1) k_max = ") + model;
  switch (stage) {
    case runtime::LobeStage::kFloat:
      lines.push_back("Lobe stage in the kernel's type (zhf emit --lobe-stage): " + float_model + ".");
      break;
    case runtime::LobeStage::kDoubleRotation:
      lines.push_back(std::string("Lobe stage ") + runtime::lobe_stage_name(stage) + " (zhf emit --lobe-stage): the lobes are rotated in double, their SH");
      lines.push_back("and the sums over lobes in the kernel's type; " + float_model + ".");
      break;
    case runtime::LobeStage::kDouble:
      lines.push_back("Lobe stage double: R is projected onto the rotations (one Newton step to its polar factor),");
      lines.push_back("and the rotated lobes, their SH and the sums over lobes are double, because in float");
      lines.push_back(float_model + " exceeds the " + runtime::format_number(runtime::tolerance::kFloatRotation) + " target (zhf emit --lobe-stage).");
      break;
  }
  for (size_t d = 0; d < module.lobes.size(); ++d)
    lines.push_back("  w_" + std::to_string(d) + ": " + module.lobes[d].source);
  std::string methods = "Rotations (zhf emit --method): ";
  for (int l = 2; l < module.order; ++l)
    methods += (l > 2 ? ", " : "") + std::string("band ") + std::to_string(l) + " " + band_method_name(module.band_methods[l]);
  lines.push_back(methods + ";");
  lines.push_back(module.band_methods_reason + ".");
  return lines;
}

}  // namespace zhf::codegen
