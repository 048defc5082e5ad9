// glsl_cpp.h - lets one header compile both as GLSL (Vulkan, glslang) and as C++20 with GLM.
//
// Shared headers (ray generation, intersection, node layouts) include this first. Rules for shared code,
// so that CPU reference and GPU kernel run the *same* arithmetic:
//   * write float literals with an `f` suffix (1.0f): otherwise C++ promotes to double and results differ;
//   * no swizzles beyond .x/.y/.z/.w (GLM swizzles are off);
//   * out/inout parameters through HT_OUT(T) / HT_INOUT(T);
//   * mark arithmetic that must not be contracted into FMA with HT_PRECISE (GLSL `precise`); C++ is
//     compiled with -ffp-contract=off for the same reason. Every pipeline is also created with no contraction at
//     all (gpu/spirv_exact_float.h); HT_PRECISE keeps its expressions unfused when a context allows fusing
//     (VulkanContext::Options::fusedFloatMath);
//   * divide and take square roots that C++ and GLSL must round alike with ht_div / ht_div3 / ht_sqrt
//     (common/exact_division.h): Vulkan's division and sqrt may be several ULP off (docs/DRIVERS.md);
//   * wrap declarations in HT_SHARED_BEGIN / HT_SHARED_END (namespace ht::gpu_shared in C++).
#ifndef HT_GLSL_CPP_H
#define HT_GLSL_CPP_H

#ifdef VULKAN  // defined by glslang when compiling GLSL for Vulkan
#define HT_GLSL 1
#define HT_OUT(T) out T
#define HT_INOUT(T) inout T
#define HT_IN(T) in T
#define HT_INLINE
#define HT_PRECISE precise
#define HT_SHARED_BEGIN
#define HT_SHARED_END
#define HT_CONST const
#else
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>
#define HT_OUT(T) T&
#define HT_INOUT(T) T&
#define HT_IN(T) const T&
#define HT_INLINE inline
#define HT_PRECISE
#define HT_SHARED_BEGIN      \
  namespace ht::gpu_shared { \
  using namespace glm;       \
  using uint = std::uint32_t;
#define HT_SHARED_END }
#define HT_CONST inline constexpr
#endif

#endif  // HT_GLSL_CPP_H
