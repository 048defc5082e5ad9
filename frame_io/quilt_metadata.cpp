// quilt_metadata.cpp - see quilt_metadata.h.
#include "frame_io/quilt_metadata.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "camera_models/lenticular_params.h"
#include "common/error.h"

namespace ht::frame_io {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The quilt cameras' full view cone in degrees, rounded through float as in their GPU block (QuiltParams::camera.w).
// It depends on the calibration and depthiness only, not on the scene the cameras are aimed at.
double quiltViewConeDeg(const DisplayConfig& display) {
  const float coneRad = float(resolveLenticularCamera(display, Bounds3{}).viewConeRad);
  return double(coneRad) * 180.0 / kPi;
}

constexpr std::uint32_t kMaxQuiltCount = 1024;  // as the quilt name's counts (quilt_layout.h)

std::uint32_t metadataCount(const nlohmann::json& meta, const char* field, const std::string& fileName) {
  const auto it = meta.find(field);
  if (it == meta.end() || !it->is_number_unsigned() || it->get<std::uint64_t>() == 0 ||
      it->get<std::uint64_t>() > kMaxQuiltCount) {
    throw ConfigError(fileName, std::string("ImageDescription.") + field, it == meta.end() ? "(missing)" : it->dump(),
                      "expected an integer in [1, 1024] in holotrace quilt metadata");
  }
  return static_cast<std::uint32_t>(it->get<std::uint64_t>());
}

}  // namespace

std::optional<QuiltName> readQuiltMetadataLayout(const std::string& description, const std::string& fileName) {
  const nlohmann::json meta = nlohmann::json::parse(description, nullptr, /*allow_exceptions=*/false);
  if (!meta.is_object() || meta.value("generator", nlohmann::json()) != "holotrace") return std::nullopt;
  QuiltName name;
  name.columns = metadataCount(meta, "columns", fileName);
  name.rows = metadataCount(meta, "rows", fileName);
  const auto aspect = meta.find("aspect");
  if (aspect == meta.end() || !aspect->is_number() || !std::isfinite(aspect->get<double>()) ||
      !(aspect->get<double>() > 0.0)) {
    throw ConfigError(fileName, "ImageDescription.aspect", aspect == meta.end() ? "(missing)" : aspect->dump(),
                      "expected the render aspect W/H > 0 in holotrace quilt metadata");
  }
  name.aspect = aspect->get<double>();
  return name;
}

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
