#include "shader_runner.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <set>
#include <sstream>
#include <utility>

#include "../vulkan_device.h"
#include "zhf/io/files.h"
#include "zhf/io/limits.h"
#include "zhf/io/process.h"
#include "zhf/runtime/limits.h"
#include "zhf/verify/limits.h"

namespace zhf::verify {
namespace {

using codegen::KernelKind;

// The call for one mode: single-channel calls use c1/z1/o1, multi-channel ones the vector arrays
// cvW/zvW/ovW of their width W.
std::string shader_call(const Mode& m, int order) {
  const std::string w = std::to_string(m.channels);
  const bool multi = m.channels > 1;
  const std::string c = multi ? "cv" + w : "c1", o = multi ? "ov" + w : "o1", z = multi ? "zv" + w : "z1";
  switch (m.kind) {
    case KernelKind::kRotate:
    case KernelKind::kSignalTailored: return m.function + "(r, " + c + ", " + o + ");";
    case KernelKind::kShEval: return "{ float d[3]; d[0] = r[0]; d[1] = r[1]; d[2] = r[2]; " + m.function + "(d, o1); }";
    case KernelKind::kLobeWeights:
    case KernelKind::kFromSamples: return m.function + "(c1, o1);";
    case KernelKind::kApplyMatrices:
      return "rotation_matrices_order" + std::to_string(order) + "(r, mats); " + m.function + "(mats, " + c + ", " + o + ");";
    case KernelKind::kZonal: return m.function + "(r, axis, " + z + ", " + o + ");";
    case KernelKind::kProduct: return m.function + "(c[0], c[1], o1);";
    case KernelKind::kSquare: return m.function + "(c1, o1);";
    case KernelKind::kShade: return "float s[1]; " + m.function + "(r, c[0], c[1], s); o1[0] = s[0];";
    case KernelKind::kShadeLobes:
      return "float lobes[" + std::to_string(order * order) + "]; float s[1]; lobe_weights_order" + std::to_string(order) +
             "(c[0], lobes); " + m.function + "(r, lobes, c[1], s); o1[0] = s[0];";
    case KernelKind::kBatch:
    case KernelKind::kRotationMatrices: break;
  }
  return "";
}

// The same calls in WGSL: arrays by value, outputs through pointers.
std::string wgsl_call(const Mode& m, int order) {
  const std::string w = std::to_string(m.channels), ns = std::to_string(order * order);
  const bool multi = m.channels > 1;
  const std::string c = multi ? "cv" + w : "c1", o = multi ? "&ov" + w : "&o1", z = multi ? "zv" + w : "z1";
  switch (m.kind) {
    case KernelKind::kRotate:
    case KernelKind::kSignalTailored: return m.function + "(r, " + c + ", " + o + ");";
    case KernelKind::kShEval: return m.function + "(array<f32, 3>(r[0], r[1], r[2]), &o1);";
    case KernelKind::kLobeWeights:
    case KernelKind::kFromSamples: return m.function + "(c1, &o1);";
    case KernelKind::kApplyMatrices:
      return "rotation_matrices_order" + std::to_string(order) + "(r, &mats); " + m.function + "(mats, " + c + ", " + o + ");";
    case KernelKind::kZonal: return m.function + "(r, axis, " + z + ", " + o + ");";
    case KernelKind::kProduct: return m.function + "(c[0], c[1], &o1);";
    case KernelKind::kSquare: return m.function + "(c1, &o1);";
    case KernelKind::kShade: return "var s: array<f32, 1>; " + m.function + "(r, c[0], c[1], &s); o1[0] = s[0];";
    case KernelKind::kShadeLobes:
      return "var lobes: array<f32, " + ns + ">; var s: array<f32, 1>; lobe_weights_order" + std::to_string(order) +
             "(c[0], &lobes); " + m.function + "(r, lobes, c[1], &s); o1[0] = s[0];";
    case KernelKind::kBatch:
    case KernelKind::kRotationMatrices: break;
  }
  return "";
}

// The modes of one channel width, as a condition on the invocation's mode.
std::string modes_of_width(const std::vector<Mode>& modes, int width) {
  std::string s;
  for (size_t k = 0; k < modes.size(); ++k)
    if (modes[k].channels == width) s += (s.empty() ? "" : " || ") + std::string("mode == ") + std::to_string(k) + "u";
  return s;
}

}  // namespace

std::string wgsl_wrapper(int order, const std::string& kernels, const std::vector<Mode>& modes) {
  const int n = order * order;
  const std::string ns = std::to_string(n), no = std::to_string(order), block = std::to_string(kMaxChannels * n);
  const std::string stride = std::to_string(kRotationStride);
  std::set<int> widths;
  for (const Mode& m : modes)
    if (m.channels > 1) widths.insert(m.channels);
  auto vec = [](int w) { return "vec" + std::to_string(w) + "<f32>"; };
  std::ostringstream s;
  // Core WebGPU (no immediates): the count is the rotations' length over their stride.
  s << "@group(0) @binding(0) var<storage, read> rotations: array<f32>;\n"
    << "@group(0) @binding(1) var<storage, read> coefficients: array<f32>;\n"
    << "@group(0) @binding(2) var<storage, read_write> results: array<f32>;\n\n"
    << kernels << "\n"
    << "@compute @workgroup_size(64)\nfn main(@builtin(global_invocation_id) id: vec3<u32>) {\n"
    << "  let count = arrayLength(&rotations) / " << stride << "u;\n"
    << "  let i = id.x;\n  if (i >= " << modes.size() << "u * count) { return; }\n"
    << "  let v = i % count;\n  let mode = i / count;\n"
    << "  var r: array<f32, 9>;\n  var axis: array<f32, 3>;\n"
    << "  var c: array<array<f32, " << ns << ">, 4>;\n  var z: array<array<f32, " << no << ">, 4>;\n"
    << "  var c1: array<f32, " << ns << ">;\n  var z1: array<f32, " << no << ">;\n  var o1: array<f32, " << ns << ">;\n"
    << "  var mats: array<f32, " << std::max(1, dense_size(order)) << ">;\n";
  for (int w : widths)
    s << "  var cv" << w << ": array<" << vec(w) << ", " << ns << ">;\n  var zv" << w << ": array<" << vec(w) << ", " << no
      << ">;\n  var ov" << w << ": array<" << vec(w) << ", " << ns << ">;\n";
  s << "  for (var k = 0u; k < 9u; k++) { r[k] = rotations[" << stride << "u * v + k]; }\n"
    << "  for (var k = 0u; k < 3u; k++) { axis[k] = rotations[" << stride << "u * v + 9u + k]; }\n"
    << "  for (var ch = 0u; ch < 4u; ch++) {\n"
    << "    for (var k = 0u; k < " << ns << "u; k++) { c[ch][k] = coefficients[" << ns << "u * ((v + ch) % count) + k]; }\n"
    << "    for (var k = 0u; k < " << no << "u; k++) { z[ch][k] = c[ch][k]; }\n"
    << "  }\n"
    << "  for (var k = 0u; k < " << ns << "u; k++) { c1[k] = c[0][k]; o1[k] = 0.0; }\n"
    << "  for (var k = 0u; k < " << no << "u; k++) { z1[k] = z[0][k]; }\n";
  for (int w : widths) {
    const std::string args = "c[0][k], c[1][k], c[2][k]" + std::string(w == 4 ? ", c[3][k]" : "");
    const std::string zargs = "z[0][k], z[1][k], z[2][k]" + std::string(w == 4 ? ", z[3][k]" : "");
    s << "  for (var k = 0u; k < " << ns << "u; k++) { cv" << w << "[k] = " << vec(w) << "(" << args << "); ov" << w << "[k] = "
      << vec(w) << "(0.0); }\n"
      << "  for (var k = 0u; k < " << no << "u; k++) { zv" << w << "[k] = " << vec(w) << "(" << zargs << "); }\n";
  }
  for (size_t k = 0; k < modes.size(); ++k) s << "  if (mode == " << k << "u) { " << wgsl_call(modes[k], order) << " }\n";
  s << "  let base = (mode * count + v) * " << block << "u;\n"
    << "  for (var k = 0u; k < " << ns << "u; k++) {\n"
    << "    results[base + k] = o1[k];\n";
  for (int w : widths) {
    s << "    if (" << modes_of_width(modes, w) << ") {\n";
    for (int ch = 0; ch < w; ++ch) s << "      results[base + " << ch * n << "u + k] = ov" << w << "[k]." << "xyzw"[ch] << ";\n";
    s << "    }\n";
  }
  s << "  }\n}\n";
  return s.str();
}

namespace {

std::string wrapper(bool glsl, int order, const std::string& kernels, const std::vector<Mode>& modes) {
  const int n = order * order;
  const std::string ns = std::to_string(n), block = std::to_string(kMaxChannels * n);
  std::ostringstream s;
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
  // Multi-channel calls of one width share vector arrays; every width present gets its own.
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
    const std::string args = "c[0][k], c[1][k], c[2][k]" + std::string(w == 4 ? ", c[3][k]" : "");
    const std::string zargs = "z[0][k], z[1][k], z[2][k]" + std::string(w == 4 ? ", z[3][k]" : "");
    s << "  for (int k = 0; k < " << ns << "; ++k) { cv" << w << "[k] = " << vec(w) << "(" << args << "); ov" << w << "[k] = "
      << vec(w) << "(0.0" << std::string(w == 4 ? ", 0.0, 0.0, 0.0" : ", 0.0, 0.0") << "); }\n"
      << "  for (int k = 0; k < " << order << "; ++k) zv" << w << "[k] = " << vec(w) << "(" << zargs << ");\n";
  }
  for (size_t k = 0; k < modes.size(); ++k) s << "  if (mode == " << k << "u) { " << shader_call(modes[k], order) << " }\n";
  s << "  uint base = (mode * params.count + v) * " << block << "u;\n"
    << "  for (int k = 0; k < " << ns << "; ++k) {\n"
    << "    results[base + uint(k)] = o1[k];\n";
  for (int w : widths) {
    s << "    if (" << modes_of_width(modes, w) << ") {\n";
    for (int ch = 0; ch < w; ++ch) s << "      results[base + " << ch * n << "u + uint(k)] = ov" << w << "[k]." << "xyzw"[ch] << ";\n";
    s << "    }\n";
  }
  s << "  }\n}\n";
  return s.str();
}

class ShaderRunner : public Runner {
 public:
  explicit ShaderRunner(ShaderDialect dialect) : d_(std::move(dialect)) {}
  bool needs_vulkan() const override { return true; }
  bool runs(const Mode& mode) const override { return mode.kind != KernelKind::kBatch && !mode.lanes; }

