#include "zhf/verify/verify.h"

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <random>
#include <sstream>

#include <Eigen/Geometry>

#include "zhf/codegen/kernels.h"
#include "zhf/io/files.h"
#include "zhf/optimizer/lobe_table.h"
#include "zhf/sh/eval.h"
#include "zhf/sh/index.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/verify/vulkan_runner.h"

namespace zhf::verify {
namespace fs = std::filesystem;
namespace {

// What each emitted function is asked to do. A mode is one function (dense: the build and
// apply pair) with a channel count; the manifest says which a file holds.
enum class Kind { kRotate, kTailored, kBatch, kEval, kTranspose, kMultiply, kDense, kZonal };

struct Mode {
  Kind kind = Kind::kRotate;
  int channels = 1;
  std::string function;  // the function checked (for dense: the apply function)
};

std::string suffix_of(int channels) { return channels == 3 ? "_rgb" : channels == 4 ? "_rgba" : ""; }

// The modes of one file from its function names; unknown names are errors, not silence.
std::vector<Mode> modes_of(const std::vector<std::string>& functions, int order, std::vector<std::string>& errors,
                           const std::string& tag) {
  const std::string tail = "_order" + std::to_string(order);
  const bool has_matrices =
      std::find(functions.begin(), functions.end(), "rotation_matrices" + tail) != functions.end();
  std::vector<Mode> modes;
  for (const std::string& name : functions) {
    if (name.size() <= tail.size() || name.compare(name.size() - tail.size(), tail.size(), tail) != 0) {
      errors.push_back(tag + ": function " + name + " does not end in " + tail);
      continue;
    }
    const std::string base = name.substr(0, name.size() - tail.size());
    if (base == "rotation_matrices") continue;
    Mode m;
    m.function = name;
    bool known = false;
    for (int channels : {1, 3, 4}) {
      const std::string sfx = suffix_of(channels);
      const std::pair<std::string, Kind> kinds[] = {{"rotate" + sfx, Kind::kRotate},
                                                    {"rotate_signal_tailored" + sfx, Kind::kTailored},
                                                    {"apply_rotation_matrices" + sfx, Kind::kDense},
                                                    {"rotate_zonal" + sfx, Kind::kZonal}};
      for (const auto& [prefix, kind] : kinds)
        if (base == prefix) {
          m.kind = kind;
          m.channels = channels;
          known = true;
        }
    }
    if (base == "rotate_batch") m.kind = Kind::kBatch, known = true;
    if (base == "sh_eval") m.kind = Kind::kEval, known = true;
    if (base == "AhatTransposeMultiply") m.kind = Kind::kTranspose, known = true;
    if (base == "AhatMultiply") m.kind = Kind::kMultiply, known = true;
    if (!known) {
      errors.push_back(tag + ": verify does not know how to run " + name);
      continue;
    }
    if (m.kind == Kind::kDense && !has_matrices) {
      errors.push_back(tag + ": " + name + " without rotation_matrices" + tail);
      continue;
    }
    modes.push_back(m);
  }
  return modes;
}

// What generated/ holds when there is no manifest: the default module.
std::vector<std::string> default_functions(int order, const std::string& language) {
  const std::string o = "_order" + std::to_string(order);
  std::vector<std::string> f = {"sh_eval" + o};
  if (order > 2) f.insert(f.end(), {"AhatTransposeMultiply" + o, "AhatMultiply" + o});
  f.insert(f.end(), {"rotate" + o, "rotate_signal_tailored" + o, "rotate_rgb" + o});
  if (language == "cpp") f.push_back("rotate_batch" + o);
  return f;
}

// One file of the generated tree, as the manifest describes it.
struct FileEntry {
  std::string path;  // relative to the generated dir
  std::vector<std::string> functions;
  std::vector<int> zero_bands;
  std::string lobe_stage;  // "double" or "native"; empty: generated/'s default (auto)
};

std::map<std::pair<int, std::string>, FileEntry> read_manifest(const fs::path& generated, std::vector<int>& orders) {
  std::map<std::pair<int, std::string>, FileEntry> files;
  const fs::path manifest = generated / "manifest.json";
  if (!fs::exists(manifest)) return files;
  const nlohmann::json j = io::read_json_file(manifest.string());
  std::set<int> seen;
  for (const nlohmann::json& f : j.value("files", nlohmann::json::array())) {
    const std::string language = f.value("language", "");
    const std::string precision = f.value("precision", "");
    if (precision == "double") continue;  // shaders are run in float; C++ in both
    if (f.contains("kind")) continue;      // tables without kernels (lanes-tables)
    FileEntry entry;
    entry.path = f.value("path", "");
    for (const nlohmann::json& fn : f.value("functions", nlohmann::json::array())) entry.functions.push_back(fn.value("name", ""));
    entry.zero_bands = f.value("zero_bands", std::vector<int>{});
    entry.lobe_stage = f.value("lobe_stage", "");
    const int order = f.value("order", 0);
    seen.insert(order);
    files[{order, language}] = entry;
  }
  orders.assign(seen.begin(), seen.end());
  return files;
}

struct Inputs {
  int order = 0;
  int count = 0;
  std::vector<double> rotations;  // 9 per input, row-major
  std::vector<double> axes;       // 3 per input: the zonal functions' axes
  std::vector<double> coeffs;     // N^2 per input, unit norm, zero on known-zero bands
  std::vector<std::string> names; // the extreme inputs' names
  std::vector<bool> live;         // per band: not known to be zero
};

// The fixed extreme set, then random rotations; the same for every language.
Inputs make_inputs(int order, int random_count, const optimizer::LobeTable& table, const std::vector<int>& zero_bands) {
  Inputs in;
  in.order = order;
  in.live.assign(order, true);
  for (int l : zero_bands)
    if (l >= 0 && l < order) in.live[l] = false;
  const double pi = 3.14159265358979323846;
  std::vector<std::pair<std::string, sh::Matrix3>> rotations = {
      {"identity", sh::Matrix3::Identity()},
      {"180 about x", sh::rotation_about_axis(Eigen::Vector3d::UnitX(), pi)},
      {"180 about y", sh::rotation_about_axis(Eigen::Vector3d::UnitY(), pi)},
      {"180 about z", sh::rotation_about_axis(Eigen::Vector3d::UnitZ(), pi)},
      {"180 about (1,1,0)/sqrt2", sh::rotation_about_axis(Eigen::Vector3d(1, 1, 0), pi)},
      {"zyz beta=0", sh::rotation_from_zyz(0.4, 0.0, -1.3)},
      {"zyz beta=pi", sh::rotation_from_zyz(0.4, pi, -1.3)},
      {"1e-7 rad", sh::rotation_about_axis(Eigen::Vector3d(0.3, -0.2, 0.9), 1e-7)},
  };
  for (size_t d = 0; d < table.lobes.size() && d < 3; ++d) {
    // Carry lobe d onto the north pole.
    const Eigen::Vector3d w(table.lobes[d].xyz), z = Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d axis = w.cross(z);
    if (axis.norm() < 1e-12) continue;
    rotations.push_back({"lobe " + std::to_string(d) + " onto the pole", sh::rotation_about_axis(axis, std::acos(std::clamp(w.dot(z), -1.0, 1.0)))});
  }
  std::mt19937_64 rng(20261122 + order);
  for (int k = 0; k < random_count; ++k) rotations.push_back({"random", sh::random_rotation(rng)});
  std::normal_distribution<double> normal;
  for (const auto& [name, r] : rotations) {
    for (int i = 0; i < 9; ++i) in.rotations.push_back(r(i / 3, i % 3));
    Eigen::VectorXd f(order * order);
    for (int i = 0; i < f.size(); ++i) f[i] = in.live[sh::band_of(i)] ? normal(rng) : 0.0;
    f.normalize();
    in.coeffs.insert(in.coeffs.end(), f.data(), f.data() + f.size());
    // The first zonal axis is +z (zonal coefficients then equal the weights); the rest random.
    Eigen::Vector3d a = in.names.empty() ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    in.axes.insert(in.axes.end(), a.data(), a.data() + 3);
    in.names.push_back(name);
  }
  in.count = static_cast<int>(rotations.size());
  return in;
}

constexpr int kMaxChannels = 4;
// Floats in the packed dense band matrices of an order (codegen's dense_matrix_offset(order)).
int dense_size(int order) { return order * (2 * order - 1) * (2 * order + 1) / 3; }

// The zonal weights channel c of input v rotates: the first N coefficients of input
// (v + c) % count, zero on known-zero bands.
double zonal_weight(const Inputs& in, int v, int c, int l) {
  const int n = in.order * in.order;
  return in.live[l] ? in.coeffs[size_t(n) * ((v + c) % in.count) + l] : 0.0;
}

// reference[mode][v * 4n + c * n + k]; channel c of input v is rotation v applied to the
// coefficients of input (v + c) % count.
std::vector<std::vector<double>> reference_outputs(const Inputs& in, const optimizer::LobeTable& table,
                                                   const std::vector<Mode>& modes) {
  const int n = in.order * in.order;
  const size_t block = size_t(kMaxChannels) * n;
  std::vector<std::vector<double>> ref(modes.size(), std::vector<double>(block * in.count, 0.0));
  for (int v = 0; v < in.count; ++v) {
    sh::Matrix3 r;
    for (int i = 0; i < 9; ++i) r(i / 3, i % 3) = in.rotations[9 * v + i];
    const sh::BandMatrices bands = sh::ivanic_ruedenberg(r, in.order);
    std::vector<Eigen::VectorXd> rotated(kMaxChannels), zonal(kMaxChannels);
    std::vector<double> y(n);
    sh::eval_sh(in.order, &in.axes[3 * v], y.data());
    for (int c = 0; c < kMaxChannels; ++c) {
      const Eigen::Map<const Eigen::VectorXd> f(&in.coeffs[size_t(n) * ((v + c) % in.count)], n);
      rotated[c] = sh::apply_band_matrices(bands, f);
      // The zonal function's coefficients in the unrotated frame, then the reference rotation.
      Eigen::VectorXd z(n);
      for (int i = 0; i < n; ++i) {
        const int l = sh::band_of(i);
        z[i] = std::sqrt(4 * 3.14159265358979323846 / (2 * l + 1)) * zonal_weight(in, v, c, l) * y[i];
      }
      zonal[c] = sh::apply_band_matrices(bands, z);
    }
    const double* f = &in.coeffs[size_t(n) * v];
    for (size_t k = 0; k < modes.size(); ++k) {
      double* out = &ref[k][block * v];
      const Mode& m = modes[k];
      switch (m.kind) {
        case Kind::kRotate:
        case Kind::kTailored:
        case Kind::kBatch:
        case Kind::kDense:
          for (int c = 0; c < m.channels; ++c)
            for (int i = 0; i < n; ++i) out[c * n + i] = rotated[c][i];
          break;
        case Kind::kZonal:
          for (int c = 0; c < m.channels; ++c)
            for (int i = 0; i < n; ++i) out[c * n + i] = zonal[c][i];
          break;
        case Kind::kEval: {
          const double dir[3] = {in.rotations[9 * v], in.rotations[9 * v + 1], in.rotations[9 * v + 2]};
          sh::eval_sh(in.order, dir, out);
          break;
        }
        case Kind::kTranspose:
        case Kind::kMultiply:
          for (int i = 0; i < std::min(n, 4); ++i) out[i] = f[i];
          for (const optimizer::TableBand& band : table.bands) {
            const int size = 2 * band.l + 1, b0 = band.l * band.l;
            for (int i = 0; i < size; ++i)
              for (int j = 0; j < size; ++j)
                out[b0 + i] += (m.kind == Kind::kTranspose ? band.inverse(j, i) : band.inverse(i, j)) * f[b0 + j];
          }
          break;
      }
    }
  }
  return ref;
}

int run_command(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string first_lines(const std::string& path, int lines) {
  std::ifstream in(path);
  std::string line, out;
  for (int i = 0; i < lines && std::getline(in, line); ++i) out += (i ? " | " : "") + line;
  return out;
}

void write_doubles(const std::string& path, const std::vector<double>& values) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(double)));
}

