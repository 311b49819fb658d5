#include "zhf/verify/verify.h"

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include <Eigen/Geometry>

#include "zhf/io/files.h"
#include "zhf/optimizer/lobe_table.h"
#include "zhf/sh/eval.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/verify/vulkan_runner.h"

namespace zhf::verify {
namespace fs = std::filesystem;
namespace {

// What each emitted function is asked to do, in the order the harnesses run them.
enum Mode { kRotate, kTailored, kRgb, kEval, kTranspose, kMultiply, kBatch, kModeCount };
const char* kModeName[kModeCount] = {"rotate", "rotate_signal_tailored", "rotate_rgb", "sh_eval",
                                     "AhatTransposeMultiply", "AhatMultiply", "rotate_batch"};
constexpr int kShaderModes = 6;  // no batch entry point in the shader languages

std::string function_name(Mode mode, int order) { return std::string(kModeName[mode]) + "_order" + std::to_string(order); }
bool has_mode(Mode mode, int order) { return order > 2 || (mode != kTranspose && mode != kMultiply); }

struct Inputs {
  int order = 0;
  int count = 0;
  std::vector<double> rotations;  // 9 per input, row-major
  std::vector<double> coeffs;     // N^2 per input, unit norm
  std::vector<std::string> names; // the extreme inputs' names
};

// The fixed extreme set, then random rotations; the same for every language.
Inputs make_inputs(int order, int random_count, const optimizer::LobeTable& table) {
  Inputs in;
  in.order = order;
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
    for (int i = 0; i < f.size(); ++i) f[i] = normal(rng);
    f.normalize();
    in.coeffs.insert(in.coeffs.end(), f.data(), f.data() + f.size());
    in.names.push_back(name);
  }
  in.count = static_cast<int>(rotations.size());
  return in;
}

// reference[mode][v * 3n + k]; RGB channel c of input v is rotation v applied to the
// coefficients of input (v + c) % count.
std::vector<std::vector<double>> reference_outputs(const Inputs& in, const optimizer::LobeTable& table) {
  const int n = in.order * in.order;
  std::vector<std::vector<double>> ref(kModeCount, std::vector<double>(size_t(3) * n * in.count, 0.0));
  for (int v = 0; v < in.count; ++v) {
    sh::Matrix3 r;
    for (int i = 0; i < 9; ++i) r(i / 3, i % 3) = in.rotations[9 * v + i];
    const sh::BandMatrices bands = sh::ivanic_ruedenberg(r, in.order);
    const size_t base = size_t(3) * n * v;
    for (int c = 0; c < 3; ++c) {
      const Eigen::Map<const Eigen::VectorXd> f(&in.coeffs[size_t(n) * ((v + c) % in.count)], n);
      const Eigen::VectorXd g = sh::apply_band_matrices(bands, f);
      for (int i = 0; i < n; ++i) {
        ref[kRgb][base + c * n + i] = g[i];
        if (c == 0) ref[kRotate][base + i] = ref[kTailored][base + i] = ref[kBatch][base + i] = g[i];
      }
    }
    const double* f = &in.coeffs[size_t(n) * v];
    const double dir[3] = {in.rotations[9 * v], in.rotations[9 * v + 1], in.rotations[9 * v + 2]};
    sh::eval_sh(in.order, dir, &ref[kEval][base]);
    for (int i = 0; i < std::min(n, 4); ++i) ref[kTranspose][base + i] = ref[kMultiply][base + i] = f[i];
    for (const optimizer::TableBand& band : table.bands) {
      const int size = 2 * band.l + 1, b0 = band.l * band.l;
      for (int i = 0; i < size; ++i)
        for (int k = 0; k < size; ++k) {
          ref[kTranspose][base + b0 + i] += band.inverse(k, i) * f[b0 + k];
          ref[kMultiply][base + b0 + i] += band.inverse(i, k) * f[b0 + k];
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

// The C++ harness zhf writes for one order: runs every function in float and double.
std::string cpp_harness(int order) {
  const std::string o = std::to_string(order);
  std::ostringstream s;
  s << "// Generated by zhf verify: runs the emitted order-" << o << " kernels on inputs.bin.\n"
    << "#include <cstdio>\n#include <vector>\n#include \"zhf_order" << o << ".h\"\n\n"
    << "constexpr int kN = " << order * order << ";\n"
    << "template <class T>\nvoid run(int count, const std::vector<double>& rot, const std::vector<double>& co, std::FILE* out) {\n"
    << "  std::vector<double> res(3 * kN * size_t(count));\n"
    << "  T r[9], c[kN], o[kN], c3[3][kN], o3[3][kN];\n"
    << "  for (int mode = 0; mode < 6; ++mode) {\n"
    << "    for (int v = 0; v < count; ++v) {\n"
    << "      for (int i = 0; i < 9; ++i) r[i] = T(rot[9 * v + i]);\n"
    << "      for (int i = 0; i < kN; ++i) c[i] = T(co[kN * v + i]);\n"
    << "      for (int ch = 0; ch < 3; ++ch) for (int i = 0; i < kN; ++i) c3[ch][i] = T(co[kN * ((v + ch) % count) + i]);\n"
    << "      for (int i = 0; i < kN; ++i) o[i] = T(0);\n"
    << "      switch (mode) {\n"
    << "        case 0: zhf::gen::rotate_order" << o << "<T>(r, c, o); break;\n"
    << "        case 1: zhf::gen::rotate_signal_tailored_order" << o << "<T>(r, c, o); break;\n"
    << "        case 2: zhf::gen::rotate_rgb_order" << o << "<T>(r, c3, o3); break;\n"
    << "        case 3: zhf::gen::sh_eval_order" << o << "<T>(r, o); break;\n";
  if (order > 2) {
    s << "        case 4: zhf::gen::AhatTransposeMultiply_order" << o << "<T>(c, o); break;\n"
      << "        case 5: zhf::gen::AhatMultiply_order" << o << "<T>(c, o); break;\n";
  }
  s << "      }\n"
    << "      for (int i = 0; i < kN; ++i) res[3 * kN * size_t(v) + i] = double(o[i]);\n"
    << "      if (mode == 2) for (int ch = 0; ch < 3; ++ch) for (int i = 0; i < kN; ++i) res[3 * kN * size_t(v) + ch * kN + i] = double(o3[ch][i]);\n"
    << "    }\n"
    << "    std::fwrite(res.data(), sizeof(double), res.size(), out);\n"
    << "  }\n"
    << "  // Batch: structure of arrays over all inputs.\n"
    << "  std::vector<T> br(9 * size_t(count)), bc(kN * size_t(count)), bo(kN * size_t(count));\n"
    << "  for (int v = 0; v < count; ++v) {\n"
    << "    for (int i = 0; i < 9; ++i) br[i * size_t(count) + v] = T(rot[9 * v + i]);\n"
    << "    for (int i = 0; i < kN; ++i) bc[i * size_t(count) + v] = T(co[kN * v + i]);\n"
    << "  }\n"
    << "  zhf::gen::rotate_batch_order" << o << "<T>(count, br.data(), bc.data(), bo.data());\n"
    << "  for (int v = 0; v < count; ++v) for (int i = 0; i < kN; ++i) res[3 * kN * size_t(v) + i] = double(bo[i * size_t(count) + v]);\n"
    << "  std::fwrite(res.data(), sizeof(double), res.size(), out);\n"
    << "}\n\n"
    << "int main(int argc, char** argv) {\n"
    << "  if (argc != 3) return 2;\n"
    << "  std::FILE* in = std::fopen(argv[1], \"rb\");\n"
    << "  double header = 0;\n"
    << "  if (!in || std::fread(&header, sizeof header, 1, in) != 1) return 3;\n"
    << "  const int count = int(header);\n"
    << "  std::vector<double> rot(9 * size_t(count)), co(kN * size_t(count));\n"
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

// Compute-shader wrappers: invocation i runs function (i / count) on input (i % count).
std::string shader_source(const std::string& language, int order, const std::string& kernels) {
  const std::string o = std::to_string(order), n = std::to_string(order * order);
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
  const std::string vec3 = glsl ? "vec3" : "float3";
  if (glsl) {
    s << "void main() {\n  uint i = gl_GlobalInvocationID.x;\n";
  } else {
    s << "[numthreads(64, 1, 1)]\nvoid main(uint3 id : SV_DispatchThreadID) {\n  uint i = id.x;\n";
  }
  s << "  if (i >= " << kShaderModes << "u * params.count) return;\n"
    << "  uint v = i % params.count;\n  uint mode = i / params.count;\n"
    << "  float r[9];\n  float c[" << n << "];\n  float o[" << n << "];\n"
    << "  " << vec3 << " c3[" << n << "];\n  " << vec3 << " o3[" << n << "];\n"
    << "  for (int k = 0; k < 9; ++k) r[k] = rotations[9u * v + uint(k)];\n"
    << "  for (int k = 0; k < " << n << "; ++k) {\n"
    << "    c[k] = coefficients[" << n << "u * v + uint(k)];\n"
    << "    c3[k] = " << vec3 << "(c[k], coefficients[" << n << "u * ((v + 1u) % params.count) + uint(k)], coefficients["
    << n << "u * ((v + 2u) % params.count) + uint(k)]);\n"
    << "    o[k] = 0.0;\n    o3[k] = " << vec3 << "(0.0, 0.0, 0.0);\n  }\n"
    << "  if (mode == 0u) rotate_order" << o << "(r, c, o);\n"
    << "  if (mode == 1u) rotate_signal_tailored_order" << o << "(r, c, o);\n"
    << "  if (mode == 2u) rotate_rgb_order" << o << "(r, c3, o3);\n"
    << "  if (mode == 3u) { float d[3]; d[0] = r[0]; d[1] = r[1]; d[2] = r[2]; sh_eval_order" << o << "(d, o); }\n";
  if (order > 2) {
    s << "  if (mode == 4u) AhatTransposeMultiply_order" << o << "(c, o);\n"
      << "  if (mode == 5u) AhatMultiply_order" << o << "(c, o);\n";
  }
  s << "  uint base = (mode * params.count + v) * " << 3 * order * order << "u;\n"
    << "  for (int k = 0; k < " << n << "; ++k) {\n"
    << "    if (mode == 2u) {\n"
    << "      results[base + uint(k)] = o3[k].x;\n"
    << "      results[base + " << n << "u + uint(k)] = o3[k].y;\n"
    << "      results[base + " << 2 * order * order << "u + uint(k)] = o3[k].z;\n"
    << "    } else {\n"
    << "      results[base + uint(k)] = o[k];\n"
    << "    }\n  }\n}\n";
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

double tolerance_for(Mode mode, const std::string& precision, int order, double worst_condition) {
  if (precision == "double") return kDoubleTolerance;
  if (mode == kEval) return kFloatEvaluationTolerance;
  if (mode == kTranspose || mode == kMultiply) return kFloatSparseTolerance;
  return float_rotation_tolerance(order, worst_condition);
}

FunctionResult compare(const Inputs& in, double worst_condition, Mode mode, const std::vector<double>& got,
                       const std::vector<double>& expected, const std::string& language, const std::string& precision,
                       const std::vector<double>* cpp_float) {
  FunctionResult r;
  r.ulp_limit = language == "hlsl" ? hlsl_ulp_limit(in.order, worst_condition) : kGlslUlpLimit;
  r.order = in.order;
  r.language = language;
  r.precision = precision;
  r.function = function_name(mode, in.order);
  r.tolerance = tolerance_for(mode, precision, in.order, worst_condition);
  const int n = in.order * in.order;
  const int lanes = mode == kRgb ? 3 * n : n;
  double sum = 0;
  size_t terms = 0;
  for (int v = 0; v < in.count; ++v)
    for (int k = 0; k < lanes; ++k) {
      const size_t at = size_t(3) * n * v + k;
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
  struct Row {
    double max_error = 0, rms = 0, ulps = 0;
    bool pass = true;
    int functions = 0;
  };
  std::map<std::tuple<int, std::string, std::string>, Row> rows;
  for (const FunctionResult& r : results) {
    Row& row = rows[{r.order, r.language, r.precision}];
    row.max_error = std::max(row.max_error, r.max_error);
    row.rms = std::max(row.rms, r.rms_error);
    row.ulps = std::max(row.ulps, r.max_ulps);
    row.pass = row.pass && r.pass;
    ++row.functions;
  }
  std::ostringstream out;
  char line[160];
  std::snprintf(line, sizeof line, "%5s  %-5s  %-9s  %9s  %9s  %9s  %9s  %s\n", "order", "lang", "precision",
                "functions", "max err", "RMS", "max ulps", "result");
  out << line;
  for (const auto& [key, row] : rows) {
    const auto& [order, language, precision] = key;
    const std::string ulps = language == "cpp" ? "-" : std::to_string(static_cast<long long>(row.ulps));
    std::snprintf(line, sizeof line, "%5d  %-5s  %-9s  %9d  %9.2e  %9.2e  %9s  %s\n", order, language.c_str(),
                  precision.c_str(), row.functions, row.max_error, row.rms, ulps.c_str(), row.pass ? "pass" : "FAIL");
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

  for (int order : options.orders) {
    const optimizer::LobeTable table =
        order == 2 ? optimizer::LobeTable{} : optimizer::read_table((generated / "lobes" / ("order_" + std::to_string(order) + ".json")).string());
    const Inputs in = make_inputs(order, options.rotations, table);
    const auto expected = reference_outputs(in, table);
    const int n = order * order;
    const size_t block = size_t(3) * n * in.count;
    const fs::path dir = work / ("order_" + std::to_string(order));
    fs::create_directories(dir);

    // C++: always run, the shaders are compared with its float results.
    std::vector<double> header = {double(in.count)};
    header.insert(header.end(), in.rotations.begin(), in.rotations.end());
    header.insert(header.end(), in.coeffs.begin(), in.coeffs.end());
    write_doubles((dir / "inputs.bin").string(), header);
    io::write_file_atomically((dir / "harness.cc").string(), cpp_harness(order));
    const std::string compile = compiler + " -std=c++17 -O1 -ffp-contract=off -I'" + (generated / "cpp").string() + "' '" +
                                (dir / "harness.cc").string() + "' -o '" + (dir / "harness").string() + "' > '" +
                                (dir / "compile.log").string() + "' 2>&1";
    std::vector<std::vector<double>> cpp_float(kModeCount);
    if (run_command(compile) != 0) {
      report.errors.push_back("order " + std::to_string(order) + ", cpp: compile failed: " + first_lines((dir / "compile.log").string(), 3));
    } else if (run_command("'" + (dir / "harness").string() + "' '" + (dir / "inputs.bin").string() + "' '" +
                           (dir / "outputs.bin").string() + "'") != 0) {
      report.errors.push_back("order " + std::to_string(order) + ", cpp: harness failed to run");
    } else {
      const std::vector<double> all = read_doubles((dir / "outputs.bin").string(), 2 * kModeCount * block);
      for (int p = 0; p < 2; ++p) {
        const std::string precision = p == 0 ? "float" : "double";
        for (int m = 0; m < kModeCount; ++m) {
          const std::vector<double> got(all.begin() + (p * kModeCount + m) * block, all.begin() + (p * kModeCount + m + 1) * block);
          if (p == 0) cpp_float[m] = got;
          if (!has_mode(Mode(m), order)) continue;
          if (std::find(options.languages.begin(), options.languages.end(), "cpp") != options.languages.end())
            report.results.push_back(compare(in, table.worst_condition(), Mode(m), got, expected[m], "cpp", precision, nullptr));
        }
      }
    }

    for (const std::string& language : {std::string("glsl"), std::string("hlsl")}) {
      if (std::find(options.languages.begin(), options.languages.end(), language) == options.languages.end() || !device)
        continue;
      const std::string tag = "order " + std::to_string(order) + ", " + language;
      const fs::path kernel_file = generated / language / ("zhf_order" + std::to_string(order) + (language == "glsl" ? ".glsl" : ".hlsli"));
      std::string kernels;
      try {
        kernels = io::read_text_file(kernel_file.string());
      } catch (const std::exception& e) {
        report.errors.push_back(tag + ": " + e.what());
        continue;
      }
      const fs::path source = dir / (language == "glsl" ? "verify.comp" : "verify.hlsl");
      const fs::path spv = dir / (language + ".spv");
      io::write_file_atomically(source.string(), shader_source(language, order, kernels));
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
      buffers[0] = pack(in.rotations);
      buffers[1] = pack(in.coeffs);
      buffers[2].assign(kShaderModes * block * sizeof(float), 0);
      const std::uint32_t count = static_cast<std::uint32_t>(in.count);
      try {
        device->run(words, buffers, &count, sizeof count, (kShaderModes * count + 63) / 64);
      } catch (const std::exception& e) {
        report.errors.push_back(tag + ": " + e.what());
        continue;
      }
      for (int m = 0; m < kShaderModes; ++m) {
        if (!has_mode(Mode(m), order)) continue;
        std::vector<double> got(block);
        for (size_t k = 0; k < block; ++k) {
          float f;
          std::memcpy(&f, &buffers[2][(m * block + k) * sizeof(float)], sizeof f);
          got[k] = f;
        }
        report.results.push_back(compare(in, table.worst_condition(), Mode(m), got, expected[m], language, "float",
                                         cpp_float[m].empty() ? nullptr : &cpp_float[m]));
      }
    }
  }
  return report;
}

}  // namespace zhf::verify
