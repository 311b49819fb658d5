// What the WebAssembly module's C API takes (zhf_web.h); every call checks these before any work.
#pragma once

namespace zhf::web {

// The 3D Gaussian Splatting layout's SH degrees rotate_splats takes: those the scene files carry
// (.ply's 72 f_rest and .spz version 4 go to degree 4; splat/limits.h).
inline constexpr int kMaxSplatDegree = 4;

}  // namespace zhf::web
