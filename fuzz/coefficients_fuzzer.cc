// The coefficient-file reader behind zhf analyze (JSON and text layouts) on arbitrary bytes:
// it may reject, never crash; what it accepts is well formed.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "zhf/io/coefficients.h"
#include "zhf/io/errors.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (int channels : {0, 3}) {
    try {
      const zhf::io::CoefficientFile file = zhf::io::parse_coefficients(text, "fuzz", channels);
      const std::size_t n = static_cast<std::size_t>(file.order) * file.order;
      if (file.signals.empty() || file.signals.size() % file.channels != 0) std::abort();
      for (const auto& s : file.signals) {
        if (s.size() != n) std::abort();
        for (double x : s)
          if (!std::isfinite(x)) std::abort();
      }
    } catch (const zhf::io::InputError&) {
    }
  }
  return 0;
}
