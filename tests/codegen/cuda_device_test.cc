// The generated C++ kernels as CUDA device code: every function of every generated order, float
// and double, called from a __global__ kernel and compiled to PTX by clang's CUDA front end in
// device-only mode. There is no CUDA SDK (nor GPU) here, so what its headers would declare, the
// execution-space attributes and the device sqrt overloads, is declared in the source below;
// compiled only, never run (docs/verification.md).
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "test_support.h"
#include "zhf/codegen/kernels.h"
#include "zhf/io/process.h"
#include "zhf/runtime/table_io.h"

namespace zhf {
namespace {

namespace fs = std::filesystem;

constexpr const char* kCudaHeaderStandIns = R"(#define __host__ __attribute__((host))
#define __device__ __attribute__((device))
#define __global__ __attribute__((global))
__device__ inline float sqrt(float x) { return __builtin_sqrtf(x); }
__device__ inline double sqrt(double x) { return __builtin_sqrt(x); }
)";

// A kernel per function: its arrays filled from data, the function called, its outputs written
// back (so nothing is optimised away), instantiated for float and double.
std::string device_calls(const codegen::Module& module, int& kernels) {
  std::ostringstream out;
  for (const codegen::Function& f : module.functions) {
    out << "template <class T>\n__global__ void call_" << f.name << "(T* data) {\n";
    std::string arguments = f.batch ? "1" : "";
    int offset = 0;
    for (size_t k = 0; k < f.params.size(); ++k) {
      const codegen::Param& p = f.params[k];
      const std::string name = "a" + std::to_string(k), values = std::to_string(p.size * p.channels);
      out << "  T " << name << "[" << values << "];\n"
          << "  for (int i = 0; i < " << values << "; ++i) " << name << "[i] = data[" << offset << " + i];\n";
      arguments += (arguments.empty() ? "" : ", ") +
                   (p.channels > 1 && !f.batch ? "reinterpret_cast<T(*)[" + std::to_string(p.size) + "]>(" + name + ")" : name);
      offset += p.size * p.channels;
    }
    out << "  zhf::gen::" << f.name << "<T>(" << arguments << ");\n";
    offset = 0;
    for (size_t k = 0; k < f.params.size(); ++k) {
      const codegen::Param& p = f.params[k];
      if (p.output)
        out << "  for (int i = 0; i < " << p.size * p.channels << "; ++i) data[" << offset << " + i] = a" << k << "[i];\n";
      offset += p.size * p.channels;
    }
    out << "}\ntemplate __global__ void call_" << f.name << "<float>(float*);\n"
        << "template __global__ void call_" << f.name << "<double>(double*);\n";
    kernels += 2;
  }
  return out.str();
}

TEST(CudaDevice, EveryGeneratedFunctionCompilesToPtxInFloatAndDouble) {
  ASSERT_TRUE(io::program_available("clang++")) << "clang++ not found: scripts/setup.sh installs it";
  const test::TempDir dir;
  for (int order = 2; order <= 8; ++order) {
    const runtime::LobeTable table = order == 2 ? runtime::lobe_free_table() : runtime::read_lobe_table(test::checked_in_table(order));
    const codegen::Module module = codegen::build_module(table, codegen::ModuleOptions());
    int kernels = 0;
    const fs::path source = dir / ("order" + std::to_string(order) + ".cu");
    {
      std::ofstream out(source);
      out << kCudaHeaderStandIns << "#include \"zhf_order" << order << ".h\"\n" << device_calls(module, kernels);
    }
    const fs::path ptx = dir / ("order" + std::to_string(order) + ".ptx"), log = dir / "clang.log";
    const io::ProcessResult result = io::run_process(
        {"clang++", "-x", "cuda", "--cuda-device-only", "-nocudainc", "-nocudalib", "--cuda-gpu-arch=sm_70", "-std=c++17", "-O2",
         "-Wno-unknown-cuda-version", "-Werror", "-S", "-I", test::source_path("generated/cpp"), source.string(), "-o", ptx.string()},
        log.string());
    ASSERT_TRUE(result.ok()) << "order " << order << ": clang++ failed:\n" << io::log_excerpt(log.string(), 30);
    const std::string text = test::read_text(ptx.string());
    int entries = 0;
    for (size_t at = text.find(".entry "); at != std::string::npos; at = text.find(".entry ", at + 1)) ++entries;
    EXPECT_EQ(entries, kernels) << "order " << order;
    if (order >= 4) {
      EXPECT_NE(text.find("sqrt.rn.f32"), std::string::npos) << "order " << order << ": the device sqrt, float";
      EXPECT_NE(text.find("sqrt.rn.f64"), std::string::npos) << "order " << order << ": the device sqrt, double";
    }
  }
}

}  // namespace
}  // namespace zhf
