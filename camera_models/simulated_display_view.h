// simulated_display_view.h - the simulated viewer of simulated_view.h for any display config: picks the model's
// simulator, its scene-independent display-local frame (make*Params(config, Bounds3{})) and its eye line, and returns
// the picture as the eye sees it in a dark room (colour times the brightness that reaches the eye, alpha 1).
// `holotrace simulate`, the quilt-vs-direct benchmark (bench/) and the daemon-free oracle tests use it.
//
// Eye frames (docs/OPTICS.md §12): lenticular = the quilt cameras' frame, origin at the focal-rectangle centre, units
// of camera.size (with "auto" size: a focal rectangle 2 units high, cameras at z = D = 1/tan(fovy/2)); projector array
// and integral = their display units (screen / lens plane z = 0, viewer toward +z).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "camera_models/display_config.h"
#include "camera_models/simulated_view.h"

namespace ht {

// A display's frame as rendered: `views` images of width x height, linear RGBA, row 0 = top, view after view.
struct DisplayFrameImages {
  std::uint32_t width = 0, height = 0, views = 1;
  std::span<const float> rgba;
};

// What the display shows an eye at `eye`. Throws ConfigError for a model without a simulator (pinhole, capture grid,
// oblique, ray table), Error when the images do not have the display's size and count (the message names both).
// Lenticular: the native panel; projector array: the N projector images (output: the projector image width across
// the screen, height by the screen's aspect); integral: the LCD image.
SimulatedView simulateDisplayView(const DisplayConfig& config, const DisplayFrameImages& images, glm::dvec3 eye,
                                  unsigned threads = 0);

// `count` eyes across the model's view cone, left to right (simulated_view.h *ViewConeEyes). Throws ConfigError
// as simulateDisplayView.
std::vector<glm::dvec3> displayViewConeEyes(const DisplayConfig& config, std::uint32_t count);

// The size of the image simulateDisplayView returns, and the image size and count it expects.
struct SimulatedViewShape {
  std::uint32_t inputWidth = 0, inputHeight = 0, inputViews = 1;
  std::uint32_t outputWidth = 0, outputHeight = 0;
};
SimulatedViewShape simulatedViewShape(const DisplayConfig& config);

}  // namespace ht