std::vector<double> read_doubles(const std::string& path, size_t count) {
  std::vector<double> values(count);
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(values.data()), std::streamsize(count * sizeof(double)));
  if (static_cast<size_t>(in.gcount()) != count * sizeof(double)) throw std::runtime_error(path + ": short read");
  return values;
}

// Input stride per input in the rotations stream: R (9) and the zonal axis (3).
constexpr int kRotationStride = 12;

// The call a harness makes for one mode, in C++ (shader = false) or a shader language. The
// harness holds r[9], axis[3], c[4][n] / c1 (channel 0), z[4][N] / z1, o[4][n] / o1 and, for
// shaders, cv/zv/ov arrays of vectors for multi-channel calls.
std::string call(const Mode& m, int order, bool cpp) {
  const std::string o = "_order" + std::to_string(order);
  const std::string t = cpp ? "<T>" : "";
  const std::string ns = cpp ? "zhf::gen::" : "";
  // C++ passes the planar [4][n] arrays; shaders the vector arrays of the channel count.
  const bool multi = m.channels > 1;
  const std::string width = cpp ? "" : std::to_string(m.channels);
  const std::string cv = multi ? (cpp ? "c" : "cv") + width : "c1";
  const std::string ov = multi ? (cpp ? "o" : "ov") + width : "o1";
  const std::string zv = multi ? (cpp ? "z" : "zv") + width : "z1";
  switch (m.kind) {
    case Kind::kRotate:
    case Kind::kTailored:
      return ns + m.function + t + "(r, " + cv + ", " + ov + ");";
    case Kind::kEval:
      return cpp ? ns + m.function + t + "(r, o1);" : "{ float d[3]; d[0] = r[0]; d[1] = r[1]; d[2] = r[2]; " + m.function + "(d, o1); }";
    case Kind::kTranspose:
    case Kind::kMultiply:
      return ns + m.function + t + "(c1, o1);";
    case Kind::kDense:
      return ns + "rotation_matrices" + o + t + "(r, mats); " + ns + m.function + t + "(mats, " + cv + ", " + ov + ");";
    case Kind::kZonal:
      return ns + m.function + t + "(r, axis, " + zv + ", " + ov + ");";
    case Kind::kBatch:
      break;
  }
  return "";
}

