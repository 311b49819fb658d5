// zhf splat's format readers on arbitrary bytes: the first byte picks the reader (binary .ply to
// .splat, .splat to .ply, compressed .ply to compressed .ply, .spz to .spz, .glb to .glb, .sog to
// .sog), the rest is the file.
// They may refuse, never crash; a .splat the reader accepts converts every one of its 32-byte
// records.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

#include "zhf/io/errors.h"
#include "zhf/io/private_dir.h"
#include "zhf/splat/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const zhf::io::PrivateDir dir("zhf-fuzz-splat");
  static const char* const kPaths[][2] = {{"/in.ply", "/out.splat"},
                                          {"/in.splat", "/out.ply"},
                                          {"/in.compressed.ply", "/out.compressed.ply"},
                                          {"/in.spz", "/out.spz"},
                                          {"/in.glb", "/out.glb"},
                                          {"/in.sog", "/out.sog"}};
  const int path = data[0] % 6;
  const bool from_splat = path == 1;
  const std::string in = dir.path() + kPaths[path][0], out = dir.path() + kPaths[path][1];
  {
    std::ofstream file(in, std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
  }
  zhf::splat::Transform turn;
  turn.r = {0, -1, 0, 1, 0, 0, 0, 0, 1};
  try {
    const zhf::splat::Summary summary = zhf::splat::transform_file(in, out, turn, 1, [](std::uint64_t, std::uint64_t) {});
    if (from_splat && summary.splats != (size - 1) / 32) std::abort();
  } catch (const zhf::io::InputError&) {
  }
  return 0;
}
