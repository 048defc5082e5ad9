// color.h - colour-space helpers shared by the loaders and the procedural scenes.
#pragma once

namespace ht {

// sRGB-encoded value in [0,1] -> linear value (IEC 61966-2-1 decoding curve; glTF 2.0 baseColorTexture
// colour channels are sRGB-encoded, alpha is linear: spec, Materials > Metallic-Roughness Material).
float srgbToLinear(float encoded);

}  // namespace ht
