#include "zhf/sh/random.h"
#include "zhf/verify/needlets.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <random>
#include <sstream>

#include "runner.h"
#include "runners/shader_runner.h"
#include "vulkan_device.h"
#include "zhf/io/files.h"
#include "zhf/io/private_dir.h"
#include "zhf/io/process.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"

namespace zhf::verify {
namespace {

using codegen::Language;

struct Case {
  std::vector<double> beta;                      // of a random unit-norm signal
  std::vector<frames::Point> directions;
  std::vector<double> mirror, exact, magnitude;  // per direction
};

Case make_case(const frames::NeedletFrame& frame, const codegen::NeedletLutOptions& lut, int directions) {
  std::mt19937_64 rng(2024);
  sh::Normal<> normal(0, 1);
  std::vector<double> f(runtime::coefficient_count(frame.band_limit() + 1));
  double norm = 0;
  for (double& c : f) {
    c = normal(rng);
    norm += c * c;
  }
  for (double& c : f) c /= std::sqrt(norm);
  Case c;
  c.beta = frame.analyze(f);
  std::vector<frames::UniformTable> tables;
  for (int a = 0; a < static_cast<int>(frame.levels().size()); ++a)
    tables.emplace_back([&](double t) { return frame.kernel(a, t); }, lut.table_size);
  for (int i = 0; i < directions; ++i) {
    frames::Point x{normal(rng), normal(rng), normal(rng)};
    const double r = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    for (double& v : x) v /= r;
    // The point as the shaders see it: in float.
    for (double& v : x) v = static_cast<float>(v);
    c.directions.push_back(x);
    double mirror = 0, magnitude = 0;
    for (int a = 0; a < static_cast<int>(frame.levels().size()); ++a) {
      const frames::NeedletLevel& level = frame.levels()[a];
      for (std::size_t k = 0; k < level.cubature.points.size(); ++k) {
        const frames::Point& p = level.cubature.points[k];
        const double term = c.beta[level.offset + k] * std::sqrt(level.cubature.weights[k]) *
                            tables[a](x[0] * p[0] + x[1] * p[1] + x[2] * p[2], lut.interpolation);
        mirror += term;
        magnitude += std::abs(term);
      }
    }
    c.mirror.push_back(mirror);
    c.magnitude.push_back(magnitude);
    c.exact.push_back(frame.evaluate(c.beta, x));
  }
  return c;
}

std::vector<double> flat_directions(const Case& c) {
  std::vector<double> out;
  for (const frames::Point& p : c.directions) out.insert(out.end(), p.begin(), p.end());
  return out;
}

std::vector<double> run_cpp(const std::string& dir, const std::string& header, const Case& c, const std::string& prefix,
                            const std::vector<std::string>& compiler) {
  std::ostringstream h;
  h << "#include <cstdio>\n#include <vector>\n#include \"" << header << "\"\n"
    << "int main(int argc, char** argv) {\n"
    << "  if (argc != 3) return 2;\n"
    << "  std::FILE* in = std::fopen(argv[1], \"rb\");\n"
    << "  if (!in) return 3;\n"
    << "  std::vector<float> beta(" << c.beta.size() << "), x(" << 3 * c.directions.size() << "), out(" << c.directions.size() << ");\n"
    << "  if (std::fread(beta.data(), 4, beta.size(), in) != beta.size() || std::fread(x.data(), 4, x.size(), in) != x.size()) return 3;\n"
    << "  std::fclose(in);\n"
    << "  for (std::size_t i = 0; i < out.size(); ++i) out[i] = " << prefix << "_eval(beta.data(), &x[3 * i]);\n"
    << "  std::FILE* o = std::fopen(argv[2], \"wb\");\n"
    << "  if (!o || std::fwrite(out.data(), 4, out.size(), o) != out.size()) return 4;\n"
    << "  return std::fclose(o) == 0 ? 0 : 4;\n}\n";
  io::write_file_atomically(dir + "/harness.cc", h.str());
  std::vector<double> stream = c.beta;
  const std::vector<double> x = flat_directions(c);
  stream.insert(stream.end(), x.begin(), x.end());
  const std::vector<std::uint8_t> bytes = as_floats(stream);
  io::write_file_atomically(dir + "/inputs.bin", std::string(bytes.begin(), bytes.end()));
  std::vector<std::string> compile = compiler;
  compile.insert(compile.end(), kHarnessFlags.begin(), kHarnessFlags.end());
  for (const std::string& arg : {"-I" + dir, dir + "/harness.cc", std::string("-o"), dir + "/harness"}) compile.push_back(arg);
  if (!io::run_process(compile, dir + "/compile.log").ok()) throw RunFailure("compile failed: " + io::log_excerpt(dir + "/compile.log", 3));
  if (!io::run_process({dir + "/harness", dir + "/inputs.bin", dir + "/outputs.bin"}, dir + "/run.log").ok())
    throw RunFailure("the harness failed to run: " + io::log_excerpt(dir + "/run.log", 3));
  const std::string out = io::read_text_file(dir + "/outputs.bin", c.directions.size() * sizeof(float));
  if (out.size() != c.directions.size() * sizeof(float)) throw RunFailure("the harness wrote " + std::to_string(out.size()) + " bytes");
  std::vector<double> got(c.directions.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    float f;
    std::memcpy(&f, &out[i * sizeof f], sizeof f);
    got[i] = f;
  }
  return got;
}

// The evaluator's data buffer goes at binding kDataBinding, after the wrapper's three.
constexpr int kDataBinding = 3;

std::string shader_wrapper(ShaderFront front, const std::string& kernels, const std::string& prefix, std::size_t count) {
  std::ostringstream s;
  const std::string n = std::to_string(count), call = prefix + "_eval(beta, x)";
  switch (front) {
    case ShaderFront::kGlsl:
      s << "#version 450\nlayout(local_size_x = 64) in;\n"
        << "layout(std430, set = 0, binding = 0) readonly buffer Beta { float beta_in[]; };\n"
        << "layout(std430, set = 0, binding = 1) readonly buffer Directions { float directions[]; };\n"
        << "layout(std430, set = 0, binding = 2) writeonly buffer Results { float results[]; };\n"
        << "layout(push_constant) uniform Params { uint count; } params;\n\n"
        << kernels << "\nvoid main() {\n  uint i = gl_GlobalInvocationID.x;\n"
        << "  if (i >= params.count) return;\n"
        << "  float beta[" << n << "];\n  for (int k = 0; k < " << n << "; ++k) beta[k] = beta_in[k];\n"
        << "  vec3 x = vec3(directions[3u * i], directions[3u * i + 1u], directions[3u * i + 2u]);\n"
        << "  results[i] = " << call << ";\n}\n";
      break;
    case ShaderFront::kHlsl:
      s << "struct Params { uint count; };\n[[vk::push_constant]] ConstantBuffer<Params> params;\n"
        << "[[vk::binding(0, 0)]] StructuredBuffer<float> beta_in;\n"
        << "[[vk::binding(1, 0)]] StructuredBuffer<float> directions;\n"
        << "[[vk::binding(2, 0)]] RWStructuredBuffer<float> results;\n\n"
        << kernels << "\n[numthreads(64, 1, 1)]\nvoid main(uint3 id : SV_DispatchThreadID) {\n  uint i = id.x;\n"
        << "  if (i >= params.count) return;\n"
        << "  float beta[" << n << "];\n  for (int k = 0; k < " << n << "; ++k) beta[k] = beta_in[k];\n"
        << "  float3 x = float3(directions[3u * i], directions[3u * i + 1u], directions[3u * i + 2u]);\n"
        << "  results[i] = " << call << ";\n}\n";
      break;
    case ShaderFront::kWgsl:
      s << "struct Params { count: u32 }\nvar<immediate> params: Params;\n"
        << "@group(0) @binding(0) var<storage, read> beta_in: array<f32>;\n"
        << "@group(0) @binding(1) var<storage, read> directions: array<f32>;\n"
        << "@group(0) @binding(2) var<storage, read_write> results: array<f32>;\n\n"
        << kernels << "\n@compute @workgroup_size(64)\nfn main(@builtin(global_invocation_id) id: vec3<u32>) {\n  let i = id.x;\n"
        << "  if (i >= params.count) { return; }\n"
        << "  var beta: array<f32, " << n << ">;\n  for (var k = 0u; k < " << n << "u; k++) { beta[k] = beta_in[k]; }\n"
        << "  let x = vec3<f32>(directions[3u * i], directions[3u * i + 1u], directions[3u * i + 2u]);\n"
        << "  results[i] = " << call << ";\n}\n";
      break;
  }
  return s.str();
}

ShaderDialect dialect(Language language) {
  return language == Language::kGlsl ? glsl_dialect() : language == Language::kHlsl ? hlsl_dialect() : wgsl_dialect();
}

std::vector<double> run_shader(Language language, const std::string& dir, const std::string& kernels, const Case& c, const std::string& prefix,
                               const std::vector<float>& data, VulkanDevice& device, const std::string& naga_wasm) {
  const ShaderDialect d = dialect(language);
  const std::vector<std::uint32_t> words = compile_spirv(d, dir, shader_wrapper(d.front, kernels, prefix, c.beta.size()), naga_wasm);
  std::vector<std::vector<std::uint8_t>> buffers = {as_floats(c.beta), as_floats(flat_directions(c)),
                                                     std::vector<std::uint8_t>(c.directions.size() * sizeof(float), 0),
                                                     std::vector<std::uint8_t>(data.size() * sizeof(float))};
  std::memcpy(buffers[3].data(), data.data(), buffers[3].size());
  const std::uint32_t count = static_cast<std::uint32_t>(c.directions.size());
  try {
    device.run(words, buffers, &count, sizeof count, (count + 63) / 64);
  } catch (const std::exception& e) {
    throw RunFailure(e.what());
  }
  std::vector<double> got(count);
  for (std::size_t i = 0; i < got.size(); ++i) {
    float f;
    std::memcpy(&f, &buffers[2][i * sizeof f], sizeof f);
    got[i] = f;
  }
  return got;
}

}  // namespace

std::vector<NeedletLutResult> verify_needlet_lut(const frames::NeedletFrame& frame, const codegen::NeedletLutOptions& requested,
                                                 const NeedletLutVerify& options) {
  codegen::NeedletLutOptions lut = requested;  // the shaders' data buffer where the wrapper leaves room
  lut.storage_set = 0;
  lut.storage_binding = kDataBinding;
  const Case c = make_case(frame, lut, options.directions);
  double table_error = 0, peak = 0, magnitude = 0;
  for (std::size_t i = 0; i < c.exact.size(); ++i) {
    table_error = std::max(table_error, std::abs(c.mirror[i] - c.exact[i]));
    peak = std::max(peak, std::abs(c.exact[i]));
    magnitude = std::max(magnitude, c.magnitude[i]);
  }
  table_error /= peak;
  const io::PrivateDir work("zhf-needlets");
  std::unique_ptr<VulkanDevice> device;
  std::string no_device;
  std::vector<NeedletLutResult> results;
  for (Language language : options.languages) {
    if (options.checkpoint) options.checkpoint(results.size(), options.languages.size());
    NeedletLutResult r;
    r.language = codegen::language_name(language);
    r.table_error = table_error;
    try {
      const codegen::EmittedFile file = codegen::emit_needlet_lut(frame, language, lut);
      const std::string dir = work.path() + "/" + r.language;
      std::filesystem::create_directories(dir);
      io::write_file_atomically(dir + "/" + file.file_name, file.text);
      std::vector<double> got;
      if (language == Language::kCpp) {
        got = run_cpp(dir, file.file_name, c, lut.prefix, compiler_argv(options.compiler));
      } else {
        if (!device && no_device.empty()) device = VulkanDevice::open(no_device);
        if (!device) throw RunFailure("no Vulkan device: " + no_device);
        got = run_shader(language, dir, file.text, c, lut.prefix, codegen::needlet_lut_data(frame, lut.table_size), *device, options.naga_wasm);
      }
      for (std::size_t i = 0; i < got.size(); ++i) {
        const double error = std::abs(got[i] - c.mirror[i]) / magnitude;
        r.vs_mirror = std::isfinite(error) ? std::max(r.vs_mirror, error) : INFINITY;
      }
      r.pass = r.vs_mirror <= zhf::tolerance::kNeedletLutFloat;
    } catch (const RunFailure& e) {
      r.error = e.what();
    }
    results.push_back(r);
  }
  if (options.checkpoint) options.checkpoint(results.size(), options.languages.size());
  return results;
}

}  // namespace zhf::verify