// The C++ harness zhf writes for one file: runs every function in float and double.
std::string cpp_harness(int order, const std::vector<Mode>& modes) {
  const std::string o = std::to_string(order);
  const int n = order * order;
  std::ostringstream s;
  s << "// Generated by zhf verify: runs the emitted order-" << o << " kernels on inputs.bin.\n"
    << "#include <cstdio>\n#include <vector>\n#include \"zhf_order" << o << ".h\"\n\n"
    << "constexpr int kN = " << n << ", kOrder = " << order << ", kBlock = " << kMaxChannels * n << ";\n"
    << "template <class T>\nvoid run(int count, const std::vector<double>& rot, const std::vector<double>& co, std::FILE* out) {\n"
    << "  std::vector<double> res(kBlock * size_t(count));\n"
    << "  T r[9], axis[3], c[4][kN], z[4][kOrder], o[4][kN], mats[" << std::max(1, dense_size(order)) << "];\n"
    << "  T* c1 = c[0]; T* z1 = z[0]; T* o1 = o[0];\n"
    << "  (void)c1; (void)z1; (void)axis; (void)mats;\n";
  for (size_t k = 0; k < modes.size(); ++k) {
    const Mode& m = modes[k];
    s << "  // " << m.function << "\n";
    if (m.kind == Kind::kBatch) {
      s << "  {\n"
        << "    std::vector<T> br(9 * size_t(count)), bc(kN * size_t(count)), bo(kN * size_t(count));\n"
        << "    for (int v = 0; v < count; ++v) {\n"
        << "      for (int i = 0; i < 9; ++i) br[i * size_t(count) + v] = T(rot[" << kRotationStride << " * v + i]);\n"
        << "      for (int i = 0; i < kN; ++i) bc[i * size_t(count) + v] = T(co[kN * v + i]);\n"
        << "    }\n"
        << "    zhf::gen::" << m.function << "<T>(count, br.data(), bc.data(), bo.data());\n"
        << "    for (int v = 0; v < count; ++v) for (int i = 0; i < kN; ++i) res[kBlock * size_t(v) + i] = double(bo[i * size_t(count) + v]);\n"
        << "  }\n";
    } else {
      s << "  for (int v = 0; v < count; ++v) {\n"
        << "    for (int i = 0; i < 9; ++i) r[i] = T(rot[" << kRotationStride << " * v + i]);\n"
        << "    for (int i = 0; i < 3; ++i) axis[i] = T(rot[" << kRotationStride << " * v + 9 + i]);\n"
        << "    for (int ch = 0; ch < 4; ++ch) {\n"
        << "      for (int i = 0; i < kN; ++i) { c[ch][i] = T(co[kN * ((v + ch) % count) + i]); o[ch][i] = T(0); }\n"
        << "      for (int l = 0; l < kOrder; ++l) z[ch][l] = c[ch][l];\n"
        << "    }\n"
        << "    " << call(m, order, true) << "\n"
        << "    for (int ch = 0; ch < 4; ++ch) for (int i = 0; i < kN; ++i) res[kBlock * size_t(v) + ch * kN + i] = double(o[ch][i]);\n"
        << "  }\n";
    }
    s << "  std::fwrite(res.data(), sizeof(double), res.size(), out);\n";
  }
  s << "}\n\n"
    << "int main(int argc, char** argv) {\n"
    << "  if (argc != 3) return 2;\n"
    << "  std::FILE* in = std::fopen(argv[1], \"rb\");\n"
    << "  double header = 0;\n"
    << "  if (!in || std::fread(&header, sizeof header, 1, in) != 1) return 3;\n"
    << "  const int count = int(header);\n"
    << "  std::vector<double> rot(" << kRotationStride << " * size_t(count)), co(kN * size_t(count));\n"
    << "  if (std::fread(rot.data(), sizeof(double), rot.size(), in) != rot.size()) return 3;\n"
    << "  if (std::fread(co.data(), sizeof(double), co.size(), in) != co.size()) return 3;\n"
    << "  std::FILE* out = std::fopen(argv[2], \"wb\");\n"
    << "  if (!out) return 4;\n"
    << "  run<float>(count, rot, co, out);\n"
    << "  run<double>(count, rot, co, out);\n"
    << "  return std::fclose(out) == 0 ? 0 : 4;\n"
    << "}\n";
  return s.str();
}

