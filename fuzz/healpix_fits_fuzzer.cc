// The HEALPix map reader behind zhf project --healpix and zhf needlets analyze, cfitsio's header
// parsing included, on arbitrary bytes: it may reject, never crash, and what it accepts holds
// together (12 Nside^2 finite pixels, Nside in range, written back and read again unchanged).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "zhf/healpix/fits.h"
#include "zhf/healpix/limits.h"
#include "zhf/io/errors.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace zhf::healpix;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    const HealpixMap map = parse_healpix_map(bytes, "fuzz.fits");
    if (map.nside < 1 || map.nside > kMaxHealpixNside) std::abort();
    if (static_cast<std::int64_t>(map.pixels.size()) != healpix_pixels(map.nside)) std::abort();
    for (double v : map.pixels)
      if (!std::isfinite(v)) std::abort();
    const HealpixMap again = parse_healpix_map(encode_healpix_map(map), "again.fits");
    if (again.pixels != map.pixels || again.ordering != map.ordering || again.nside != map.nside) std::abort();
  } catch (const zhf::io::InputError&) {
  }
  return 0;
}
