// examples/webgpu/rotate_splats.wgsl, the WebGPU example, after the generated order-4 WGSL kernels,
// through naga to SPIR-V and run on the Vulkan device verify uses: every splat's colour SH as the
// C++ kernel rotates them, so the example's layout and call stay right as the generator changes.
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../../verify/src/runners/shader_runner.h"
#include "../../verify/src/vulkan_device.h"
#include "test_support.h"
#include "zhf/runtime/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/rotation_matrix.h"
#include "zhf_order4.h"

namespace zhf::verify {
namespace {

constexpr int kSplats = 300;
constexpr int kFloatsPerSplat = 48;  // f_dc_0..2, then f_rest channel by channel (15 each)

TEST(WebGpuExample, RotatesSplatsOnVulkanAsTheCppKernelDoes) {
  std::string why;
  const std::unique_ptr<VulkanDevice> device = VulkanDevice::open(why);
  if (!device) GTEST_SKIP() << "no Vulkan device: " << why;
  const std::string naga = test::source_path("tools/node/node_modules/naga-wasm");
  ASSERT_EQ(wgsl_compiler_missing(naga), "");
  const test::TempDir dir;
  const std::string source = test::read_text(test::source_path("generated/wgsl/zhf_order4.wgsl")) +
                             test::read_text(test::source_path("examples/webgpu/rotate_splats.wgsl"));
  const std::vector<std::uint32_t> words = compile_spirv(wgsl_dialect(), dir.string(), source, naga);

  std::mt19937_64 rng(31);
  sh::Normal<> normal;
  const sh::RotationMatrix r = sh::random_rotation(rng);
  float rotation[9];
  for (int i = 0; i < 9; ++i) rotation[i] = float(r(i / 3, i % 3));
  std::vector<float> splats(std::size_t(kSplats) * kFloatsPerSplat);
  for (float& x : splats) x = float(normal(rng) / 4);  // unit-sized colours per channel
  auto bytes = [](const float* p, std::size_t n) {
    std::vector<std::uint8_t> b(n * sizeof(float));
    std::memcpy(b.data(), p, b.size());
    return b;
  };
  std::vector<std::vector<std::uint8_t>> buffers = {bytes(rotation, 9), bytes(splats.data(), splats.size()),
                                                    std::vector<std::uint8_t>(splats.size() * sizeof(float), 0)};
  const std::uint32_t count = kSplats;
  device->run(words, buffers, &count, sizeof count, (count + 63) / 64);
  std::vector<float> got(splats.size());
  std::memcpy(got.data(), buffers[2].data(), buffers[2].size());

  for (int s = 0; s < kSplats; ++s) {
    const float* in = &splats[std::size_t(s) * kFloatsPerSplat];
    float coeffs[3][16], rotated[3][16];
    for (int c = 0; c < 3; ++c) {
      coeffs[c][0] = in[c];
      for (int i = 1; i < 16; ++i) coeffs[c][i] = in[3 + 15 * c + i - 1];
    }
    gen::rotate_rgb_order4<float>(rotation, coeffs, rotated);
    const float* out = &got[std::size_t(s) * kFloatsPerSplat];
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(out[c], rotated[c][0], runtime::tolerance::kFloatRotation) << "splat " << s << ", channel " << c << ", index 0";
      for (int i = 1; i < 16; ++i)
        EXPECT_NEAR(out[3 + 15 * c + i - 1], rotated[c][i], runtime::tolerance::kFloatRotation)
            << "splat " << s << ", channel " << c << ", band " << (i < 4 ? 1 : i < 9 ? 2 : 3) << ", index " << i;
    }
  }
}

}  // namespace
}  // namespace zhf::verify
