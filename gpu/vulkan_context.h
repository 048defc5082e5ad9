// vulkan_context.h - Vulkan instance/device selection and the few objects every pass needs.
// Device choice prefers a discrete GPU, then integrated, then virtual, then CPU (lavapipe); `--device N`
// overrides. The Vulkan instance is the only process-wide state (DEVELOPERS.md).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace ht::gpu {

struct DeviceInfo {
  std::uint32_t index = 0;  // position in vkEnumeratePhysicalDevices order (what --device takes)
  std::string name;
  std::string type;        // "discrete", "integrated", "virtual", "cpu", "other"
  std::string apiVersion;  // "1.3.230"
  std::string driver;      // driver name + info
  std::uint64_t maxStorageBufferRange = 0;
  std::uint64_t maxMemoryAllocationSize = 0;
  std::uint32_t maxComputeWorkGroupInvocations = 0;
  std::uint32_t maxTexelBufferElements = 0;
  std::uint32_t subgroupSize = 0;
  float timestampPeriodNs = 0.0f;
  bool shaderFloat64 = false;
  bool denormPreserveFloat32 = false;  // shaders can keep 32-bit denormals (spirv_exact_float.h)
  bool bufferDeviceAddress = false;
  bool usable = false;  // has everything holotrace needs
  std::string unusableReason;
};

class VulkanContext {
 public:
  struct Options {
    int deviceIndex = -1;     // -1 = automatic choice
    bool validation = false;  // enable VK_LAYER_KHRONOS_validation; validation messages are counted
    // Also enable presentation: the instance extensions VK_KHR_surface + VK_KHR_xcb_surface and the device extension
    // VK_KHR_swapchain (the display sink, present/). Names only: gpu/ links no window system. GpuError if missing.
    bool presentation = false;
    // Let the driver fuse float multiplies and adds and flush denormals (spirv_exact_float.h). Off: every pipeline
    // rounds each operation as the C++ references do, on every driver. On: a few ULP from them where the driver
    // fuses (NVIDIA, lavapipe), for its speed (docs/DRIVERS.md).
    bool fusedFloatMath = false;
    // Off: buffers in device memory are never mapped, even where that memory is host visible (lavapipe, integrated
    // GPUs), so every copy to and from them takes the staging path of a discrete GPU (tests of that path).
    bool mapDeviceMemory = true;
  };
  explicit VulkanContext(const Options& options);
  ~VulkanContext();
  VulkanContext(const VulkanContext&) = delete;
  VulkanContext& operator=(const VulkanContext&) = delete;

  // Every physical device with its relevant limits (does not create a logical device).
  static std::vector<DeviceInfo> listDevices();

  const DeviceInfo& device() const;
  // Validation-layer errors and warnings seen so far (0 when validation is off).
  std::uint32_t validationMessageCount() const;

  struct Impl;
  Impl& impl() { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace ht::gpu
