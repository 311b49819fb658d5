// The one lobe-table reader and validator (runtime/lobe_table.h: the runtime's table loading and
// every command's) on arbitrary bytes: it may refuse, never crash; what it accepts is a table a
// Rotator can use and the writer can write.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "zhf/runtime/table_io.h"
#include "zhf/runtime/rotator.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const zhf::runtime::LobeTable table =
        zhf::runtime::parse_lobe_table(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
    const auto rotator = zhf::runtime::Rotator<double>::from_table(table);
    std::vector<double> in(rotator.coefficients(), 0.5), out(rotator.coefficients());
    const double r[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};
    rotator.rotate(r, in.data(), out.data());
  } catch (const zhf::runtime::InputError&) {
  }
  return 0;
}