// Compute-shader wrappers: invocation i runs mode (i / count) on input (i % count).
std::string shader_source(const std::string& language, int order, const std::string& kernels,
                          const std::vector<Mode>& modes) {
  const int n = order * order;
  const std::string ns = std::to_string(n), block = std::to_string(kMaxChannels * n);
  std::ostringstream s;
  const bool glsl = language == "glsl";
  if (glsl) {
    s << "#version 450\n"
      << "layout(local_size_x = 64) in;\n"
      << "layout(std430, set = 0, binding = 0) readonly buffer Rotations { float rotations[]; };\n"
      << "layout(std430, set = 0, binding = 1) readonly buffer Coefficients { float coefficients[]; };\n"
      << "layout(std430, set = 0, binding = 2) writeonly buffer Results { float results[]; };\n"
      << "layout(push_constant) uniform Params { uint count; } params;\n\n";
  } else {
    s << "struct Params { uint count; };\n"
      << "[[vk::push_constant]] ConstantBuffer<Params> params;\n"
      << "[[vk::binding(0, 0)]] StructuredBuffer<float> rotations;\n"
      << "[[vk::binding(1, 0)]] StructuredBuffer<float> coefficients;\n"
      << "[[vk::binding(2, 0)]] RWStructuredBuffer<float> results;\n\n";
  }
  s << kernels << "\n";
  // Multi-channel calls of one channel count share vector arrays; at most one count per file
  // is common, but every count present gets its own.
  std::set<int> widths;
  for (const Mode& m : modes)
    if (m.channels > 1) widths.insert(m.channels);
  auto vec = [&](int w) { return (glsl ? std::string("vec") : std::string("float")) + std::to_string(w); };
  if (glsl) {
    s << "void main() {\n  uint i = gl_GlobalInvocationID.x;\n";
  } else {
    s << "[numthreads(64, 1, 1)]\nvoid main(uint3 id : SV_DispatchThreadID) {\n  uint i = id.x;\n";
  }
  s << "  if (i >= " << modes.size() << "u * params.count) return;\n"
    << "  uint v = i % params.count;\n  uint mode = i / params.count;\n"
    << "  float r[9];\n  float axis[3];\n  float c[4][" << ns << "];\n  float z[4][" << order << "];\n"
    << "  float c1[" << ns << "];\n  float z1[" << order << "];\n  float o1[" << ns << "];\n"
    << "  float mats[" << std::max(1, dense_size(order)) << "];\n";
  for (int w : widths)
    s << "  " << vec(w) << " cv" << w << "[" << ns << "];\n  " << vec(w) << " zv" << w << "[" << order << "];\n  " << vec(w)
      << " ov" << w << "[" << ns << "];\n";
  s << "  for (int k = 0; k < 9; ++k) r[k] = rotations[" << kRotationStride << "u * v + uint(k)];\n"
    << "  for (int k = 0; k < 3; ++k) axis[k] = rotations[" << kRotationStride << "u * v + 9u + uint(k)];\n"
    << "  for (int ch = 0; ch < 4; ++ch) {\n"
    << "    for (int k = 0; k < " << ns << "; ++k) c[ch][k] = coefficients[" << ns << "u * ((v + uint(ch)) % params.count) + uint(k)];\n"
    << "    for (int k = 0; k < " << order << "; ++k) z[ch][k] = c[ch][k];\n"
    << "  }\n"
    << "  for (int k = 0; k < " << ns << "; ++k) { c1[k] = c[0][k]; o1[k] = 0.0; }\n"
    << "  for (int k = 0; k < " << order << "; ++k) z1[k] = z[0][k];\n";
  for (int w : widths) {
    const std::string args3 = "c[0][k], c[1][k], c[2][k]" + std::string(w == 4 ? ", c[3][k]" : "");
    const std::string zargs = "z[0][k], z[1][k], z[2][k]" + std::string(w == 4 ? ", z[3][k]" : "");
    s << "  for (int k = 0; k < " << ns << "; ++k) { cv" << w << "[k] = " << vec(w) << "(" << args3 << "); ov" << w << "[k] = "
      << vec(w) << "(0.0" << std::string(w == 4 ? ", 0.0, 0.0, 0.0" : ", 0.0, 0.0") << "); }\n"
      << "  for (int k = 0; k < " << order << "; ++k) zv" << w << "[k] = " << vec(w) << "(" << zargs << ");\n";
  }
  for (size_t k = 0; k < modes.size(); ++k) s << "  if (mode == " << k << "u) { " << call(modes[k], order, false) << " }\n";
  s << "  uint base = (mode * params.count + v) * " << block << "u;\n"
    << "  for (int k = 0; k < " << ns << "; ++k) {\n"
    << "    results[base + uint(k)] = o1[k];\n";
  for (int w : widths) {
    s << "    if (";
    bool first = true;
    for (size_t k = 0; k < modes.size(); ++k)
      if (modes[k].channels == w) {
        s << (first ? "" : " || ") << "mode == " << k << "u";
        first = false;
      }
    s << ") {\n";
    for (int ch = 0; ch < w; ++ch)
      s << "      results[base + " << ch * n << "u + uint(k)] = ov" << w << "[k]." << "xyzw"[ch] << ";\n";
    s << "    }\n";
  }
  s << "  }\n}\n";
  return s.str();
}

