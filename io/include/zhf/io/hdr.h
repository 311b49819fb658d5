// Radiance RGBE images (.hdr, "#?RADIANCE" / "#?RGBE"), as environment maps are shipped: a text
// header (FORMAT=32-bit_rle_rgbe; EXPOSURE and other lines ignored), the resolution line
// "-Y H +X W" (rows top to bottom, columns left to right; other orientations are refused), then
// H scanlines, each either W flat RGBE pixels or, for 8 <= W < 32768, the adaptive run-length form
// (2, 2, W >> 8, W & 255, then each of the four components in runs). A pixel is
// (r, g, b) = m * 2^(e - 136) for mantissas m and exponent byte e (0: black). Bytes after the last
// scanline are refused, as are the old-style repeat runs (1, 1, 1, n).
// Limits, checked before decoding: files up to kMaxHdrBytes, headers up to kMaxHdrHeader, width
// and height 1..kMaxHdrSide, width * height up to kMaxHdrPixels.
#pragma once

#include <cstddef>
#include <string>
#include <vector>
#include "zhf/io/limits.h"

namespace zhf::io {

struct HdrImage {
  int width = 0, height = 0;
  std::vector<float> rgb;  // row-major from the top row, 3 floats a pixel
};

// Throws InputError naming the source and what is wrong (the scanline, for pixel data).
HdrImage parse_hdr(const std::string& bytes, const std::string& source);
HdrImage read_hdr(const std::string& path);

// The RGBE file of an image (flat scanlines below width 8 or above 32767, run-length otherwise;
// components rounded to the nearest representable value), for tests and examples.
std::string encode_hdr(const HdrImage& image);

}  // namespace zhf::io
