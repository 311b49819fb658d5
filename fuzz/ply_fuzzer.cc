// The PLY header reader behind zhf splat on arbitrary bytes: it may reject, never crash, and what
// it accepts holds together (its text is the input's prefix, the limits hold, the record size is
// the sum of the property sizes).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

#include "zhf/io/errors.h"
#include "zhf/io/ply.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  std::istringstream in(bytes);
  namespace ply = zhf::io::ply;
  try {
    const ply::Header h = ply::read_header(in, "fuzz.ply");
    if (bytes.compare(0, h.text.size(), h.text) != 0 || h.text.size() > zhf::io::kMaxPlyHeaderBytes + 1) std::abort();
    if (h.properties.empty() || h.properties.size() > zhf::io::kMaxPlyProperties || h.vertices > zhf::io::kMaxPlyVertices) std::abort();
    std::size_t total = 0;
    for (const ply::Property& p : h.properties) {
      if (p.offset != total) std::abort();
      total += ply::type_size(p.type);
    }
    if (total != h.record_bytes) std::abort();
  } catch (const zhf::io::InputError&) {
  }
  return 0;
}