  RunOutputs run(const RunRequest& r) const override {
    const Inputs& in = *r.inputs;
    const std::string kernels = io::read_text_file(r.kernel_file, runtime::kMaxTableBytes);
    const std::vector<std::uint32_t> words =
        compile_spirv(d_, r.work_dir,
                      d_.front == ShaderFront::kWgsl ? wgsl_wrapper(r.order, kernels, r.modes)
                                                     : wrapper(d_.front == ShaderFront::kGlsl, r.order, kernels, r.modes),
                      r.naga_wasm);
    const size_t block = size_t(kMaxChannels) * r.order * r.order * in.count;
    std::vector<std::vector<std::uint8_t>> buffers = {as_floats(in.rotation_stream()), as_floats(in.coeffs),
                                                       std::vector<std::uint8_t>(r.modes.size() * block * sizeof(float), 0)};
    const std::uint32_t count = static_cast<std::uint32_t>(in.count);
    try {
      r.device->run(words, buffers, &count, sizeof count, (static_cast<std::uint32_t>(r.modes.size()) * count + 63) / 64);
    } catch (const std::exception& e) {
      throw RunFailure(e.what());
    }
    RunOutputs out;
    out.precisions = {"float"};
    out.outputs.resize(1);
    for (size_t m = 0; m < r.modes.size(); ++m) {
      std::vector<double> got(block);
      for (size_t k = 0; k < block; ++k) {
        float f;
        std::memcpy(&f, &buffers[2][(m * block + k) * sizeof(float)], sizeof f);
        got[k] = f;
      }
      out.outputs[0].push_back(std::move(got));
    }
    return out;
  }

