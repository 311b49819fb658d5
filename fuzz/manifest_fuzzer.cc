// The manifest reader behind verify and generate (codegen/manifest.h) on arbitrary bytes: it may
// refuse, never crash; what it accepts keeps its paths inside the tree.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "zhf/codegen/manifest.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const zhf::io::json::Json root = zhf::io::json::parse(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
    for (const zhf::codegen::ManifestFile& f : zhf::codegen::parse_manifest(root, "fuzz.json").files)
      if (f.path.empty() || f.path[0] == '/' || f.path.find("..") != std::string::npos) std::abort();
  } catch (const zhf::runtime::InputError&) {
  }
  return 0;
}
