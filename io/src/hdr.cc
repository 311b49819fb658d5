#include "zhf/io/hdr.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/limits.h"

namespace zhf::io {
namespace {

// Radiance RGBE: a pixel whose largest channel is below this is stored black (the format's rule).
constexpr float kRgbeBlack = 1e-32f;  // an input, not a tolerance


float component(std::uint8_t mantissa, std::uint8_t exponent) {
  return exponent == 0 ? 0.0f : std::ldexp(static_cast<float>(mantissa), static_cast<int>(exponent) - 136);
}

// The resolution line "-Y <height> +X <width>", each a decimal integer in range.
bool parse_resolution(const std::string& line, int& height, int& width) {
  std::size_t at = 0;
  auto word = [&](const char* expected) {
    const std::string w(expected);
    if (line.compare(at, w.size(), w) != 0) return false;
    at += w.size();
    return true;
  };
  auto number = [&](int& out) {
    long long v = 0;
    const std::size_t start = at;
    while (at < line.size() && line[at] >= '0' && line[at] <= '9' && at - start < 6) v = v * 10 + (line[at++] - '0');
    if (at == start || (at < line.size() && line[at] >= '0' && line[at] <= '9') || v < 1 || v > kMaxHdrSide) return false;
    out = static_cast<int>(v);
    return true;
  };
  return word("-Y ") && number(height) && word(" +X ") && number(width) && at == line.size();
}

}  // namespace

HdrImage parse_hdr(const std::string& bytes, const std::string& source) {
  auto fail = [&](const std::string& what) { throw InputError(source + ": " + what); };
  if (bytes.size() > kMaxHdrBytes) fail("larger than the limit of " + std::to_string(kMaxHdrBytes) + " bytes");
  std::size_t at = 0;
  auto line = [&](const char* what) {
    const std::size_t end = bytes.find('\n', at);
    if (end == std::string::npos || end > kMaxHdrHeader) fail(std::string("the header ends before ") + what);
    std::string text = bytes.substr(at, end - at);
    at = end + 1;
    return text;
  };
  const std::string magic = line("the first line");
  if (magic != "#?RADIANCE" && magic != "#?RGBE") fail("not a Radiance file (first line '" + excerpt(magic) + "')");
  for (;;) {
    const std::string text = line("its blank line");
    if (text.empty()) break;
    if (text.rfind("FORMAT=", 0) == 0 && text != "FORMAT=32-bit_rle_rgbe")
      fail("FORMAT '" + excerpt(text.substr(7)) + "' is not 32-bit_rle_rgbe");
  }
  HdrImage image;
  const std::string resolution = line("the resolution line");
  if (!parse_resolution(resolution, image.height, image.width))
    fail("resolution '" + excerpt(resolution) + "' is not '-Y H +X W' with H and W in 1.." + std::to_string(kMaxHdrSide));
  if (static_cast<long long>(image.width) * image.height > kMaxHdrPixels)
    fail(std::to_string(image.width) + " x " + std::to_string(image.height) + " pixels, above the limit of " +
         std::to_string(kMaxHdrPixels));
  const int w = image.width;
  image.rgb.resize(static_cast<std::size_t>(w) * image.height * 3);
  std::vector<std::uint8_t> scan(static_cast<std::size_t>(w) * 4);
  auto byte = [&](int row) -> std::uint8_t {
    if (at >= bytes.size()) fail("scanline " + std::to_string(row) + ": the file ends inside it");
    return static_cast<std::uint8_t>(bytes[at++]);
  };
  for (int row = 0; row < image.height; ++row) {
    const bool rle = w >= 8 && w < 32768 && at + 4 <= bytes.size() && bytes[at] == 2 && bytes[at + 1] == 2 && !(bytes[at + 2] & 0x80);
    if (rle) {
      at += 2;
      const int width = (byte(row) << 8) | byte(row);
      if (width != w) fail("scanline " + std::to_string(row) + ": run-length width " + std::to_string(width) + ", the image's is " + std::to_string(w));
      for (int c = 0; c < 4; ++c) {
        for (int x = 0; x < w;) {
          int count = byte(row);
          const bool run = count > 128;
          if (run) count -= 128;
          if (count == 0 || x + count > w) fail("scanline " + std::to_string(row) + ": a run overflows the line");
          if (run) {
            const std::uint8_t value = byte(row);
            for (int k = 0; k < count; ++k) scan[4 * (x++) + c] = value;
          } else {
            for (int k = 0; k < count; ++k) scan[4 * (x++) + c] = byte(row);
          }
        }
      }
    } else {
      for (int x = 0; x < w; ++x) {
        for (int c = 0; c < 4; ++c) scan[4 * x + c] = byte(row);
        if (scan[4 * x] == 1 && scan[4 * x + 1] == 1 && scan[4 * x + 2] == 1)
          fail("scanline " + std::to_string(row) + ": old-style repeat runs are not supported");
      }
    }
    float* out = &image.rgb[static_cast<std::size_t>(row) * w * 3];
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) out[3 * x + c] = component(scan[4 * x + c], scan[4 * x + 3]);
  }
  if (at != bytes.size()) fail(std::to_string(bytes.size() - at) + " bytes after the last scanline");
  return image;
}

HdrImage read_hdr(const std::string& path) { return parse_hdr(read_text_file(path, kMaxHdrBytes), path); }

std::string encode_hdr(const HdrImage& image) {
  std::string out = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(image.height) + " +X " + std::to_string(image.width) + "\n";
  const int w = image.width;
  std::vector<std::uint8_t> scan(static_cast<std::size_t>(w) * 4);
  for (int row = 0; row < image.height; ++row) {
    for (int x = 0; x < w; ++x) {
      const float* p = &image.rgb[(static_cast<std::size_t>(row) * w + x) * 3];
      const float largest = std::fmax(p[0], std::fmax(p[1], p[2]));
      int e = 0;
      if (!(largest > kRgbeBlack)) {
        scan[4 * x] = scan[4 * x + 1] = scan[4 * x + 2] = scan[4 * x + 3] = 0;
        continue;
      }
      std::frexp(largest, &e);  // largest = f 2^e, f in [0.5, 1)
      for (int c = 0; c < 3; ++c) {
        const long m = std::lround(std::ldexp(std::fmax(p[c], 0.0f), 8 - e));
        scan[4 * x + c] = static_cast<std::uint8_t>(m > 255 ? 255 : m);
      }
      scan[4 * x + 3] = static_cast<std::uint8_t>(e + 128);
    }
    if (w < 8 || w >= 32768) {
      out.append(reinterpret_cast<const char*>(scan.data()), scan.size());
      continue;
    }
    out += {2, 2, static_cast<char>(w >> 8), static_cast<char>(w & 255)};
    for (int c = 0; c < 4; ++c)  // literal runs of up to 128 bytes
      for (int x = 0; x < w; x += 128) {
        const int count = std::min(128, w - x);
        out += static_cast<char>(count);
        for (int k = 0; k < count; ++k) out += static_cast<char>(scan[4 * (x + k) + c]);
      }
  }
  return out;
}

}  // namespace zhf::io