 private:
  ShaderDialect d_;
};

}  // namespace

std::vector<std::uint8_t> as_floats(const std::vector<double>& values) {
  std::vector<std::uint8_t> out(values.size() * sizeof(float));
  for (size_t i = 0; i < values.size(); ++i) {
    const float f = static_cast<float>(values[i]);
    std::memcpy(&out[i * sizeof(float)], &f, sizeof f);
  }
  return out;
}

ShaderDialect glsl_dialect() { return {ShaderFront::kGlsl, "verify.comp", {"-V", "-S", "comp"}}; }
// HLSL: glslangValidator's HLSL front end, entry main, compute stage; push constants as
// [[vk::push_constant]] ConstantBuffer<T>.
ShaderDialect hlsl_dialect() { return {ShaderFront::kHlsl, "verify.hlsl", {"-D", "-e", "main", "-S", "comp", "-V"}}; }
// WGSL: naga's front end (the wrapper takes no push constants: core WebGPU).
ShaderDialect wgsl_dialect() { return {ShaderFront::kWgsl, "verify.wgsl", {}}; }

namespace {

// WGSL to SPIR-V through naga-wasm: node <this> <package dir> <in.wgsl> <out.spv>; naga's own
// message on stderr and exit 1 when it refuses the source.
constexpr const char* kNagaScript = R"(import { readFileSync, writeFileSync } from "node:fs";
import { pathToFileURL } from "node:url";
const [pkg, input, output] = process.argv.slice(2);
const { translate } = await import(pathToFileURL(pkg + "/dist/node.js").href);
try {
  const words = translate({ from: "wgsl", source: readFileSync(input, "utf8"), to: "spirv", options: {} });
  writeFileSync(output, Buffer.from(words.buffer, words.byteOffset, words.byteLength));
} catch (e) {
  console.error(e.formatted ?? e.message);
  process.exit(1);
}
)";

