#include "zhf/dispatch/isa.h"

#include <atomic>
#include <cstdlib>
#include <stdexcept>

#include "zhf/runtime/enum_names.h"
#include "zhf/runtime/errors.h"

namespace zhf::dispatch {
namespace {

// The paths this library was built with, fastest first (dispatch/CMakeLists.txt sets the list).
constexpr Isa kBuilt[] = {ZHF_DISPATCH_PATHS};
constexpr runtime::EnumName<Isa> kIsaNames[] = {
    {Isa::kGeneric, "generic"}, {Isa::kSse2, "sse2"}, {Isa::kAvx2, "avx2"}, {Isa::kAvx512, "avx512"}, {Isa::kNeon, "neon"},
    {Isa::kSimd128, "simd128"}};

bool cpu_runs(Isa isa) {
  switch (isa) {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
    case Isa::kAvx2: return __builtin_cpu_supports("x86-64-v3");
    case Isa::kAvx512: return __builtin_cpu_supports("x86-64-v4");
#elif defined(__x86_64__)
    // Clang names features only, not all of them: these are the levels' (the rest of v3, F16C,
    // MOVBE and LZCNT, came with every CPU that has AVX2 and BMI2).
    case Isa::kAvx2:
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi") &&
             __builtin_cpu_supports("bmi2");
    case Isa::kAvx512:
      return cpu_runs(Isa::kAvx2) && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
             __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl");
#endif
    default: return true;  // the baseline of the architecture the library was built for
  }
}

std::string names(const std::vector<Isa>& isas) {
  std::string out;
  for (Isa isa : isas) out += (out.empty() ? "" : ", ") + std::string(isa_name(isa));
  return out;
}

// The path called name, refused in one line naming what (the variable or the call) when the
// library lacks it or this CPU does not run it.
Isa checked(const std::string& name, const std::string& what) {
  Isa isa = Isa::kGeneric;
  if (runtime::parse_enum(kIsaNames, name, isa))
    for (Isa built : kBuilt) {
      if (built != isa) continue;
      if (!cpu_runs(isa)) throw std::invalid_argument(what + ": this CPU does not run " + name + " (it runs " + names(supported_isas()) + ")");
      return isa;
    }
  std::vector<Isa> built(std::begin(kBuilt), std::end(kBuilt));
  throw std::invalid_argument(what + ": '" + runtime::excerpt(name) + "' is not one of this build's paths (" + names(built) + ")");
}

constexpr int kNotForced = -1;
std::atomic<int> forced{kNotForced};

}  // namespace

const char* isa_name(Isa isa) { return runtime::enum_name(kIsaNames, isa); }

std::vector<Isa> supported_isas() {
  std::vector<Isa> out;
  for (Isa isa : kBuilt)
    if (cpu_runs(isa)) out.push_back(isa);
  return out;
}

Isa active_isa() {
  const int f = forced.load(std::memory_order_acquire);
  if (f != kNotForced) return static_cast<Isa>(f);
  static const Isa from_environment = [] {
    const char* name = std::getenv("ZHF_ISA");
    return name && *name ? checked(name, "ZHF_ISA") : supported_isas().front();
  }();
  return from_environment;
}

void use_isa(const std::string& name) { forced.store(static_cast<int>(checked(name, "use_isa")), std::memory_order_release); }

}  // namespace zhf::dispatch
