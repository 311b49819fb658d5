// The rotation parsers behind zhf rotate (--matrix, --zyz, --axis-angle) on arbitrary text:
// they may reject, never crash; what they accept is finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "zhf/io/errors.h"
#include "zhf/io/rotation_text.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (auto form : {zhf::io::RotationForm::kMatrix, zhf::io::RotationForm::kZyz, zhf::io::RotationForm::kAxisAngle}) {
    try {
      for (double x : zhf::io::parse_rotation(text, form, "--fuzz"))
        if (!std::isfinite(x)) std::abort();
    } catch (const zhf::io::InputError&) {
    }
  }
  return 0;
}
