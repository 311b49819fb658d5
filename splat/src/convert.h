// Conversion through the canonical record (scene_io.h): any pair of formats but .ply to .ply, a
// scene whose bands are cut or whose splats are filtered, and several scenes merged into one.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "zhf/splat/scene.h"

namespace zhf::splat {

struct Input {
  std::string path;
  FileFormat format;
};

// The inputs, one after another, into `out` as format `to`; see transform_files.
Summary convert(const std::vector<Input>& inputs, const std::string& out, FileFormat to, const Formats& formats, const Transform& transform,
                int threads, const std::function<void(std::uint64_t, std::uint64_t)>& progress);

}  // namespace zhf::splat
