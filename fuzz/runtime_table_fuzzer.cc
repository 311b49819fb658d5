// The runtime's own JSON reader and table checks on arbitrary bytes: reject, never crash.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "zhf/runtime/lobe_table.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    zhf::runtime::parse_lobe_table(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
  } catch (const std::runtime_error&) {
  }
  return 0;
}
