// quilt_metadata.cpp - see quilt_metadata.h.
#include "frame_io/quilt_metadata.h"

#include <nlohmann/json.hpp>

#include "camera_models/lenticular_params.h"

namespace ht::frame_io {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The quilt cameras' full view cone in degrees, rounded through float as in their GPU block (QuiltParams::camera.w).
// It depends on the calibration and depthiness only, not on the scene the cameras are aimed at.
double quiltViewConeDeg(const DisplayConfig& display) {
  const float coneRad = float(resolveLenticularCamera(display, Bounds3{}).viewConeRad);
  return double(coneRad) * 180.0 / kPi;
}

}  // namespace

std::string quiltMetadataJson(const DisplayConfig& display, const QuiltLayout& layout) {
  nlohmann::json meta;
  meta["generator"] = "holotrace";
  meta["display"] = display.name;
  meta["model"] = std::string(displayModelName(display.model));
  meta["views"] = layout.views();
  meta["columns"] = layout.columns;
  meta["rows"] = layout.rows;
  meta["aspect"] = layout.aspect;
  meta["quiltWidth"] = layout.quiltWidth;
  meta["quiltHeight"] = layout.quiltHeight;
  meta["tileWidth"] = layout.tileWidth;
  meta["tileHeight"] = layout.tileHeight;
  meta["viewOrder"] = "view 0 = bottom-left tile = leftmost (bottom) camera; left to right, then upward";
  if (display.model == DisplayModel::Lenticular) {
    meta["viewConeDeg"] = quiltViewConeDeg(display);
    meta["fovyDeg"] = display.camera.fovyDeg;
  }
  if (display.calibration) meta["calibration"] = nlohmann::json::parse(display.calibration->rawJson);
  return meta.dump(2);
}

}  // namespace ht::frame_io
