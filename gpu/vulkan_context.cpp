// vulkan_context.cpp - instance creation, physical-device survey and choice, logical device and queue.
#include "gpu/vulkan_context.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

#include "gpu/pipeline_library.h"
#include "gpu/vulkan_handles.h"
#include "gpu/vulkan_impl.h"

#ifdef HT_SANITIZED_BUILD
#include <dlfcn.h>
#include <link.h>

#include <string>
#endif

namespace ht::gpu {

const char* vkResultName(VkResult result) {
  switch (result) {
    case VK_SUCCESS: return "VK_SUCCESS";
    case VK_NOT_READY: return "VK_NOT_READY";
    case VK_TIMEOUT: return "VK_TIMEOUT";
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER:
      return "VK_ERROR_INCOMPATIBLE_DRIVER (no Vulkan driver found: install mesa-vulkan-drivers)";
    case VK_ERROR_TOO_MANY_OBJECTS: return "VK_ERROR_TOO_MANY_OBJECTS";
    case VK_SUBOPTIMAL_KHR: return "VK_SUBOPTIMAL_KHR";
    case VK_ERROR_OUT_OF_DATE_KHR: return "VK_ERROR_OUT_OF_DATE_KHR";
    case VK_ERROR_SURFACE_LOST_KHR: return "VK_ERROR_SURFACE_LOST_KHR";
    case VK_ERROR_NATIVE_WINDOW_IN_USE_KHR: return "VK_ERROR_NATIVE_WINDOW_IN_USE_KHR";
    default: return "VkResult error";
  }
}

void checkVk(VkResult result, const char* call) {
  if (result != VK_SUCCESS) {
    throw GpuError(std::string("Vulkan call failed: ") + call + " -> " + vkResultName(result) + " (" +
                   std::to_string(static_cast<int>(result)) + ")");
  }
}

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool hasLayer(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  return std::any_of(layers.begin(), layers.end(),
                     [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* impl = static_cast<VulkanContext::Impl*>(user);
  if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
    impl->validationMessages.fetch_add(1);
    impl->lastValidationMessage = data->pMessage ? data->pMessage : "";
    std::fprintf(stderr, "[vulkan validation] %s\n", impl->lastValidationMessage.c_str());
  }
  return VK_FALSE;
}

bool hasInstanceExtension(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateInstanceExtensionProperties(nullptr, &count, extensions.data());
  return std::any_of(extensions.begin(), extensions.end(),
                     [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

bool hasDeviceExtension(VkPhysicalDevice physical, const char* name) {
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, extensions.data());
  return std::any_of(extensions.begin(), extensions.end(),
                     [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

// The window-system extensions of a presenting instance, by name (no X headers here; present/ creates the surface).
constexpr const char* kSurfaceExtensions[] = {"VK_KHR_surface", "VK_KHR_xcb_surface"};
constexpr const char* kSwapchainExtension = "VK_KHR_swapchain";

std::vector<const char*> presentationExtensions() {
  std::vector<const char*> names;
  for (const char* name : kSurfaceExtensions) {
    if (!hasInstanceExtension(name)) {
      throw GpuError(std::string("presenting to a display needs the Vulkan instance extension ") + name +
                     ", which this Vulkan loader/driver does not offer");
    }
    names.push_back(name);
  }
  return names;
}

VkInstance createInstance(bool validation, VulkanContext::Impl* impl, VkDebugUtilsMessengerEXT* messenger,
                          bool presentation = false) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "holotrace";
  app.apiVersion = VK_API_VERSION_1_2;
  std::vector<const char*> layers, extensions;
  if (validation) {
    if (!hasLayer(kValidationLayer)) {
      throw GpuError(
          "--validation: layer VK_LAYER_KHRONOS_validation is not installed (apt-get install vulkan-validationlayers)");
    }
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  if (presentation) {
    for (const char* name : presentationExtensions()) extensions.push_back(name);
  }
  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ci.pApplicationInfo = &app;
  ci.enabledLayerCount = static_cast<uint32_t>(layers.size());
  ci.ppEnabledLayerNames = layers.data();
  ci.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  ci.ppEnabledExtensionNames = extensions.data();
  VkInstance instance = VK_NULL_HANDLE;
  HT_VK(vkCreateInstance(&ci, nullptr, &instance));
  if (validation && impl) {
    VkDebugUtilsMessengerCreateInfoEXT mi{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    mi.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    mi.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    mi.pfnUserCallback = onValidationMessage;
    mi.pUserData = impl;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    if (create) HT_VK(create(instance, &mi, nullptr, messenger));
  }
  return instance;
}

std::string typeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
  }
}

int typeRank(const std::string& type) {  // lower = preferred
  if (type == "discrete") return 0;
  if (type == "integrated") return 1;
  if (type == "virtual") return 2;
  if (type == "cpu") return 3;
  return 4;
}

DeviceInfo describe(VkPhysicalDevice physical, uint32_t index) {
  VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  subgroup.pNext = &driver;
  VkPhysicalDeviceFloatControlsProperties floatControls{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FLOAT_CONTROLS_PROPERTIES};
  driver.pNext = &floatControls;
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props.pNext = &subgroup;
  vkGetPhysicalDeviceProperties2(physical, &props);
  VkPhysicalDeviceMaintenance3Properties m3{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
  VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props2.pNext = &m3;
  vkGetPhysicalDeviceProperties2(physical, &props2);

  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  features.pNext = &f12;
  vkGetPhysicalDeviceFeatures2(physical, &features);

  const VkPhysicalDeviceProperties& p = props.properties;
  DeviceInfo info;
  info.index = index;
  info.name = p.deviceName;
  info.type = typeName(p.deviceType);
  info.apiVersion = std::to_string(VK_API_VERSION_MAJOR(p.apiVersion)) + "." +
                    std::to_string(VK_API_VERSION_MINOR(p.apiVersion)) + "." +
                    std::to_string(VK_API_VERSION_PATCH(p.apiVersion));
  info.driver = std::string(driver.driverName) + " " + driver.driverInfo;
  info.maxStorageBufferRange = p.limits.maxStorageBufferRange;
  info.maxMemoryAllocationSize = m3.maxMemoryAllocationSize;
  info.maxComputeWorkGroupInvocations = p.limits.maxComputeWorkGroupInvocations;
  info.maxTexelBufferElements = p.limits.maxTexelBufferElements;
  info.subgroupSize = subgroup.subgroupSize;
  info.timestampPeriodNs = p.limits.timestampPeriod;
  info.shaderFloat64 = features.features.shaderFloat64 == VK_TRUE;
  info.denormPreserveFloat32 = floatControls.shaderDenormPreserveFloat32 == VK_TRUE;
  info.bufferDeviceAddress = f12.bufferDeviceAddress == VK_TRUE;
  const VkSubgroupFeatureFlags neededSubgroup =
      VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_BALLOT_BIT | VK_SUBGROUP_FEATURE_ARITHMETIC_BIT;
  if (p.apiVersion < VK_API_VERSION_1_2)
    info.unusableReason = "Vulkan 1.2 required";
  else if (!info.bufferDeviceAddress)
    info.unusableReason = "bufferDeviceAddress not supported";
  else if (!features.features.shaderInt64)
    info.unusableReason = "shaderInt64 not supported";
  else if (!info.shaderFloat64)
    info.unusableReason = "shaderFloat64 not supported (watertight fallback needs it)";
  else if ((subgroup.supportedOperations & neededSubgroup) != neededSubgroup ||
           !(subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT))
    info.unusableReason = "subgroup basic/ballot/arithmetic in compute not supported";
  else if (p.limits.timestampComputeAndGraphics != VK_TRUE)
    info.unusableReason = "timestamps on compute queues not supported";
  info.usable = info.unusableReason.empty();
  return info;
}

#ifdef HT_SANITIZED_BUILD
// Sanitized builds only (the test suite's build-asan). LeakSanitizer names a leak's modules when the process exits,
// and tests/lsan.supp suppresses the blocks that lavapipe and the Vulkan loader keep for good. vkDestroyInstance
// unloads the ICD and its layers, though, so at exit a kept driver block's 2-frame stack points into unmapped or
// reused memory, matches no suppression and fails the process (seen in holotraced as "libOpenImageIO+0x47455" and
// "libcrypto+0x3a455" for one lavapipe PC, allocated in vkEnumeratePhysicalDevices). Promoting every library
// loaded so far to RTLD_NODELETE keeps the driver where its stacks say it is, so suppressions keep working and a
// leak of ours is still reported. Names are gathered first: dlopen must not run inside dl_iterate_phdr.
void keepLoadedLibrariesMapped() {
  std::vector<std::string> names;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* out) {
        if (info->dlpi_name && info->dlpi_name[0])
          static_cast<std::vector<std::string>*>(out)->emplace_back(info->dlpi_name);
        return 0;
      },
      &names);
  for (const std::string& name : names) dlopen(name.c_str(), RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE);
}
#endif

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
  uint32_t count = 0;
  HT_VK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  HT_VK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
#ifdef HT_SANITIZED_BUILD
  keepLoadedLibrariesMapped();
#endif
  return devices;
}

// Automatic choice: the usable device of the best type (discrete > integrated > virtual > cpu).
int chooseDevice(const std::vector<DeviceInfo>& infos) {
  int best = -1;
  for (const DeviceInfo& d : infos) {
    if (!d.usable) continue;
    if (best < 0 || typeRank(d.type) < typeRank(infos[static_cast<size_t>(best)].type))
      best = static_cast<int>(d.index);
  }
  return best;
}

uint32_t computeQueueFamily(VkPhysicalDevice physical) {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, families.data());
  for (uint32_t i = 0; i < count; ++i) {  // prefer a compute family with timestamps
    if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && families[i].timestampValidBits > 0) return i;
  }
  throw GpuError("the chosen Vulkan device has no compute queue with timestamps");
}

}  // namespace

std::vector<DeviceInfo> VulkanContext::listDevices() {
  VkInstance instance = createInstance(false, nullptr, nullptr);
  std::vector<DeviceInfo> infos;
  auto devices = physicalDevices(instance);
  for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describe(devices[i], i));
  vkDestroyInstance(instance, nullptr);
  return infos;
}

