#include "zhf/codegen/needlet_lut.h"
#include "zhf/codegen/limits.h"
#include "zhf/frames/limits.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "c_family_printer.h"

namespace zhf::codegen {
namespace {

// How each language spells the few constructs the evaluator needs.
struct NeedletSpelling {
  std::string extension;
  std::string int_type, float_type;                  // also the conversions' names
  std::string beta_parameter, direction_parameter;  // with %N for the coefficient count
  std::string clamp_open, clamp_close;               // around t
  bool wgsl = false;                                 // `fn f(a: T) -> f32`, `var`/`let`
  std::string inline_keyword;                        // C++: "inline "

  std::string parameter(bool integer, const std::string& name) const {
    const std::string& type = integer ? int_type : float_type;
    return wgsl ? name + ": " + type : type + " " + name;
  }
  std::string signature(const std::string& name, const std::string& parameters) const {
    return wgsl ? "fn " + name + "(" + parameters + ") -> f32 {\n" : inline_keyword + "float " + name + "(" + parameters + ") {\n";
  }
  // A local: `int i` / `var i: i32` when it changes, `float s` / `let s: f32` when not.
  std::string local(bool integer, bool changes, const std::string& name) const {
    return wgsl ? std::string(changes ? "var " : "let ") + parameter(integer, name) : parameter(integer, name);
  }
};

NeedletSpelling spelling(Language language) {
  switch (language) {
    case Language::kCpp: return {".h", "int", "float", "const float beta[%N]", "const float x[3]", "std::fmin(std::fmax(", ", -1.0f), 1.0f)", false, "inline "};
    case Language::kGlsl: return {".glsl", "int", "float", "in float beta[%N]", "vec3 x", "clamp(", ", -1.0f, 1.0f)", false, ""};
    case Language::kHlsl: return {".hlsl", "int", "float", "float beta[%N]", "float3 x", "clamp(", ", -1.0f, 1.0f)", false, ""};
    case Language::kWgsl: return {".wgsl", "i32", "f32", "beta: array<f32, %N>", "x: vec3<f32>", "clamp(", ", -1.0f, 1.0f)", true, ""};
  }
  throw std::invalid_argument("no needlet printer for this language");
}

std::string spell(std::string text, std::size_t n) {
  for (std::size_t at; (at = text.find("%N")) != std::string::npos;) text.replace(at, 2, std::to_string(n));
  return text;
}

std::string upper(const std::string& text) {
  std::string out;
  for (char c : text) out += (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
  return out;
}

// Where the data's three parts start (in floats): nodes, scales, tables.
struct DataLayout {
  int nodes = 0, scales = 0, tables = 0, total = 0;
};
DataLayout layout(const frames::NeedletFrame& frame, int table_size) {
  DataLayout d;
  d.scales = 3 * frame.size();
  d.tables = 4 * frame.size();
  d.total = d.tables + static_cast<int>(frame.levels().size()) * table_size;
  return d;
}

}  // namespace

const std::vector<Language>& needlet_lut_languages() {
  static const std::vector<Language> languages = {Language::kCpp, Language::kGlsl, Language::kHlsl, Language::kWgsl};
  return languages;
}

bool valid_prefix(const std::string& prefix, std::string& why) {
  if (prefix.empty() || prefix.size() > 48) {
    why = "must be 1..48 characters";
    return false;
  }
  for (std::size_t i = 0; i < prefix.size(); ++i) {
    const char c = prefix[i];
    const bool letter = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
    if (!letter && !(i > 0 && c >= '0' && c <= '9')) {
      why = "must be an identifier: letters, digits and '_', not starting with a digit";
      return false;
    }
  }
  if (prefix.rfind("gl_", 0) == 0 || prefix.find("__") != std::string::npos) {
    why = "must not start with 'gl_' or contain '__' (reserved in GLSL and C++)";
    return false;
  }
  return true;
}

OpCount needlet_lut_ops(const frames::NeedletFrame& frame, frames::Interpolation interpolation) {
  // Per node, float operations as printed: the dot product (3, 2), the table read (linear: 2
  // multiplies, 4 adds; quadratic: 9 multiplies, 9 adds), the weighted accumulation (2, 1).
  const bool linear = interpolation == frames::Interpolation::kLinear;
  OpCount per_node{3 + (linear ? 2 : 9) + 2, 2 + (linear ? 4 : 9) + 1};
  return {per_node.multiplies * frame.size(), per_node.adds * frame.size()};
}

std::vector<float> needlet_lut_data(const frames::NeedletFrame& frame, int table_size) {
  std::vector<float> data;
  for (const frames::NeedletLevel& level : frame.levels())
    for (const frames::Point& p : level.cubature.points)
      for (double c : p) data.push_back(static_cast<float>(c));
  for (const frames::NeedletLevel& level : frame.levels())
    for (double w : level.cubature.weights) data.push_back(static_cast<float>(std::sqrt(w)));
  for (int a = 0; a < static_cast<int>(frame.levels().size()); ++a) {
    const frames::UniformTable table([&](double t) { return frame.kernel(a, t); }, table_size);
    for (double v : table.values()) data.push_back(static_cast<float>(v));
  }
  return data;
}

EmittedFile emit_needlet_lut(const frames::NeedletFrame& frame, Language language, const NeedletLutOptions& o) {
  std::string why;
  if (!valid_prefix(o.prefix, why)) throw std::invalid_argument("prefix: " + why);
  if (o.table_size < frames::kMinNeedletTableSize || o.table_size > frames::kMaxNeedletTableSize)
    throw std::invalid_argument("table size must be " + std::to_string(frames::kMinNeedletTableSize) + ".." + std::to_string(frames::kMaxNeedletTableSize));
  if (o.storage_set < 0 || o.storage_set > codegen::kMaxStorageSet || o.storage_binding < 0 || o.storage_binding > codegen::kMaxStorageBinding)
    throw std::invalid_argument("storage set must be 0.." + std::to_string(codegen::kMaxStorageSet) + " and binding 0.." +
                                std::to_string(codegen::kMaxStorageBinding));
  const NeedletSpelling s = spelling(language);
  const std::string& p = o.prefix;
  const int size = o.table_size, levels = static_cast<int>(frame.levels().size());
  const bool linear = o.interpolation == frames::Interpolation::kLinear;
  const DataLayout d = layout(frame, size);
  const std::string data = p + "_data";

  EmittedFile file;
  file.file_name = p + s.extension;
  EmittedFunction eval;
  eval.name = p + "_eval";
  eval.ops = needlet_lut_ops(frame, o.interpolation);
  file.functions.push_back(eval);

  std::ostringstream b;
  b.precision(17);
  b << frame.dilation();
  std::vector<std::string> about = {
      "A needlet expansion (zhf docs/frames.md): f(x) = sum over levels and nodes k of",
      "beta[k] sqrt(lambda_k) K_level(x . xi_k), for the needlet frame of bands 0.." + std::to_string(frame.band_limit()) +
          " with dilation B = " + b.str() + ", " + std::to_string(frame.size()) + " coefficients.",
      "Each kernel K(t) = sum_l b(l / B^j) (2l+1)/(4 pi) P_l(t) is tabulated at " + std::to_string(size) +
          " equally spaced t in [-1, 1] and read by " + (linear ? "linear" : "quadratic (three nearest nodes)") + " interpolation.",
      "Levels (j = -1: the scaling function, band 0), their bands and nodes:"};
  for (const frames::NeedletLevel& level : frame.levels())
    about.push_back("  j = " + std::to_string(level.j) + ": bands " + std::to_string(level.lmin) + ".." + std::to_string(level.lmax) + ", " +
                    std::to_string(level.cubature.points.size()) + " nodes (" + level.cubature.name + ")");
  about.push_back("The " + std::to_string(d.total) + " floats of " + data + ": node xi_k at [3k..3k+2], sqrt(lambda_k) at [" +
                  std::to_string(d.scales) + " + k],");
  about.push_back("kernel a at t_i = -1 + 2 i / " + std::to_string(size - 1) + " at [" + std::to_string(d.tables) + " + " +
                  std::to_string(size) + " a + i].");

  std::ostringstream out;
  out << "// Generated by zhf " << ZHF_VERSION << ": " << comment_text(o.command) << "\n"
      << "// Do not edit: run the command above again.\n"
      << "// Operations per call (multiplies, adds): " << eval.name << ": " << eval.ops.multiplies << " multiplies, " << eval.ops.adds
      << " adds\n//\n"
      << commented(about) << "\n";
  if (language == Language::kCpp) {
    LanguageConfig literal;
    literal.scalar = "float";
    literal.literal_suffix = "f";
    const std::vector<float> values = needlet_lut_data(frame, size);
    out << "#pragma once\n\n#include <cmath>\n\ninline constexpr float " << data << "[" << values.size() << "] = {\n";
    for (std::size_t i = 0; i < values.size(); ++i)
      out << (i % 8 ? " " : "    ") << format_literal(values[i], literal, Precision::kFloat) << (i + 1 < values.size() ? "," : "")
          << (i % 8 == 7 || i + 1 == values.size() ? "\n" : "");
    out << "};\n\n";
  } else {
    // Shaders read the numbers from a storage buffer (a constant array this size costs drivers
    // minutes to compile): the application uploads the file `zhf needlets emit --data` writes.
    const std::string set_value = std::to_string(o.storage_set), binding_value = std::to_string(o.storage_binding);
    if (s.wgsl) {
      // WGSL has no preprocessor: the group and binding are fixed here.
      out << "// The application binds the " << d.total << " floats (zhf needlets emit --data) as a storage buffer at\n"
          << "// group " << set_value << ", binding " << binding_value << " (zhf needlets emit --set, --binding).\n"
          << "@group(" << set_value << ") @binding(" << binding_value << ") var<storage, read> " << data << ": array<f32>;\n\n";
    } else {
      const std::string set = upper(p) + "_SET", binding = upper(p) + "_BINDING";
      out << "// The application binds the " << d.total << " floats (zhf needlets emit --data) as a storage buffer at\n"
          << "// " << set << " / " << binding << " (default " << set_value << " / " << binding_value
          << "; define them before including this file).\n"
          << "#ifndef " << set << "\n#define " << set << " " << set_value << "\n#endif\n"
          << "#ifndef " << binding << "\n#define " << binding << " " << binding_value << "\n#endif\n";
      if (language == Language::kGlsl)
        out << "layout(std430, set = " << set << ", binding = " << binding << ") readonly buffer " << p << "_buffer { float " << data
            << "[]; };\n\n";
      else
        out << "[[vk::binding(" << binding << ", " << set << ")]] StructuredBuffer<float> " << data << ";\n\n";
    }
  }
  // `if (c) x = v;`, braced in WGSL.
  const auto assign_if = [&](const std::string& condition, const std::string& assignment) {
    return "if (" + condition + ") " + (s.wgsl ? "{ " + assignment + "; }" : assignment + ";");
  };
  const std::string& to_int = s.int_type;
  const std::string& to_float = s.float_type;
  const std::string half_last = std::to_string(0.5 * (size - 1)) + "f", tables = std::to_string(d.tables);
  out << s.signature(p + "_kernel", s.parameter(true, "level") + ", " + s.parameter(false, "t"))
      << "  " << s.local(false, false, "u") << " = (" << s.clamp_open << "t" << s.clamp_close << " + 1.0f) * " << half_last << ";\n";
  if (linear) {
    out << "  " << s.local(true, true, "i") << " = " << to_int << "(u);\n"
        << "  " << assign_if("i > " + std::to_string(size - 2), "i = " + std::to_string(size - 2)) << "\n"
        << "  " << s.local(false, false, "s") << " = u - " << to_float << "(i);\n"
        << "  " << s.local(true, false, "base") << " = " << tables << " + level * " << size << " + i;\n"
        << "  " << s.local(false, false, "a") << " = " << data << "[base];\n"
        << "  return a + s * (" << data << "[base + 1] - a);\n";
  } else {
    out << "  " << s.local(true, true, "c") << " = " << to_int << "(u + 0.5f);\n"
        << "  " << assign_if("c < 1", "c = 1") << "\n"
        << "  " << assign_if("c > " + std::to_string(size - 2), "c = " + std::to_string(size - 2)) << "\n"
        << "  " << s.local(false, false, "s") << " = u - " << to_float << "(c);\n"
        << "  " << s.local(true, false, "base") << " = " << tables << " + level * " << size << " + c;\n"
        << "  return " << data << "[base - 1] * s * (s - 1.0f) * 0.5f + " << data << "[base] * (1.0f - s) * (1.0f + s) + " << data
        << "[base + 1] * s * (s + 1.0f) * 0.5f;\n";
  }
  out << "}\n\n";
  // The level boundaries as a chain of comparisons: a few integers need no array.
  out << s.signature(p + "_eval", spell(s.beta_parameter, frame.size()) + ", " + s.direction_parameter)
      << "  " << s.local(false, true, "sum") << " = 0.0f;\n"
      << "  " << s.local(true, true, "level") << " = 0;\n"
      << "  " << s.local(true, true, "next") << " = " << (levels > 1 ? frame.levels()[1].offset : frame.size()) << ";\n"
      << "  for (" << s.local(true, true, "k") << " = 0; k < " << frame.size() << "; " << (s.wgsl ? "k++" : "++k") << ") {\n";
  if (levels > 1) {
    out << "    if (k == next) {\n      " << (s.wgsl ? "level++;" : "++level;") << "\n";
    for (int a = 1; a < levels; ++a)
      out << "      " << (a > 1 ? "else " : "")
          << assign_if("level == " + std::to_string(a),
                       "next = " + std::to_string(a + 1 < levels ? frame.levels()[a + 1].offset : frame.size()))
          << "\n";
    out << "    }\n";
  }
  out << "    " << s.local(false, false, "t") << " = x[0] * " << data << "[3 * k] + x[1] * " << data << "[3 * k + 1] + x[2] * " << data
      << "[3 * k + 2];\n"
      << "    sum += beta[k] * " << data << "[" << d.scales << " + k] * " << p << "_kernel(level, t);\n"
      << "  }\n"
      << "  return sum;\n"
      << "}\n";
  file.text = out.str();
  return file;
}

}  // namespace zhf::codegen
