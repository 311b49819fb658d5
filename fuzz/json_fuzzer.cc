// The runtime's JSON reader (runtime/json.h) on arbitrary bytes: it may refuse, never crash or run
// past its limits; every message is one line.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "zhf/runtime/json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    zhf::runtime::json::parse(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
  } catch (const zhf::runtime::InputError& e) {
    if (std::string(e.what()).find('\n') != std::string::npos) std::abort();
  }
  return 0;
}
