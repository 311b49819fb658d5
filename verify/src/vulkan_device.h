// A headless Vulkan compute runner: one device, storage buffers, push constants, one dispatch.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace zhf::verify {

class VulkanDevice {
 public:
  // A discrete GPU when present, else integrated, virtual or CPU (lavapipe). nullptr and a
  // reason in `why` when there is no usable device.
  static std::unique_ptr<VulkanDevice> open(std::string& why);
  virtual ~VulkanDevice() = default;
  virtual std::string description() const = 0;
  // Whether shaders may use double (shaderFloat64, enabled when the device has it).
  virtual bool float64() const = 0;

  // Runs a compute shader (entry "main") with buffers[i] bound as storage buffer i of set 0;
  // every buffer is copied in before and out after. Throws std::runtime_error on failure.
  virtual void run(const std::vector<std::uint32_t>& spirv, std::vector<std::vector<std::uint8_t>>& buffers,
                   const void* push_constants, std::uint32_t push_size, std::uint32_t groups) = 0;
};

}  // namespace zhf::verify
