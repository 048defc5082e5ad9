// color.cpp - sRGB transfer function.
#include "scene/color.h"

#include <cmath>

namespace ht {

// IEC 61966-2-1:1999 sRGB decoding (electro-optical transfer function):
//   c <= 0.04045 : c / 12.92
//   otherwise    : ((c + 0.055) / 1.055)^2.4
float srgbToLinear(float encoded) {
  if (encoded <= 0.04045f) return encoded / 12.92f;
  return std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

}  // namespace ht