// |a - b| in units in the last place of max(|a|, |b|, kUlpFloor): near zero a plain ulp count
// is meaningless (1e-12 against 0 is a billion ulps), so differences are measured at least
// at the scale of the coefficients (unit-norm vectors of up to 64 entries).
constexpr float kUlpFloor = 1.0f / 64;

double ulp_distance(float a, float b) {
  if (a == b) return 0;
  if (!std::isfinite(a) || !std::isfinite(b)) return INFINITY;
  const float scale = std::max({std::abs(a), std::abs(b), kUlpFloor});
  const double ulp = static_cast<double>(std::nextafter(scale, INFINITY)) - scale;
  return std::abs(static_cast<double>(a) - static_cast<double>(b)) / ulp;
}

// What a file's tolerances depend on besides the order.
struct Conditioning {
  double worst_condition = 1;
  bool wide_lobes = false;  // the lobe stage runs in double
};

Conditioning conditioning(const optimizer::LobeTable& table, const FileEntry& entry) {
  Conditioning c;
  if (table.order <= 2) return c;
  c.worst_condition = table.worst_condition();
  c.wide_lobes = entry.lobe_stage.empty() ? codegen::float_needs_wide_lobes(table) : entry.lobe_stage == "double";
  return c;
}

double tolerance_for(Kind kind, const std::string& precision, int order, const Conditioning& c) {
  if (precision == "double") return kDoubleTolerance;
  if (kind == Kind::kEval || kind == Kind::kZonal) return kFloatEvaluationTolerance;
  if (kind == Kind::kTranspose || kind == Kind::kMultiply) return kFloatSparseTolerance;
  return float_rotation_tolerance(order, c.worst_condition, c.wide_lobes);
}

