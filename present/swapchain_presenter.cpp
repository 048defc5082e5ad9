// swapchain_presenter.cpp - surface, swapchain (re)creation, staging upload, copy, present (swapchain_presenter.h).
#include "present/swapchain_presenter.h"

// clang-format off
#include <xcb/xcb.h>
#include <vulkan/vulkan.h>
#include <vulkan/vulkan_xcb.h>
// clang-format on

#include <algorithm>
#include <cstring>
#include <vector>

#include "gpu/vulkan_handles.h"
#include "present/spirv/panel_store.spv.h"

namespace ht::present {
namespace {

constexpr std::uint64_t kAcquireTimeoutNs = 1'000'000'000;  // 1 s: a free image takes one present at most
constexpr int kOutOfDateRetries = 3;

std::string formatName(VkFormat format) {
  switch (format) {
    case VK_FORMAT_B8G8R8A8_UNORM: return "B8G8R8A8_UNORM";
    case VK_FORMAT_R8G8B8A8_UNORM: return "R8G8B8A8_UNORM";
    case VK_FORMAT_B8G8R8A8_SRGB: return "B8G8R8A8_SRGB";
    case VK_FORMAT_R8G8B8A8_SRGB: return "R8G8B8A8_SRGB";
    default: return "VkFormat " + std::to_string(static_cast<int>(format));
  }
}

std::string modeName(VkPresentModeKHR mode) {
  switch (mode) {
    case VK_PRESENT_MODE_MAILBOX_KHR: return "MAILBOX";
    case VK_PRESENT_MODE_FIFO_KHR: return "FIFO";
    case VK_PRESENT_MODE_FIFO_RELAXED_KHR: return "FIFO_RELAXED";
    case VK_PRESENT_MODE_IMMEDIATE_KHR: return "IMMEDIATE";
    default: return "mode " + std::to_string(static_cast<int>(mode));
  }
}

bool isByteFormat(VkFormat f, bool srgb) {
  return srgb ? (f == VK_FORMAT_B8G8R8A8_SRGB || f == VK_FORMAT_R8G8B8A8_SRGB)
              : (f == VK_FORMAT_B8G8R8A8_UNORM || f == VK_FORMAT_R8G8B8A8_UNORM);
}

// UNORM (bytes copied as they are, displayed as sRGB) first, an _SRGB format only if no UNORM one is offered.
VkSurfaceFormatKHR chooseFormat(VkPhysicalDevice physical, VkSurfaceKHR surface) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, nullptr);
  std::vector<VkSurfaceFormatKHR> formats(count);
  vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, formats.data());
  for (bool srgb : {false, true}) {
    for (const VkSurfaceFormatKHR& f : formats) {
      if (f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR && isByteFormat(f.format, srgb)) return f;
    }
  }
  std::string offered;
  for (const VkSurfaceFormatKHR& f : formats) offered += " " + formatName(f.format);
  throw PresentError(
      "the display surface offers no 8-bit RGBA/BGRA format in the sRGB colour space (offered:" + offered + ")");
}

VkPresentModeKHR chooseMode(VkPhysicalDevice physical, VkSurfaceKHR surface, PresentModeChoice choice) {
  if (choice == PresentModeChoice::Fifo) return VK_PRESENT_MODE_FIFO_KHR;
  std::uint32_t count = 0;
  vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &count, nullptr);
  std::vector<VkPresentModeKHR> modes(count);
  vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &count, modes.data());
  bool mailbox = std::find(modes.begin(), modes.end(), VK_PRESENT_MODE_MAILBOX_KHR) != modes.end();
  return mailbox ? VK_PRESENT_MODE_MAILBOX_KHR : VK_PRESENT_MODE_FIFO_KHR;
}

VkCompositeAlphaFlagBitsKHR chooseAlpha(VkCompositeAlphaFlagsKHR supported) {
  for (VkCompositeAlphaFlagBitsKHR bit :
       {VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR, VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR,
        VK_COMPOSITE_ALPHA_PRE_MULTIPLIED_BIT_KHR, VK_COMPOSITE_ALPHA_POST_MULTIPLIED_BIT_KHR}) {
    if (supported & bit) return bit;
  }
  return VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
}