void compile_wgsl(const std::string& dir, const std::string& path, const std::string& spirv, const std::string& naga_wasm) {
  if (const std::string why = wgsl_compiler_missing(naga_wasm); !why.empty()) throw RunFailure(why);
  const std::string script = dir + "/wgsl_to_spirv.mjs";
  io::write_file_atomically(script, kNagaScript);
  io::ProcessOptions options;
  options.stdout_path = dir + "/compile.log";
  options.time_limit_seconds = verify::kShaderCompileSeconds;
  const io::ProcessResult result = io::run_process({"node", script, naga_wasm, path, spirv}, options);
  if (!result.ok())
    throw RunFailure(std::string(result.timed_out ? "naga timed out" : "naga refused the WGSL") + ": " +
                     io::log_excerpt(dir + "/compile.log", 6));
}

}  // namespace

std::string wgsl_compiler_missing(const std::string& naga_wasm) {
  if (!io::program_available("node")) return "node not found: WGSL is compiled by naga-wasm under Node (scripts/setup.sh)";
  std::error_code ec;
  if (naga_wasm.empty() || !std::filesystem::is_regular_file(naga_wasm + "/dist/node.js", ec))
    return "naga-wasm not found at '" + runtime::excerpt(naga_wasm, 200) + "' (scripts/setup.sh installs it)";
  return "";
}

std::vector<std::uint32_t> compile_spirv(const ShaderDialect& dialect, const std::string& dir, const std::string& source,
                                         const std::string& naga_wasm) {
  const std::string path = dir + "/" + dialect.source_name, spirv = dir + "/shader.spv";
  io::write_file_atomically(path, source);
  if (dialect.front == ShaderFront::kWgsl) {
    compile_wgsl(dir, path, spirv, naga_wasm);
  } else {
    std::vector<std::string> compile = {"glslangValidator"};
    compile.insert(compile.end(), dialect.compile_flags.begin(), dialect.compile_flags.end());
    compile.insert(compile.end(), {"-o", spirv, path});
    if (!io::run_process(compile, dir + "/compile.log").ok())
      throw RunFailure("glslangValidator failed: " + io::log_excerpt(dir + "/compile.log", 4));
  }
  if (!io::run_process({"spirv-val", spirv}, dir + "/validate.log").ok())
    throw RunFailure("spirv-val failed: " + io::log_excerpt(dir + "/validate.log", 3));
  const std::string bytes = io::read_text_file(spirv, kMaxSpirvBytes);
  std::vector<std::uint32_t> words(bytes.size() / 4);
  std::memcpy(words.data(), bytes.data(), words.size() * 4);
  return words;
}

std::unique_ptr<Runner> make_shader_runner(ShaderDialect dialect) { return std::make_unique<ShaderRunner>(std::move(dialect)); }

}  // namespace zhf::verify
