// panel_store.comp - the display sink's storage-write path (present/frame_transfer.h): one invocation per pixel
// copies the frame's RGBA8 bytes (one uint per pixel, R in the low byte, as the PNG holds them) into the swapchain
// image. The image is UNORM, so unpackUnorm4x8 -> imageStore gives back exactly the bytes (k/255 -> k); the image's
// channel order (BGRA) is the driver's business, hence no format qualifier (shaderStorageImageWriteWithoutFormat).
// CPU reference: the copy path (vkCmdCopyBufferToImage of the same bytes); the Xvfb tests compare both with the PNG.
#version 450

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, set = 0, binding = 0) readonly buffer Pixels { uint rgba[]; };
layout(set = 0, binding = 1) uniform writeonly image2D panel;

layout(push_constant) uniform Size { uint width; uint height; };

void main() {
  const uvec2 p = gl_GlobalInvocationID.xy;
  if (p.x >= width || p.y >= height) return;
  imageStore(panel, ivec2(p), unpackUnorm4x8(rgba[p.y * width + p.x]));
}