std::uint32_t hostVisibleMemoryType(VkPhysicalDevice physical, std::uint32_t typeBits) {
  VkPhysicalDeviceMemoryProperties props;
  vkGetPhysicalDeviceMemoryProperties(physical, &props);
  const VkMemoryPropertyFlags wanted = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  for (std::uint32_t i = 0; i < props.memoryTypeCount; ++i) {
    if ((typeBits & (1u << i)) && (props.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
  }
  throw PresentError("the Vulkan device has no host-visible coherent memory for the frame upload");
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to, VkAccessFlags srcAccess,
                  VkAccessFlags dstAccess, VkPipelineStageFlags srcStage, VkPipelineStageFlags dstStage) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = srcAccess;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 0, nullptr, 0, nullptr, 1, &b);
}

}  // namespace

// The storage-write path's compute pipeline and, per swapchain image, a view and a descriptor set
// (frame_transfer.h, shaders/panel_store.comp).
struct StoragePath {
  VkDevice device = VK_NULL_HANDLE;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  std::vector<VkImageView> views;
  std::vector<VkDescriptorSet> sets;

  void create(VkDevice d);
  void bindImages(const std::vector<VkImage>& images, VkFormat format, VkBuffer pixels, VkDeviceSize bytes);
  void releaseImages();
  void destroy();
};