VulkanContext::VulkanContext(const Options& options) : impl_(std::make_unique<Impl>()) {
  Impl& v = *impl_;
  v.exactFloat.noContraction = !options.fusedFloatMath;
  v.mapDeviceMemory = options.mapDeviceMemory;
  v.instance = createInstance(options.validation, &v, &v.messenger, options.presentation);
  auto devices = physicalDevices(v.instance);
  if (devices.empty())
    throw GpuError("no Vulkan device found (install mesa-vulkan-drivers for the lavapipe CPU driver)");
  std::vector<DeviceInfo> infos;
  for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describe(devices[i], i));
  int chosen = options.deviceIndex;
  if (chosen >= 0) {
    if (static_cast<size_t>(chosen) >= devices.size()) {
      throw GpuError("--device " + std::to_string(chosen) + ": only " + std::to_string(devices.size()) +
                     " Vulkan device(s) present (see `holotrace info`)");
    }
    if (!infos[static_cast<size_t>(chosen)].usable) {
      throw GpuError("--device " + std::to_string(chosen) + " (" + infos[static_cast<size_t>(chosen)].name +
                     ") cannot run holotrace: " + infos[static_cast<size_t>(chosen)].unusableReason);
    }
  } else {
    chosen = chooseDevice(infos);
    if (chosen < 0)
      throw GpuError("no usable Vulkan device: " + infos.front().name + ": " + infos.front().unusableReason);
  }
  v.physical = devices[static_cast<size_t>(chosen)];
  v.info = infos[static_cast<size_t>(chosen)];
  v.exactFloat.preserveDenormals = v.exactFloat.noContraction && v.info.denormPreserveFloat32;
  v.queueFamily = computeQueueFamily(v.physical);
  vkGetPhysicalDeviceMemoryProperties(v.physical, &v.memoryProperties);

  float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = v.queueFamily;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  f12.bufferDeviceAddress = VK_TRUE;
  f12.scalarBlockLayout = VK_TRUE;
  f12.hostQueryReset = VK_TRUE;
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  features.pNext = &f12;
  features.features.shaderInt64 = VK_TRUE;
  features.features.shaderFloat64 = VK_TRUE;
  std::vector<const char*> deviceExtensions;
  if (options.presentation) {
    if (!hasDeviceExtension(v.physical, kSwapchainExtension)) {
      throw GpuError("presenting to a display needs VK_KHR_swapchain, which " + v.info.name + " does not offer");
    }
    deviceExtensions.push_back(kSwapchainExtension);
    // The display sink's storage-write path writes BGRA swapchain images from a shader without a format qualifier
    // (present/frame_transfer.h); enabled where offered, the sink checks it before choosing that path.
    VkPhysicalDeviceFeatures offered;
    vkGetPhysicalDeviceFeatures(v.physical, &offered);
    features.features.shaderStorageImageWriteWithoutFormat = offered.shaderStorageImageWriteWithoutFormat;
  }
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.pNext = &features;
  dci.enabledExtensionCount = static_cast<uint32_t>(deviceExtensions.size());
  dci.ppEnabledExtensionNames = deviceExtensions.data();
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  HT_VK(vkCreateDevice(v.physical, &dci, nullptr, &v.device));
  vkGetDeviceQueue(v.device, v.queueFamily, 0, &v.queue);
  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pci.queueFamilyIndex = v.queueFamily;
  HT_VK(vkCreateCommandPool(v.device, &pci, nullptr, &v.commandPool));
  v.pipelines = std::make_unique<PipelineLibrary>(v);
}

VulkanContext::~VulkanContext() {
  Impl& v = *impl_;
  if (v.device) {
    vkDeviceWaitIdle(v.device);
    v.pipelines.reset();
    vkDestroyCommandPool(v.device, v.commandPool, nullptr);
    vkDestroyDevice(v.device, nullptr);
  }
  if (v.messenger) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(v.instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(v.instance, v.messenger, nullptr);
  }
  if (v.instance) vkDestroyInstance(v.instance, nullptr);
}

const DeviceInfo& VulkanContext::device() const { return impl_->info; }

void checkVulkan(VkResult result, const char* call) { checkVk(result, call); }

VulkanHandles vulkanHandles(VulkanContext& context) {
  VulkanContext::Impl& v = context.impl();
  return VulkanHandles{v.instance, v.physical, v.device, v.queue, v.queueFamily, v.commandPool};
}
uint32_t VulkanContext::validationMessageCount() const { return impl_->validationMessages.load(); }

}  // namespace ht::gpu
