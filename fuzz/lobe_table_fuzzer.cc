// The optimizer's lobe-table reader (used by emit, generate, verify) on arbitrary bytes: it
// may reject, never crash.
#include <cstddef>
#include <cstdint>
#include <string>

#include "zhf/io/errors.h"
#include "zhf/optimizer/lobe_table.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const nlohmann::json json =
      nlohmann::json::parse(std::string(reinterpret_cast<const char*>(data), size), nullptr, /*allow_exceptions=*/false);
  if (json.is_discarded()) return 0;
  try {
    zhf::optimizer::table_from_json(json, "fuzz.json");
  } catch (const zhf::io::InputError&) {
  }
  return 0;
}