FunctionResult compare(const Inputs& in, const Conditioning& conditioning, const Mode& mode, const std::vector<double>& got,
                       const std::vector<double>& expected, const std::string& language, const std::string& precision,
                       const std::vector<double>* cpp_float) {
  FunctionResult r;
  r.ulp_limit = language == "hlsl" || mode.kind == Kind::kDense ? hlsl_ulp_limit(in.order, conditioning.worst_condition) : kGlslUlpLimit;
  r.order = in.order;
  r.language = language;
  r.precision = precision;
  r.function = mode.function;
  r.tolerance = tolerance_for(mode.kind, precision, in.order, conditioning);
  const int n = in.order * in.order;
  const int lanes = mode.channels * n;
  double sum = 0;
  size_t terms = 0;
  for (int v = 0; v < in.count; ++v)
    for (int k = 0; k < lanes; ++k) {
      const size_t at = size_t(kMaxChannels) * n * v + k;
      const double e = std::abs(got[at] - expected[at]);
      if (!(e <= r.max_error)) {
        r.max_error = std::isnan(e) ? INFINITY : e;
        r.worst_index = k % n;
        r.worst_input = v;
      }
      sum += e * e;
      ++terms;
      if (cpp_float) r.max_ulps = std::max(r.max_ulps, ulp_distance(float(got[at]), float((*cpp_float)[at])));
    }
  if (!cpp_float) r.max_ulps = -1;
  r.rms_error = std::sqrt(sum / std::max<size_t>(1, terms));
  r.pass = r.max_error <= r.tolerance && r.max_ulps <= r.ulp_limit;
  return r;
}

}  // namespace

bool VerifyReport::pass() const {
  if (!errors.empty() || vulkan_missing) return false;
  for (const FunctionResult& r : results)
    if (!r.pass) return false;
  return !results.empty();
}

nlohmann::ordered_json VerifyReport::to_json() const {
  nlohmann::ordered_json j;
  j["format"] = "zhf-verify-1";
  j["pass"] = pass();
  j["device"] = device;
  j["tolerances"] = {{"double", kDoubleTolerance},
                     {"float_rotation", kFloatRotationTolerance},
                     {"float_sh_eval", kFloatEvaluationTolerance},
                     {"float_sparse_multiply", kFloatSparseTolerance},
                     {"glsl_ulps_vs_cpp_float", kGlslUlpLimit},
                     {"hlsl_ulps_vs_cpp_float", "max(256, 8 (N-1) k_max)"}};
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const FunctionResult& r : results)
    rows.push_back({{"order", r.order},
                    {"language", r.language},
                    {"precision", r.precision},
                    {"function", r.function},
                    {"max_error", r.max_error},
                    {"rms_error", r.rms_error},
                    {"max_ulps", r.max_ulps},
                    {"tolerance", r.tolerance},
                    {"worst_index", r.worst_index},
                    {"worst_input", r.worst_input},
                    {"pass", r.pass}});
  j["results"] = rows;
  j["errors"] = errors;
  return j;
}

std::string VerifyReport::table() const {
  // Rotations (the 1e-6 target) and the building blocks (sh_eval, the sparse products: values
  // up to ~10, their own tolerances) in separate columns.
  struct Row {
    double rotation_error = -1, other_error = -1, rms = 0, ulps = 0;
    bool pass = true;
    int functions = 0;
  };
  auto building_block = [](const std::string& f) { return f.rfind("sh_eval", 0) == 0 || f.rfind("Ahat", 0) == 0; };
  auto error_text = [](double e) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2e", e);
    return e < 0 ? std::string("-") : std::string(text);
  };
  std::map<std::tuple<int, std::string, std::string>, Row> rows;
  for (const FunctionResult& r : results) {
    const bool first = !rows.count({r.order, r.language, r.precision});
    Row& row = rows[{r.order, r.language, r.precision}];
    double& error = building_block(r.function) ? row.other_error : row.rotation_error;
    error = std::max(error, r.max_error);
    row.rms = std::max(row.rms, r.rms_error);
    row.ulps = first ? r.max_ulps : std::max(row.ulps, r.max_ulps);
    row.pass = row.pass && r.pass;
    ++row.functions;
  }
  std::ostringstream out;
  char line[160];
  std::snprintf(line, sizeof line, "%5s  %-5s  %-9s  %9s  %12s  %11s  %9s  %9s  %s\n", "order", "lang", "precision",
                "functions", "rotation err", "other err", "RMS", "max ulps", "result");
  out << line;
  for (const auto& [key, row] : rows) {
    const auto& [order, language, precision] = key;
    const std::string ulps = row.ulps < 0 ? "-" : std::to_string(static_cast<long long>(row.ulps));
    std::snprintf(line, sizeof line, "%5d  %-5s  %-9s  %9d  %12s  %11s  %9.2e  %9s  %s\n", order, language.c_str(),
                  precision.c_str(), row.functions, error_text(row.rotation_error).c_str(), error_text(row.other_error).c_str(),
                  row.rms, ulps.c_str(), row.pass ? "pass" : "FAIL");
    out << line;
  }
  for (const FunctionResult& r : results) {
    if (r.pass) continue;
    std::snprintf(line, sizeof line, "FAIL: order %d, %s %s, %s, coefficient %d (input %d): error %.3g > %.3g%s\n",
                  r.order, r.language.c_str(), r.precision.c_str(), r.function.c_str(), r.worst_index, r.worst_input,
                  r.max_error, r.tolerance, r.max_ulps > r.ulp_limit ? " (or too many ulps from C++ float)" : "");
    out << line;
  }
  for (const std::string& e : errors) out << "ERROR: " << e << "\n";
  return out.str();
}

