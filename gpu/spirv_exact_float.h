// spirv_exact_float.h - makes a driver round a shader's float arithmetic as the C++ references do.
//
// Two freedoms that Vulkan gives a driver break bit-exact parity between a kernel and its C++ reference (the same
// shared source), and were seen on an NVIDIA H200 (docs/DRIVERS.md):
//  * Contraction. SPIR-V lets a driver fuse a*b + c into one fused multiply-add (one rounding instead of two)
//    unless the multiply or the add carries the NoContraction decoration (SPIR-V spec 3.20 "Decoration"). Where a
//    driver fuses depends on the surrounding code, so two pipelines inlining one shared function can round it
//    differently (the flattened and the two-level traversal). lavapipe fused too, as far as the host's FMA allowed.
//    The C++ is compiled with -ffp-contract=off.
//  * Denormals. Without the DenormPreserve execution mode (SPIR-V 1.4 / VK_KHR_shader_float_controls, core in
//    Vulkan 1.2) a driver may flush 32-bit denormals to zero; the host keeps them.
// makeFloatExact decorates the result of every float arithmetic instruction with NoContraction (what GLSL's
// `precise` does for one expression) and, where the device supports it, asks for 32-bit denormals to be preserved.
// Division and sqrt are not exact in Vulkan either (2.5 ULP): common/exact_division.h handles the quotients that
// must match.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

namespace ht::gpu {

struct ExactFloatOptions {
  bool noContraction = true;       // decorate every float arithmetic result NoContraction
  bool preserveDenormals = false;  // add OpCapability DenormPreserve + OpExecutionMode DenormPreserve 32 (needs
                                   // VkPhysicalDeviceVulkan12Properties::shaderDenormPreserveFloat32)
};

// `spirv` with, for options.noContraction, an `OpDecorate %result NoContraction` for the result of every
// OpFNegate, OpFAdd, OpFSub, OpFMul, OpFDiv, OpFRem, OpFMod, OpVectorTimesScalar, OpMatrixTimesScalar,
// OpVectorTimesMatrix, OpMatrixTimesVector, OpMatrixTimesMatrix, OpOuterProduct and OpDot that has none yet, placed
// after the module's last annotation instruction (logical layout, SPIR-V spec 2.4); and for
// options.preserveDenormals the execution mode of each entry point (after the others) and, with any, the
// capability (after the others). Needs SPIR-V 1.4 or later for the latter (no OpExtension is added). Throws GpuError on
// a module too short or malformed to walk (no header, a word count of 0, an instruction past the end).
std::vector<std::uint32_t> makeFloatExact(std::span<const std::uint32_t> spirv, const ExactFloatOptions& options);

// What a module asks of the driver (for tests): float arithmetic results and how many carry NoContraction, and
// whether the DenormPreserve capability and a 32-bit DenormPreserve execution mode are declared.
struct ExactFloatCount {
  std::uint32_t arithmetic = 0;
  std::uint32_t decorated = 0;
  bool denormCapability = false;
  std::uint32_t denormModes = 0;
};
ExactFloatCount countExactFloat(std::span<const std::uint32_t> spirv);

}  // namespace ht::gpu