void StoragePath::create(VkDevice d) {
  device = d;
  VkDescriptorSetLayoutBinding bindings[2] = {
      {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
  VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  li.bindingCount = 2;
  li.pBindings = bindings;
  gpu::checkVulkan(vkCreateDescriptorSetLayout(device, &li, nullptr, &setLayout), "vkCreateDescriptorSetLayout");
  VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, 2 * sizeof(std::uint32_t)};
  VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pli.setLayoutCount = 1;
  pli.pSetLayouts = &setLayout;
  pli.pushConstantRangeCount = 1;
  pli.pPushConstantRanges = &range;
  gpu::checkVulkan(vkCreatePipelineLayout(device, &pli, nullptr, &layout), "vkCreatePipelineLayout");
  VkShaderModuleCreateInfo mi{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  mi.codeSize = sizeof(ht_spv_panel_store);
  mi.pCode = ht_spv_panel_store;
  VkShaderModule module = VK_NULL_HANDLE;
  gpu::checkVulkan(vkCreateShaderModule(device, &mi, nullptr, &module), "vkCreateShaderModule");
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  ci.stage.module = module;
  ci.stage.pName = "main";
  ci.layout = layout;
  const VkResult r = vkCreateComputePipelines(device, VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline);
  vkDestroyShaderModule(device, module, nullptr);
  gpu::checkVulkan(r, "vkCreateComputePipelines");
}

void StoragePath::bindImages(const std::vector<VkImage>& images, VkFormat format, VkBuffer pixels, VkDeviceSize bytes) {
  releaseImages();
  const auto n = static_cast<std::uint32_t>(images.size());
  VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, n}, {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, n}};
  VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pi.maxSets = n;
  pi.poolSizeCount = 2;
  pi.pPoolSizes = sizes;
  gpu::checkVulkan(vkCreateDescriptorPool(device, &pi, nullptr, &pool), "vkCreateDescriptorPool");
  std::vector<VkDescriptorSetLayout> layouts(n, setLayout);
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool;
  ai.descriptorSetCount = n;
  ai.pSetLayouts = layouts.data();
  sets.resize(n);
  gpu::checkVulkan(vkAllocateDescriptorSets(device, &ai, sets.data()), "vkAllocateDescriptorSets");
  views.assign(n, VK_NULL_HANDLE);
  for (std::uint32_t i = 0; i < n; ++i) {
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = images[i];
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = format;
    vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    gpu::checkVulkan(vkCreateImageView(device, &vi, nullptr, &views[i]), "vkCreateImageView");
    VkDescriptorBufferInfo buffer{pixels, 0, bytes};
    VkDescriptorImageInfo image{VK_NULL_HANDLE, views[i], VK_IMAGE_LAYOUT_GENERAL};
    VkWriteDescriptorSet writes[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET},
                                      {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
    writes[0].dstSet = writes[1].dstSet = sets[i];
    writes[0].dstBinding = 0;
    writes[0].descriptorCount = 1;
    writes[0].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[0].pBufferInfo = &buffer;
    writes[1].dstBinding = 1;
    writes[1].descriptorCount = 1;
    writes[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    writes[1].pImageInfo = &image;
    vkUpdateDescriptorSets(device, 2, writes, 0, nullptr);
  }
}

void StoragePath::releaseImages() {
  for (VkImageView v : views) vkDestroyImageView(device, v, nullptr);
  views.clear();
  sets.clear();
  if (pool) vkDestroyDescriptorPool(device, pool, nullptr);
  pool = VK_NULL_HANDLE;
}

void StoragePath::destroy() {
  if (!device) return;
  releaseImages();
  if (pipeline) vkDestroyPipeline(device, pipeline, nullptr);
  if (layout) vkDestroyPipelineLayout(device, layout, nullptr);
  if (setLayout) vkDestroyDescriptorSetLayout(device, setLayout, nullptr);
  device = VK_NULL_HANDLE;
}

struct SwapchainPresenter::Impl {
  gpu::VulkanHandles vk;
  std::string display;
  PresentModeChoice choice = PresentModeChoice::Auto;
  FrameTransferChoice transferChoice = FrameTransferChoice::Auto;
  FrameTransfer transfer = FrameTransfer::Copy;
  StoragePath storage;
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  VkSwapchainKHR swapchain = VK_NULL_HANDLE;
  VkSurfaceFormatKHR format{};
  std::vector<VkImage> images;
  std::vector<VkSemaphore> copied;  // per swapchain image: the copy is done, present may read
  VkSemaphore acquired = VK_NULL_HANDLE;
  VkFence inFlight = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkBuffer staging = VK_NULL_HANDLE;
  VkDeviceMemory stagingMemory = VK_NULL_HANDLE;
  void* mapped = nullptr;
  VkDeviceSize stagingSize = 0;
  SwapchainInfo info;
  std::uint32_t recreations = 0;

  void createSurface(const XConnection& x, xcb_window_t window);
  void createSwapchain();
  void destroyImageSemaphores();
  void ensureStaging(VkDeviceSize size);
  void upload(const PanelFrame& frame);
  void recordCopy(VkImage image);
  void recordStore(std::uint32_t index);
  FrameTransfer chooseTransfer(const VkSurfaceCapabilitiesKHR& caps) const;
  void bindStorage();
  void recreate();
  void destroy();
};

void SwapchainPresenter::Impl::createSurface(const XConnection& x, xcb_window_t window) {
  VkXcbSurfaceCreateInfoKHR ci{VK_STRUCTURE_TYPE_XCB_SURFACE_CREATE_INFO_KHR};
  ci.connection = x.get();
  ci.window = window;
  gpu::checkVulkan(vkCreateXcbSurfaceKHR(vk.instance, &ci, nullptr, &surface), "vkCreateXcbSurfaceKHR");
  VkBool32 supported = VK_FALSE;
  vkGetPhysicalDeviceSurfaceSupportKHR(vk.physical, vk.queueFamily, surface, &supported);
  if (!supported) throw PresentError("the Vulkan device's queue cannot present to X display '" + display + "'");
}

void SwapchainPresenter::Impl::createSwapchain() {
  VkSurfaceCapabilitiesKHR caps;
  gpu::checkVulkan(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(vk.physical, surface, &caps),
                   "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
  if (caps.currentExtent.width == 0 || caps.currentExtent.height == 0)
    throw PresentError("the panel window has size 0");
  format = chooseFormat(vk.physical, surface);
  transfer = chooseTransfer(caps);
  VkPresentModeKHR mode = chooseMode(vk.physical, surface, choice);
  std::uint32_t count = std::max(caps.minImageCount, 3u);
  if (caps.maxImageCount > 0) count = std::min(count, caps.maxImageCount);
  VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  ci.surface = surface;
  ci.minImageCount = count;
  ci.imageFormat = format.format;
  ci.imageColorSpace = format.colorSpace;
  ci.imageExtent = caps.currentExtent;
  ci.imageArrayLayers = 1;
  ci.imageUsage =
      VkImageUsageFlags(transfer == FrameTransfer::Copy ? VK_IMAGE_USAGE_TRANSFER_DST_BIT : VK_IMAGE_USAGE_STORAGE_BIT);
  ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.preTransform = caps.currentTransform;
  ci.compositeAlpha = chooseAlpha(caps.supportedCompositeAlpha);
  ci.presentMode = mode;
  ci.clipped = VK_FALSE;  // every pixel is written: a covered part must still hold the frame (read back in tests)
  ci.oldSwapchain = swapchain;
  VkSwapchainKHR created = VK_NULL_HANDLE;
  gpu::checkVulkan(vkCreateSwapchainKHR(vk.device, &ci, nullptr, &created), "vkCreateSwapchainKHR");
  storage.releaseImages();  // views of the old swapchain's images go before those images
  if (swapchain) vkDestroySwapchainKHR(vk.device, swapchain, nullptr);
  swapchain = created;
  std::uint32_t n = 0;
  vkGetSwapchainImagesKHR(vk.device, swapchain, &n, nullptr);
  images.resize(n);
  vkGetSwapchainImagesKHR(vk.device, swapchain, &n, images.data());
  destroyImageSemaphores();
  VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  copied.assign(n, VK_NULL_HANDLE);
  for (VkSemaphore& s : copied) gpu::checkVulkan(vkCreateSemaphore(vk.device, &si, nullptr, &s), "vkCreateSemaphore");
  info = SwapchainInfo{caps.currentExtent.width, caps.currentExtent.height, n,
                       modeName(mode),           formatName(format.format), frameTransferName(transfer)};
  bindStorage();
}

FrameTransfer SwapchainPresenter::Impl::chooseTransfer(const VkSurfaceCapabilitiesKHR& caps) const {
  VkFormatProperties props;
  vkGetPhysicalDeviceFormatProperties(vk.physical, format.format, &props);
  VkPhysicalDeviceFeatures features;
  vkGetPhysicalDeviceFeatures(vk.physical, &features);  // the presentation context enables it where offered
  TransferAbilities a;
  a.surfaceUsage = caps.supportedUsageFlags;
  a.storageFormat =
      isByteFormat(format.format, false) && (props.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) != 0;
  a.writeWithoutFormat = features.shaderStorageImageWriteWithoutFormat == VK_TRUE;
  return chooseFrameTransfer(a, transferChoice);
}

// Storage path: the staging buffer (sized for this swapchain) and each image get their descriptor set.
void SwapchainPresenter::Impl::bindStorage() {
  if (transfer != FrameTransfer::StorageWrite) return;
  if (!storage.pipeline) storage.create(vk.device);
  const VkDeviceSize bytes = VkDeviceSize(info.width) * info.height * 4;
  ensureStaging(bytes);
  storage.bindImages(images, format.format, staging, bytes);
}

void SwapchainPresenter::Impl::destroyImageSemaphores() {
  for (VkSemaphore s : copied) vkDestroySemaphore(vk.device, s, nullptr);
  copied.clear();
}

void SwapchainPresenter::Impl::ensureStaging(VkDeviceSize size) {
  if (size <= stagingSize) return;
  if (staging) {
    vkDestroyBuffer(vk.device, staging, nullptr);
    vkFreeMemory(vk.device, stagingMemory, nullptr);
    staging = VK_NULL_HANDLE;
    stagingMemory = VK_NULL_HANDLE;
    stagingSize = 0;
  }
  VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bi.size = size;
  bi.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  gpu::checkVulkan(vkCreateBuffer(vk.device, &bi, nullptr, &staging), "vkCreateBuffer");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(vk.device, staging, &req);
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = hostVisibleMemoryType(vk.physical, req.memoryTypeBits);
  gpu::checkVulkan(vkAllocateMemory(vk.device, &ai, nullptr, &stagingMemory), "vkAllocateMemory");
  gpu::checkVulkan(vkBindBufferMemory(vk.device, staging, stagingMemory, 0), "vkBindBufferMemory");
  gpu::checkVulkan(vkMapMemory(vk.device, stagingMemory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
  stagingSize = size;
}

// RGBA bytes into the staging buffer in the swapchain's byte order (B and R swapped for a BGRA format).
void SwapchainPresenter::Impl::upload(const PanelFrame& frame) {
  ensureStaging(frame.rgba.size());
  auto* dst = static_cast<std::uint8_t*>(mapped);
  // The storage write stores RGBA values and the image puts the channels in its own order.
  const bool bgra = transfer == FrameTransfer::Copy &&
                    (format.format == VK_FORMAT_B8G8R8A8_UNORM || format.format == VK_FORMAT_B8G8R8A8_SRGB);
  if (!bgra) {
    std::memcpy(dst, frame.rgba.data(), frame.rgba.size());
    return;
  }
  // One 32-bit word per pixel with R and B exchanged (a loop the compiler vectorises).
  const std::size_t pixels = frame.rgba.size() / 4;
  for (std::size_t i = 0; i < pixels; ++i) {
    std::uint32_t p;
    std::memcpy(&p, frame.rgba.data() + 4 * i, 4);
    p = (p & 0xFF00FF00u) | ((p & 0x000000FFu) << 16) | ((p >> 16) & 0x000000FFu);
    std::memcpy(dst + 4 * i, &p, 4);
  }
}

void SwapchainPresenter::Impl::recordCopy(VkImage image) {
  gpu::checkVulkan(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  gpu::checkVulkan(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
  imageBarrier(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
               VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {info.width, info.height, 1};
  vkCmdCopyBufferToImage(cmd, staging, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  imageBarrier(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
               VK_ACCESS_TRANSFER_WRITE_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT);
  gpu::checkVulkan(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
}

void SwapchainPresenter::Impl::recordStore(std::uint32_t index) {
  gpu::checkVulkan(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  gpu::checkVulkan(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
  imageBarrier(cmd, images[index], VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, 0, VK_ACCESS_SHADER_WRITE_BIT,
               VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, storage.pipeline);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, storage.layout, 0, 1, &storage.sets[index], 0, nullptr);
  const std::uint32_t size[2] = {info.width, info.height};
  vkCmdPushConstants(cmd, storage.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof size, size);
  vkCmdDispatch(cmd, (info.width + 7) / 8, (info.height + 7) / 8, 1);
  imageBarrier(cmd, images[index], VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_ACCESS_SHADER_WRITE_BIT,
               0, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT);
  gpu::checkVulkan(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
}

void SwapchainPresenter::Impl::recreate() {
  vkDeviceWaitIdle(vk.device);
  createSwapchain();
  ++recreations;
}

void SwapchainPresenter::Impl::destroy() {
  if (!vk.device) return;
  vkDeviceWaitIdle(vk.device);
  destroyImageSemaphores();
  storage.destroy();
  if (swapchain) vkDestroySwapchainKHR(vk.device, swapchain, nullptr);
  if (surface) vkDestroySurfaceKHR(vk.instance, surface, nullptr);
  if (staging) vkDestroyBuffer(vk.device, staging, nullptr);
  if (stagingMemory) vkFreeMemory(vk.device, stagingMemory, nullptr);
  if (cmd) vkFreeCommandBuffers(vk.device, vk.commandPool, 1, &cmd);
  if (acquired) vkDestroySemaphore(vk.device, acquired, nullptr);
  if (inFlight) vkDestroyFence(vk.device, inFlight, nullptr);
}

SwapchainPresenter::SwapchainPresenter(gpu::VulkanContext& context, const XConnection& x, xcb_window_t window,
                                       PresentModeChoice mode, FrameTransferChoice transfer)
    : impl_(std::make_unique<Impl>()) {
  Impl& v = *impl_;
  v.vk = gpu::vulkanHandles(context);
  v.display = x.name();
  v.choice = mode;
  v.transferChoice = transfer;
  try {
    v.createSurface(x, window);
    v.createSwapchain();
    VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    gpu::checkVulkan(vkCreateSemaphore(v.vk.device, &si, nullptr, &v.acquired), "vkCreateSemaphore");
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fi.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    gpu::checkVulkan(vkCreateFence(v.vk.device, &fi, nullptr, &v.inFlight), "vkCreateFence");
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = v.vk.commandPool;
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    gpu::checkVulkan(vkAllocateCommandBuffers(v.vk.device, &ai, &v.cmd), "vkAllocateCommandBuffers");
  } catch (...) {
    v.destroy();
    throw;
  }
}

SwapchainPresenter::~SwapchainPresenter() { impl_->destroy(); }

PresentOutcome SwapchainPresenter::present(const PanelFrame& frame) {
  Impl& v = *impl_;
  for (int attempt = 0; attempt <= kOutOfDateRetries; ++attempt) {
    if (frame.width != v.info.width || frame.height != v.info.height ||
        frame.rgba.size() != std::size_t(frame.width) * frame.height * 4) {
      throw PresentError("frame of " + std::to_string(frame.width) + "x" + std::to_string(frame.height) +
                         " for a panel window of " + std::to_string(v.info.width) + "x" +
                         std::to_string(v.info.height));
    }
    gpu::checkVulkan(vkWaitForFences(v.vk.device, 1, &v.inFlight, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    std::uint32_t index = 0;
    VkResult r = vkAcquireNextImageKHR(v.vk.device, v.swapchain, kAcquireTimeoutNs, v.acquired, VK_NULL_HANDLE, &index);
    if (r == VK_ERROR_OUT_OF_DATE_KHR) {
      v.recreate();
      continue;
    }
    if (r == VK_ERROR_SURFACE_LOST_KHR) return PresentOutcome::SurfaceLost;
    if (r == VK_TIMEOUT || r == VK_NOT_READY) return PresentOutcome::Timeout;
    if (r != VK_SUBOPTIMAL_KHR) gpu::checkVulkan(r, "vkAcquireNextImageKHR");
    v.upload(frame);
    const bool copy = v.transfer == FrameTransfer::Copy;
    if (copy)
      v.recordCopy(v.images[index]);
    else
      v.recordStore(index);
    gpu::checkVulkan(vkResetFences(v.vk.device, 1, &v.inFlight), "vkResetFences");
    VkPipelineStageFlags waitStage = copy ? VK_PIPELINE_STAGE_TRANSFER_BIT : VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.waitSemaphoreCount = 1;
    si.pWaitSemaphores = &v.acquired;
    si.pWaitDstStageMask = &waitStage;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &v.cmd;
    si.signalSemaphoreCount = 1;
    si.pSignalSemaphores = &v.copied[index];
    gpu::checkVulkan(vkQueueSubmit(v.vk.queue, 1, &si, v.inFlight), "vkQueueSubmit");
    VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    pi.waitSemaphoreCount = 1;
    pi.pWaitSemaphores = &v.copied[index];
    pi.swapchainCount = 1;
    pi.pSwapchains = &v.swapchain;
    pi.pImageIndices = &index;
    VkResult p = vkQueuePresentKHR(v.vk.queue, &pi);
    if (p == VK_ERROR_SURFACE_LOST_KHR) return PresentOutcome::SurfaceLost;
    if (p == VK_ERROR_OUT_OF_DATE_KHR) {  // not shown: rebuild and show it again
      v.recreate();
      continue;
    }
    if (p == VK_SUBOPTIMAL_KHR || r == VK_SUBOPTIMAL_KHR) {  // shown; rebuild for the next frame
      v.recreate();
      return PresentOutcome::Presented;
    }
    gpu::checkVulkan(p, "vkQueuePresentKHR");
    return PresentOutcome::Presented;
  }
  throw PresentError("the panel's swapchain stayed out of date after " + std::to_string(kOutOfDateRetries) +
                     " rebuilds (is the window being resized?)");
}

const SwapchainInfo& SwapchainPresenter::info() const { return impl_->info; }
std::uint32_t SwapchainPresenter::recreations() const { return impl_->recreations; }

}  // namespace ht::present