VerifyReport run_verify(const VerifyOptions& options) {
  VerifyReport report;
  const fs::path generated(options.generated_dir);
  fs::path work = options.work_dir.empty() ? fs::temp_directory_path() / ("zhf-verify-" + std::to_string(::getpid()))
                                           : fs::path(options.work_dir);
  fs::create_directories(work);
  struct Cleanup {
    fs::path path;
    bool keep;
    ~Cleanup() {
      std::error_code ignored;
      if (!keep) fs::remove_all(path, ignored);
    }
  } cleanup{work, options.keep_work_dir || !options.work_dir.empty()};
  const bool want_shaders =
      std::find(options.languages.begin(), options.languages.end(), "glsl") != options.languages.end() ||
      std::find(options.languages.begin(), options.languages.end(), "hlsl") != options.languages.end();
  std::unique_ptr<VulkanDevice> device;
  if (want_shaders) {
    std::string why;
    device = VulkanDevice::open(why);
    if (!device) {
      report.vulkan_missing = true;
      report.errors.push_back("no Vulkan device: " + why + "; GLSL and HLSL kernels were not run");
    } else {
      report.device = device->description();
    }
  }
  std::string compiler = options.compiler;
  if (compiler.empty()) compiler = std::getenv("CXX") ? std::getenv("CXX") : "c++";

  std::vector<int> manifest_orders;
  const auto files = read_manifest(generated, manifest_orders);
  std::vector<int> orders = options.orders;
  if (orders.empty()) orders = files.empty() ? std::vector<int>{2, 3, 4, 5, 6, 7, 8} : manifest_orders;
  auto wanted = [&](const std::string& language) {
    return std::find(options.languages.begin(), options.languages.end(), language) != options.languages.end();
  };
  // The file's functions and zero bands, from the manifest (or generated/'s defaults without one).
  auto entry_for = [&](int order, const std::string& language) -> std::optional<FileEntry> {
    if (files.empty()) {
      FileEntry e;
      e.path = language + "/zhf_order" + std::to_string(order) + (language == "cpp" ? ".h" : language == "glsl" ? ".glsl" : ".hlsli");
      e.functions = default_functions(order, language);
      return e;
    }
    const auto it = files.find({order, language});
    if (it == files.end()) return std::nullopt;
    return it->second;
  };

  for (int order : orders) {
    const std::string o = "order " + std::to_string(order);
    const auto cpp_entry = entry_for(order, "cpp");
    std::optional<FileEntry> any = cpp_entry;
    for (const std::string language : {"glsl", "hlsl"})
      if (!any) any = entry_for(order, language);
    if (!any) {
      report.errors.push_back(o + ": not in " + (generated / "manifest.json").string());
      continue;
    }
    const optimizer::LobeTable table =
        order == 2 ? optimizer::LobeTable{} : optimizer::read_table((generated / "lobes" / ("order_" + std::to_string(order) + ".json")).string());
    const Inputs in = make_inputs(order, options.rotations, table, any->zero_bands);
    const int n = order * order;
    const size_t block = size_t(kMaxChannels) * n * in.count;
    const fs::path dir = work / ("order_" + std::to_string(order));
    fs::create_directories(dir);
    std::vector<double> stream = {double(in.count)};
    for (int v = 0; v < in.count; ++v) {
      stream.insert(stream.end(), in.rotations.begin() + 9 * v, in.rotations.begin() + 9 * v + 9);
      stream.insert(stream.end(), in.axes.begin() + 3 * v, in.axes.begin() + 3 * v + 3);
    }
    const std::vector<double> rotation_stream(stream.begin() + 1, stream.end());
    stream.insert(stream.end(), in.coeffs.begin(), in.coeffs.end());

    // C++: run whenever the file exists; the shaders are compared with its float results.
    std::map<std::string, std::vector<double>> cpp_float;  // by function name
    if (cpp_entry) {
      const std::string tag = o + ", cpp";
      const std::vector<Mode> modes = modes_of(cpp_entry->functions, order, report.errors, tag);
      const auto expected = reference_outputs(in, table, modes);
      write_doubles((dir / "inputs.bin").string(), stream);
      io::write_file_atomically((dir / "harness.cc").string(), cpp_harness(order, modes));
      const fs::path include_dir = (generated / cpp_entry->path).parent_path();
      const std::string compile = compiler + " -std=c++17 -O1 -ffp-contract=off -I'" + include_dir.string() + "' '" +
                                  (dir / "harness.cc").string() + "' -o '" + (dir / "harness").string() + "' > '" +
                                  (dir / "compile.log").string() + "' 2>&1";
      if (run_command(compile) != 0) {
        report.errors.push_back(tag + ": compile failed: " + first_lines((dir / "compile.log").string(), 3));
      } else if (run_command("'" + (dir / "harness").string() + "' '" + (dir / "inputs.bin").string() + "' '" +
                             (dir / "outputs.bin").string() + "'") != 0) {
        report.errors.push_back(tag + ": harness failed to run");
      } else {
        const std::vector<double> all = read_doubles((dir / "outputs.bin").string(), 2 * modes.size() * block);
        for (int p = 0; p < 2; ++p) {
          const std::string precision = p == 0 ? "float" : "double";
          for (size_t m = 0; m < modes.size(); ++m) {
            const std::vector<double> got(all.begin() + (p * modes.size() + m) * block, all.begin() + (p * modes.size() + m + 1) * block);
            if (p == 0) cpp_float[modes[m].function] = got;
            if (wanted("cpp"))
              report.results.push_back(compare(in, conditioning(table, *cpp_entry), modes[m], got, expected[m], "cpp", precision, nullptr));
          }
        }
      }
    }

    for (const std::string& language : {std::string("glsl"), std::string("hlsl")}) {
      if (!wanted(language) || !device) continue;
      const auto entry = entry_for(order, language);
      if (!entry) continue;
      const std::string tag = o + ", " + language;
      if (conditioning(table, *entry).wide_lobes && !device->float64()) {
        report.errors.push_back(tag + ": " + entry->path + " runs its lobe stage in double and " + device->description() +
                                " lacks shaderFloat64; emit it with --lobe-precision float for such devices");
        continue;
      }
      std::vector<Mode> modes = modes_of(entry->functions, order, report.errors, tag);
      modes.erase(std::remove_if(modes.begin(), modes.end(), [](const Mode& m) { return m.kind == Kind::kBatch; }), modes.end());
      if (modes.empty()) continue;
      const auto expected = reference_outputs(in, table, modes);
      std::string kernels;
      try {
        kernels = io::read_text_file((generated / entry->path).string());
      } catch (const std::exception& e) {
        report.errors.push_back(tag + ": " + e.what());
        continue;
      }
      const fs::path source = dir / (language == "glsl" ? "verify.comp" : "verify.hlsl");
      const fs::path spv = dir / (language + ".spv");
      io::write_file_atomically(source.string(), shader_source(language, order, kernels, modes));
      const std::string flags = language == "glsl" ? "-V -S comp" : "-D -e main -S comp -V";
      if (run_command("glslangValidator " + flags + " -o '" + spv.string() + "' '" + source.string() + "' > '" +
                      (dir / (language + "_compile.log")).string() + "' 2>&1") != 0) {
        report.errors.push_back(tag + ": glslangValidator failed: " + first_lines((dir / (language + "_compile.log")).string(), 4));
        continue;
      }
      if (run_command("spirv-val '" + spv.string() + "' > '" + (dir / (language + "_val.log")).string() + "' 2>&1") != 0) {
        report.errors.push_back(tag + ": spirv-val failed: " + first_lines((dir / (language + "_val.log")).string(), 3));
        continue;
      }
      const std::string bytes = io::read_text_file(spv.string());
      std::vector<std::uint32_t> words(bytes.size() / 4);
      std::memcpy(words.data(), bytes.data(), words.size() * 4);
      std::vector<std::vector<std::uint8_t>> buffers(3);
      auto pack = [](const std::vector<double>& values) {
        std::vector<std::uint8_t> out(values.size() * sizeof(float));
        for (size_t i = 0; i < values.size(); ++i) {
          const float f = static_cast<float>(values[i]);
          std::memcpy(&out[i * sizeof(float)], &f, sizeof f);
        }
        return out;
      };
      buffers[0] = pack(rotation_stream);
      buffers[1] = pack(in.coeffs);
      buffers[2].assign(modes.size() * block * sizeof(float), 0);
      const std::uint32_t count = static_cast<std::uint32_t>(in.count);
      try {
        device->run(words, buffers, &count, sizeof count, (static_cast<std::uint32_t>(modes.size()) * count + 63) / 64);
      } catch (const std::exception& e) {
        report.errors.push_back(tag + ": " + e.what());
        continue;
      }
      for (size_t m = 0; m < modes.size(); ++m) {
        std::vector<double> got(block);
        for (size_t k = 0; k < block; ++k) {
          float f;
          std::memcpy(&f, &buffers[2][(m * block + k) * sizeof(float)], sizeof f);
          got[k] = f;
        }
        const auto reference = cpp_float.find(modes[m].function);
        report.results.push_back(compare(in, conditioning(table, *entry), modes[m], got, expected[m], language, "float",
                                         reference == cpp_float.end() ? nullptr : &reference->second));
      }
    }
  }
  return report;
}

}  // namespace zhf::verify
