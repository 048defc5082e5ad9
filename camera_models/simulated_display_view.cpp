// simulated_display_view.cpp - see simulated_display_view.h.
#include "camera_models/simulated_display_view.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "camera_models/integral_setup.h"
#include "camera_models/lenticular_params.h"
#include "camera_models/projector_setup.h"
#include "common/error.h"

namespace ht {
namespace {

[[noreturn]] void throwNoSimulator(const DisplayConfig& config) {
  throw ConfigError(config.sourcePath, "model", std::string(displayModelName(config.model)),
                    "expected a lenticular, projector-array or integral display (the models with a simulated viewer)");
}

// All projectors must share one image size: the simulator takes one stack of images.
glm::uvec2 projectorImageSize(const DisplayConfig& config) {
  const auto& projectors = config.projectorArray->projectors;
  const glm::uvec2 size(projectors.front().width, projectors.front().height);
  for (std::size_t k = 1; k < projectors.size(); ++k) {
    if (projectors[k].width != size.x || projectors[k].height != size.y) {
      throw ConfigError(config.sourcePath, "projectorArray.projectors[" + std::to_string(k) + "].image",
                        std::to_string(projectors[k].width) + "x" + std::to_string(projectors[k].height),
                        "the simulated viewer needs one image size for every projector");
    }
  }
  return size;
}

// Alpha 1, the colour as the eye sees it: the projector simulator's colour is a normalised blend and its alpha the
// brightness toward the eye (so colour times alpha); the integral one already averages black into points off the LCD
// (its alpha only counts them), the lenticular one has alpha 1.
SimulatedView overBlack(SimulatedView view, bool scaleByAlpha) {
  for (std::size_t i = 0; i < view.rgba.size(); i += 4) {
    if (scaleByAlpha) {
      for (std::size_t c = 0; c < 3; ++c) view.rgba[i + c] *= view.rgba[i + 3];
    }
    view.rgba[i + 3] = 1.0f;
  }
  return view;
}

void checkImages(const DisplayConfig& config, const DisplayFrameImages& images) {
  const SimulatedViewShape shape = simulatedViewShape(config);
  if (images.width != shape.inputWidth || images.height != shape.inputHeight || images.views != shape.inputViews ||
      images.rgba.size() != std::size_t(images.width) * images.height * images.views * 4) {
    throw Error("display '" + config.name + "' (" + std::string(displayModelName(config.model)) + ") shows " +
                std::to_string(shape.inputViews) + " image(s) of " + std::to_string(shape.inputWidth) + "x" +
                std::to_string(shape.inputHeight) + ", got " + std::to_string(images.views) + " of " +
                std::to_string(images.width) + "x" + std::to_string(images.height) +
                " (render it for this display: holotrace render --display ...)");
  }
}

}  // namespace

SimulatedViewShape simulatedViewShape(const DisplayConfig& config) {
  SimulatedViewShape shape;
  switch (config.model) {
    case DisplayModel::Lenticular: {
      const PanelLayout panel = panelLayout(config);
      shape = {panel.width, panel.height, 1, panel.width, panel.height};
      break;
    }
    case DisplayModel::ProjectorArray: {
      const glm::uvec2 size = projectorImageSize(config);
      const auto& array = *config.projectorArray;
      const auto height = std::uint32_t(std::max(1.0, std::round(size.x * array.screenHeight / array.screenWidth)));
      shape = {size.x, size.y, std::uint32_t(array.projectors.size()), size.x, height};
      break;
    }
    case DisplayModel::Integral:
      shape = {config.integral->panelWidth, config.integral->panelHeight, 1, config.integral->panelWidth,
               config.integral->panelHeight};
      break;
    default: throwNoSimulator(config);
  }
  return shape;
}

SimulatedView simulateDisplayView(const DisplayConfig& config, const DisplayFrameImages& images, glm::dvec3 eye,
                                  unsigned threads) {
  checkImages(config, images);
  switch (config.model) {
    case DisplayModel::Lenticular:
      return overBlack(simulateLenticularView(makeLenticularParams(config, Bounds3{}), images.rgba, eye, threads),
                       false);
    case DisplayModel::ProjectorArray: {
      const SimulatedViewShape shape = simulatedViewShape(config);
      const glm::dvec2 screen(config.projectorArray->screenWidth, config.projectorArray->screenHeight);
      return overBlack(
          simulateProjectorView(makeProjectorArrayParams(config, Bounds3{}), screen, images.width, images.height,
                                images.rgba, eye, {shape.outputWidth, shape.outputHeight}, threads),
          true);
    }
    case DisplayModel::Integral:
      return overBlack(simulateIntegralView(makeIntegralParams(config, Bounds3{}), images.rgba, eye, threads), false);
    default: throwNoSimulator(config);
  }
}

std::vector<glm::dvec3> displayViewConeEyes(const DisplayConfig& config, std::uint32_t count) {
  switch (config.model) {
    case DisplayModel::Lenticular: return lenticularViewConeEyes(makeLenticularParams(config, Bounds3{}), count);
    case DisplayModel::ProjectorArray: return projectorViewConeEyes(makeProjectorArrayParams(config, Bounds3{}), count);
    case DisplayModel::Integral:
      return integralViewConeEyes(makeIntegralParams(config, Bounds3{}), config.integral->viewerDistance, count);
    default: throwNoSimulator(config);
  }
}

}  // namespace ht
