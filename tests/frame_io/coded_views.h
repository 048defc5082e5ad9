// coded_views.h - a test frame whose pixels say where they come from: views x (w x h), pixel R, G, B = (view, x,
// row from the top), A = 1, so tiling, ordering and orientation mistakes show as wrong values.
#pragma once
#include <cstdint>
#include <vector>

namespace ht::test {

inline std::vector<float> codedViews(std::uint32_t views, std::uint32_t w, std::uint32_t h) {
  std::vector<float> rgba;
  for (std::uint32_t v = 0; v < views; ++v)
    for (std::uint32_t row = 0; row < h; ++row)
      for (std::uint32_t x = 0; x < w; ++x) rgba.insert(rgba.end(), {float(v), float(x), float(row), 1.0f});
  return rgba;
}

}  // namespace ht::test
