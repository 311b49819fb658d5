#include "vulkan_device.h"

#include <vulkan/vulkan.h>

#include <cstring>
#include <stdexcept>

namespace zhf::verify {
namespace {

void check(VkResult result, const char* what) {
  if (result != VK_SUCCESS) throw std::runtime_error(std::string("Vulkan: ") + what + " failed (VkResult " + std::to_string(result) + ")");
}

int device_rank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
  }
}

class Device : public VulkanDevice {
 public:
  ~Device() override {
    if (device_) vkDestroyDevice(device_, nullptr);
    if (instance_) vkDestroyInstance(instance_, nullptr);
  }

  bool init(std::string& why) {
    VkApplicationInfo app{};
    app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    app.pApplicationName = "zhf verify";
    app.apiVersion = VK_API_VERSION_1_0;
    VkInstanceCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    info.pApplicationInfo = &app;
    if (vkCreateInstance(&info, nullptr, &instance_) != VK_SUCCESS) {
      instance_ = VK_NULL_HANDLE;
      why = "no Vulkan instance could be created (is a Vulkan driver installed? on Debian: mesa-vulkan-drivers)";
      return false;
    }
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance_, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance_, &count, devices.data());
    int best_rank = 99;
    for (VkPhysicalDevice d : devices) {
      VkPhysicalDeviceProperties p;
      vkGetPhysicalDeviceProperties(d, &p);
      uint32_t families = 0;
      vkGetPhysicalDeviceQueueFamilyProperties(d, &families, nullptr);
      std::vector<VkQueueFamilyProperties> props(families);
      vkGetPhysicalDeviceQueueFamilyProperties(d, &families, props.data());
      for (uint32_t f = 0; f < families; ++f) {
        if (!(props[f].queueFlags & VK_QUEUE_COMPUTE_BIT)) continue;
        if (device_rank(p.deviceType) < best_rank) {
          best_rank = device_rank(p.deviceType);
          physical_ = d;
          family_ = f;
          properties_ = p;
        }
        break;
      }
    }
    if (!physical_) {
      why = "no Vulkan device with a compute queue (on Debian, lavapipe is in mesa-vulkan-drivers)";
      return false;
    }
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{};
    queue.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    queue.queueFamilyIndex = family_;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    VkPhysicalDeviceFeatures available{}, enabled{};
    vkGetPhysicalDeviceFeatures(physical_, &available);
    enabled.shaderFloat64 = available.shaderFloat64;
    float64_ = available.shaderFloat64 == VK_TRUE;
    VkDeviceCreateInfo device_info{};
    device_info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue;
    device_info.pEnabledFeatures = &enabled;
    check(vkCreateDevice(physical_, &device_info, nullptr, &device_), "vkCreateDevice");
    vkGetDeviceQueue(device_, family_, 0, &queue_);
    return true;
  }

  bool float64() const override { return float64_; }

  std::string description() const override {
    const char* type = "other";
    switch (properties_.deviceType) {
      case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: type = "discrete GPU"; break;
      case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: type = "integrated GPU"; break;
      case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: type = "virtual GPU"; break;
      case VK_PHYSICAL_DEVICE_TYPE_CPU: type = "CPU"; break;
      default: break;
    }
    return std::string(properties_.deviceName) + " (" + type + ")";
  }

  void run(const std::vector<std::uint32_t>& spirv, std::vector<std::vector<std::uint8_t>>& buffers,
           const void* push_constants, std::uint32_t push_size, std::uint32_t groups) override {
    Resources r(device_);
    const uint32_t n = static_cast<uint32_t>(buffers.size());
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(physical_, &memory);
    for (uint32_t i = 0; i < n; ++i) {
      VkBufferCreateInfo info{};
      info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
      info.size = std::max<size_t>(buffers[i].size(), 4);
      info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
      VkBuffer buffer;
      check(vkCreateBuffer(device_, &info, nullptr, &buffer), "vkCreateBuffer");
      r.buffers.push_back(buffer);
      VkMemoryRequirements req;
      vkGetBufferMemoryRequirements(device_, buffer, &req);
      const VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      uint32_t type = UINT32_MAX;
      for (uint32_t t = 0; t < memory.memoryTypeCount; ++t)
        if ((req.memoryTypeBits & (1u << t)) && (memory.memoryTypes[t].propertyFlags & want) == want) {
          type = t;
          break;
        }
      if (type == UINT32_MAX) throw std::runtime_error("Vulkan: no host-visible coherent memory");
      VkMemoryAllocateInfo alloc{};
      alloc.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
      alloc.allocationSize = req.size;
      alloc.memoryTypeIndex = type;
      VkDeviceMemory mem;
      check(vkAllocateMemory(device_, &alloc, nullptr, &mem), "vkAllocateMemory");
      r.memories.push_back(mem);
      check(vkBindBufferMemory(device_, buffer, mem, 0), "vkBindBufferMemory");
      void* mapped = nullptr;
      check(vkMapMemory(device_, mem, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
      std::memcpy(mapped, buffers[i].data(), buffers[i].size());
      vkUnmapMemory(device_, mem);
    }

    std::vector<VkDescriptorSetLayoutBinding> bindings(n);
    for (uint32_t i = 0; i < n; ++i) {
      bindings[i] = {};
      bindings[i].binding = i;
      bindings[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
      bindings[i].descriptorCount = 1;
      bindings[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    VkDescriptorSetLayoutCreateInfo layout_info{};
    layout_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    layout_info.bindingCount = n;
    layout_info.pBindings = bindings.data();
    check(vkCreateDescriptorSetLayout(device_, &layout_info, nullptr, &r.set_layout), "vkCreateDescriptorSetLayout");
    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_size};
    VkPipelineLayoutCreateInfo pipeline_layout_info{};
    pipeline_layout_info.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    pipeline_layout_info.setLayoutCount = 1;
    pipeline_layout_info.pSetLayouts = &r.set_layout;
    pipeline_layout_info.pushConstantRangeCount = push_size ? 1 : 0;
    pipeline_layout_info.pPushConstantRanges = &range;
    check(vkCreatePipelineLayout(device_, &pipeline_layout_info, nullptr, &r.pipeline_layout), "vkCreatePipelineLayout");
    VkShaderModuleCreateInfo module_info{};
    module_info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    module_info.codeSize = spirv.size() * 4;
    module_info.pCode = spirv.data();
    check(vkCreateShaderModule(device_, &module_info, nullptr, &r.module), "vkCreateShaderModule");
    VkComputePipelineCreateInfo pipeline_info{};
    pipeline_info.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
    pipeline_info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    pipeline_info.stage.module = r.module;
    pipeline_info.stage.pName = "main";
    pipeline_info.layout = r.pipeline_layout;
    check(vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &pipeline_info, nullptr, &r.pipeline),
          "vkCreateComputePipelines");

    VkDescriptorPoolSize pool_size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, n};
    VkDescriptorPoolCreateInfo pool_info{};
    pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    pool_info.maxSets = 1;
    pool_info.poolSizeCount = 1;
    pool_info.pPoolSizes = &pool_size;
    check(vkCreateDescriptorPool(device_, &pool_info, nullptr, &r.pool), "vkCreateDescriptorPool");
    VkDescriptorSetAllocateInfo set_info{};
    set_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    set_info.descriptorPool = r.pool;
    set_info.descriptorSetCount = 1;
    set_info.pSetLayouts = &r.set_layout;
    VkDescriptorSet set;
    check(vkAllocateDescriptorSets(device_, &set_info, &set), "vkAllocateDescriptorSets");
    std::vector<VkDescriptorBufferInfo> infos(n);
    std::vector<VkWriteDescriptorSet> writes(n);
    for (uint32_t i = 0; i < n; ++i) {
      infos[i] = {r.buffers[i], 0, VK_WHOLE_SIZE};
      writes[i] = {};
      writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
      writes[i].dstSet = set;
      writes[i].dstBinding = i;
      writes[i].descriptorCount = 1;
      writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
      writes[i].pBufferInfo = &infos[i];
    }
    vkUpdateDescriptorSets(device_, n, writes.data(), 0, nullptr);

    VkCommandPoolCreateInfo command_pool_info{};

    command_pool_info.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    command_pool_info.queueFamilyIndex = family_;
    check(vkCreateCommandPool(device_, &command_pool_info, nullptr, &r.command_pool), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo command_info{};
    command_info.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    command_info.commandPool = r.command_pool;
    command_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    command_info.commandBufferCount = 1;
    VkCommandBuffer commands;
    check(vkAllocateCommandBuffers(device_, &command_info, &commands), "vkAllocateCommandBuffers");
    VkCommandBufferBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(commands, &begin), "vkBeginCommandBuffer");
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, r.pipeline);
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, r.pipeline_layout, 0, 1, &set, 0, nullptr);
    if (push_size) vkCmdPushConstants(commands, r.pipeline_layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, push_size, push_constants);
    vkCmdDispatch(commands, groups, 1, 1);
    VkMemoryBarrier barrier{};
    barrier.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
    barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                         nullptr, 0, nullptr);
    check(vkEndCommandBuffer(commands), "vkEndCommandBuffer");
    VkFenceCreateInfo fence_info{};
    fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    check(vkCreateFence(device_, &fence_info, nullptr, &r.fence), "vkCreateFence");
    VkSubmitInfo submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands;
    check(vkQueueSubmit(queue_, 1, &submit, r.fence), "vkQueueSubmit");
    check(vkWaitForFences(device_, 1, &r.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");

    for (uint32_t i = 0; i < n; ++i) {
      void* mapped = nullptr;
      check(vkMapMemory(device_, r.memories[i], 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
      std::memcpy(buffers[i].data(), mapped, buffers[i].size());
      vkUnmapMemory(device_, r.memories[i]);
    }
  }

 private:
  // Everything one run creates, destroyed in reverse order whatever happens.
  struct Resources {
    explicit Resources(VkDevice d) : device(d) {}
    ~Resources() {
      if (fence) vkDestroyFence(device, fence, nullptr);
      if (command_pool) vkDestroyCommandPool(device, command_pool, nullptr);
      if (pool) vkDestroyDescriptorPool(device, pool, nullptr);
      if (pipeline) vkDestroyPipeline(device, pipeline, nullptr);
      if (module) vkDestroyShaderModule(device, module, nullptr);
      if (pipeline_layout) vkDestroyPipelineLayout(device, pipeline_layout, nullptr);
      if (set_layout) vkDestroyDescriptorSetLayout(device, set_layout, nullptr);
      for (VkBuffer b : buffers) vkDestroyBuffer(device, b, nullptr);
      for (VkDeviceMemory m : memories) vkFreeMemory(device, m, nullptr);
    }
    VkDevice device;
    std::vector<VkBuffer> buffers;
    std::vector<VkDeviceMemory> memories;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    VkPipelineLayout pipeline_layout = VK_NULL_HANDLE;
    VkShaderModule module = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkCommandPool command_pool = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
  };

  VkInstance instance_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties_{};
  bool float64_ = false;
  uint32_t family_ = 0;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
};

}  // namespace

std::unique_ptr<VulkanDevice> VulkanDevice::open(std::string& why) {
  auto device = std::make_unique<Device>();
  if (!device->init(why)) return nullptr;
  return device;
}

}  // namespace zhf::verify
