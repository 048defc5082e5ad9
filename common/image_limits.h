// image_limits.h - the one bound on image sizes: every width and height in pixels that holotrace reads (configs,
// calibrations, image files) or renders is at most kMaxImageSide. It keeps width * height * 4 floats per view and
// the 32-bit ray counts of a frame in range.
#pragma once
#include <cstdint>

namespace ht {

inline constexpr std::uint32_t kMaxImageSide = 32768;

}  // namespace ht
