// The Radiance reader behind zhf project on arbitrary bytes: it may reject, never crash, and what
// it accepts holds together (the pixel count is within the limits, every value finite).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "zhf/io/errors.h"
#include "zhf/io/hdr.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    const zhf::io::HdrImage image = zhf::io::parse_hdr(bytes, "fuzz.hdr");
    if (image.width < 1 || image.height < 1 || static_cast<long long>(image.width) * image.height > zhf::io::kMaxHdrPixels) std::abort();
    if (image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3) std::abort();
    for (float v : image.rgb)
      if (!std::isfinite(v) || v < 0) std::abort();
  } catch (const zhf::io::InputError&) {
  }
  return 0;
}
