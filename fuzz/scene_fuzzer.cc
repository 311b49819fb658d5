// The scene-spec reader behind zhf generate --scene on arbitrary bytes: it may reject, never
// crash; what it accepts yields module options within the documented ranges.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "zhf/codegen/limits.h"
#include "zhf/codegen/scene.h"
#include "zhf/io/errors.h"
#include "zhf/runtime/limits.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const zhf::io::json::Json json = zhf::io::json::parse(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
    const zhf::codegen::Scene scene = zhf::codegen::parse_scene(json, "fuzz.json");
    for (const auto& [order, options] : scene.module_options()) {
      if (order < zhf::runtime::kMinGeneratedOrder || order > zhf::codegen::kMaxEmitOrder) std::abort();
      for (int l : options.zero_bands)
        if (l < 0 || l >= order) std::abort();
    }
  } catch (const zhf::io::InputError&) {
  }
  return 0;
}
