// The Radiance reader (io/hdr.h): files written by encode_hdr read back within RGBE's rounding,
// flat and run-length scanlines, and every malformed or oversized file refused with one line.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "zhf/io/errors.h"
#include "zhf/io/hdr.h"

namespace zhf::io {
namespace {

HdrImage gradient(int width, int height) {
  HdrImage image;
  image.width = width;
  image.height = height;
  for (int r = 0; r < height; ++r)
    for (int c = 0; c < width; ++c) image.rgb.insert(image.rgb.end(), {0.01f * c, 100.0f / (1 + r), c == r ? 0.0f : 3.5f});
  return image;
}

TEST(Hdr, RoundTripsWithinRgbeRounding) {
  for (int width : {1, 7, 8, 200}) {
    const HdrImage image = gradient(width, 5);
    const HdrImage back = parse_hdr(encode_hdr(image), "gradient.hdr");
    ASSERT_EQ(back.width, width);
    ASSERT_EQ(back.height, 5);
    for (std::size_t i = 0; i < image.rgb.size(); i += 3) {
      const float largest = std::fmax(image.rgb[i], std::fmax(image.rgb[i + 1], image.rgb[i + 2]));
      for (int c = 0; c < 3; ++c)  // 8-bit mantissas on the pixel's largest component's exponent
        ASSERT_NEAR(back.rgb[i + c], image.rgb[i + c], largest / 256 + 1e-30) << "width " << width << ", value " << i / 3 << ", channel " << c;
    }
  }
}

TEST(Hdr, RunLengthScanlinesAreDecoded) {
  // Width 8, one scanline: a run of 8 for red (value 128), literals for green, runs for blue and the exponent.
  std::string file = "#?RGBE\n\n-Y 1 +X 8\n";
  file += std::string{2, 2, 0, 8};
  file += std::string{static_cast<char>(128 + 8), static_cast<char>(128)};
  file += std::string{8, 1, 2, 3, 4, 5, 6, 7, 8};
  file += std::string{static_cast<char>(128 + 8), 0};
  file += std::string{static_cast<char>(128 + 8), static_cast<char>(129)};
  const HdrImage image = parse_hdr(file, "rle.hdr");
  for (int x = 0; x < 8; ++x) {
    EXPECT_FLOAT_EQ(image.rgb[3 * x], 128.0f / 128) << x;  // m 2^(129 - 136)
    EXPECT_FLOAT_EQ(image.rgb[3 * x + 1], (x + 1) / 128.0f) << x;
    EXPECT_EQ(image.rgb[3 * x + 2], 0.0f) << x;
  }
}

TEST(Hdr, MalformedFilesAreRefused) {
  const std::string good = encode_hdr(gradient(16, 3));
  const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n";
  struct Case {
    std::string name, bytes, message;
  };
  const Case cases[] = {
      {"empty", "", "the header ends before the first line"},
      {"not radiance", "P6\n16 3\n255\n", "not a Radiance file"},
      {"xyze", "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n\1\1\1\1", "FORMAT '32-bit_rle_xyze'"},
      {"no blank line", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n", "the header ends before its blank line"},
      {"flipped", header + "+Y 3 +X 16\n", "is not '-Y H +X W'"},
      {"zero width", header + "-Y 3 +X 0\n", "is not '-Y H +X W'"},
      {"huge side", header + "-Y 99999999999 +X 4\n", "is not '-Y H +X W'"},
      {"trailing text", header + "-Y 1 +X 1 x\n", "is not '-Y H +X W'"},
      {"too many pixels", header + "-Y 32767 +X 32767\n", "above the limit"},
      {"truncated", good.substr(0, good.size() - 5), "the file ends inside it"},
      {"trailing bytes", good + "junk", "4 bytes after the last scanline"},
      {"run overflow", header + "-Y 1 +X 8\n" + std::string{2, 2, 0, 8, static_cast<char>(128 + 9), 1}, "a run overflows the line"},
      {"wrong rle width", header + "-Y 1 +X 8\n" + std::string{2, 2, 0, 9}, "run-length width 9"},
      {"old repeat", header + "-Y 1 +X 2\n" + std::string{1, 1, 1, 5, 0, 0, 0, 0}, "old-style repeat runs"},
  };
  for (const Case& c : cases) {
    try {
      parse_hdr(c.bytes, "bad.hdr");
      ADD_FAILURE() << c.name << ": accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("bad.hdr: ", 0), 0u) << c.name << ": " << what;
      EXPECT_NE(what.find(c.message), std::string::npos) << c.name << ": " << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << c.name;
    }
  }
}

}  // namespace
}  // namespace zhf::io
