// display_model_registry.cpp - the rows of display_model_registry.h, one per model, and the dispatch through them.
#include "camera_models/display_model_registry.h"

#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "camera_models/capture_grid_setup.h"
#include "camera_models/integral_setup.h"
#include "camera_models/lenticular_params.h"
#include "camera_models/oblique_setup.h"
#include "camera_models/pinhole_params.h"
#include "camera_models/projector_setup.h"
#include "camera_models/quilt_setup.h"
#include "camera_models/ray_table.h"
#include "common/error.h"

namespace ht {
namespace {

using detail::JsonLocation;
using gpu_shared::CameraBlock;
using nlohmann::json;

// --- setup: config -> camera --------------------------------------------------------------------------------------

template <auto make>
FrameCamera fromConfig(const DisplayConfig& config, const Bounds3& bounds, std::shared_ptr<const RayTable>) {
  return make(config, bounds);
}

FrameCamera quiltCamera(const DisplayConfig& config, const Bounds3& bounds, std::shared_ptr<const RayTable>) {
  return makeQuiltParams(config, bounds, defaultQuiltLayout(config));
}

FrameCamera rayTableCamera(const DisplayConfig& config, const Bounds3& bounds, std::shared_ptr<const RayTable> table) {
  if (!table) {
    throw ConfigError(config.sourcePath, "rayTable.file", "(not loaded)",
                      "a ray table read from the file before the camera is made (a caller bug)");
  }
  return RayTableCamera{makeRayTableParams(config, *table, bounds), std::move(table)};
}

// --- frame shapes -------------------------------------------------------------------------------------------------

std::uint32_t whole(float value) { return static_cast<std::uint32_t>(value); }

FrameShape subpixelPanel(DisplayModel model, float width, float height) {
  return {static_cast<std::uint32_t>(model), whole(width), whole(height), 1, 3};
}

// A grid of views: x columns, y rows, z x w pixels each.
FrameShape viewGrid(DisplayModel model, const glm::ivec4& grid) {
  return {static_cast<std::uint32_t>(model), static_cast<std::uint32_t>(grid.z), static_cast<std::uint32_t>(grid.w),
          static_cast<std::uint32_t>(grid.x) * static_cast<std::uint32_t>(grid.y), 1};
}

FrameShape lenticularShape(const FrameCamera& camera) {
  const auto& p = std::get<gpu_shared::LenticularParams>(camera);
  return subpixelPanel(DisplayModel::Lenticular, p.panel.x, p.panel.y);
}

FrameShape pinholeShape(const FrameCamera& camera) {
  const auto& p = std::get<gpu_shared::PinholeParams>(camera);
  return {gpu_shared::HT_MODEL_PINHOLE, whole(p.lens.z), whole(p.lens.w), 1, 1};
}

FrameShape quiltShape(const FrameCamera& camera) {
  const auto& p = std::get<gpu_shared::QuiltParams>(camera);
  return {gpu_shared::HT_MODEL_QUILT, static_cast<std::uint32_t>(p.tiles.z), static_cast<std::uint32_t>(p.tiles.w),
          static_cast<std::uint32_t>(p.views.x), 1};
}

FrameShape projectorArrayShape(const FrameCamera& camera) {
  const auto& p = std::get<gpu_shared::ProjectorArrayParams>(camera);
  const FrameShape shape{gpu_shared::HT_MODEL_PROJECTOR_ARRAY, whole(p.projector[0][0].w), whole(p.projector[0][1].w),
                         whole(p.observer.w), 1};
  if (shape.views > gpu_shared::HT_MAX_PROJECTORS) {
    throw GpuError("projector array of " + std::to_string(shape.views) + " projectors exceeds " +
                   std::to_string(gpu_shared::HT_MAX_PROJECTORS));
  }
  return shape;
}

FrameShape integralShape(const FrameCamera& camera) {
  const auto& p = std::get<gpu_shared::IntegralParams>(camera);
  return subpixelPanel(DisplayModel::Integral, p.panel.x, p.panel.y);
}

FrameShape captureGridShape(const FrameCamera& camera) {
  return viewGrid(DisplayModel::CaptureGrid, std::get<gpu_shared::CaptureGridParams>(camera).grid);
}

FrameShape obliqueShape(const FrameCamera& camera) {
  return viewGrid(DisplayModel::Oblique, std::get<gpu_shared::ObliqueParams>(camera).grid);
}

FrameShape rayTableShape(const FrameCamera& camera) {
  const auto& p = std::get<RayTableCamera>(camera);
  if (!p.table) throw GpuError("ray-table camera without a table");
  return {gpu_shared::HT_MODEL_RAY_TABLE, p.table->width, p.table->height, 1, 1};
}

// --- GPU blocks ---------------------------------------------------------------------------------------------------

template <class Params, Params CameraBlock::*member>
void writeParams(const FrameCamera& camera, CameraBlock& block) {
  block.*member = std::get<Params>(camera);
}

void writeRayTable(const FrameCamera& camera, CameraBlock& block) {
  block.rayTable = std::get<RayTableCamera>(camera).params;
}

// --- view layouts -------------------------------------------------------------------------------------------------

std::optional<QuiltLayout> noQuilt(const DisplayConfig&, const FrameCamera&, const FrameShape&) { return std::nullopt; }

std::optional<QuiltLayout> deviceQuilt(const DisplayConfig& config, const FrameCamera&, const FrameShape&) {
  return defaultQuiltLayout(config);
}

// A view grid (capture grid, oblique directions) as a quilt: columns x rows tiles of the view size, view 0
// bottom-left.
template <class Params>
std::optional<QuiltLayout> gridQuilt(const DisplayConfig&, const FrameCamera& camera, const FrameShape& shape) {
  const glm::ivec4& grid = std::get<Params>(camera).grid;
  const auto columns = static_cast<std::uint32_t>(grid.x), rows = static_cast<std::uint32_t>(grid.y);
  return makeQuiltLayout(columns, rows, columns * shape.width, rows * shape.height,
                         static_cast<double>(shape.width) / shape.height);
}

// --- config sections ----------------------------------------------------------------------------------------------

template <auto member>
bool has(const DisplayConfig& config) {
  return (config.*member).has_value();
}

template <auto member, auto parse>
void parseInto(const JsonLocation& at, const json& section, const std::filesystem::path&, DisplayConfig& config) {
  config.*member = parse(at, section);
}

void parseRayTableSection(const JsonLocation& at, const json& section, const std::filesystem::path& baseDir,
                          DisplayConfig& config) {
  config.rayTable = parseRayTable(at, section, baseDir);
}

// --- the rows -----------------------------------------------------------------------------------------------------

// A small Looking Glass Portrait calibration (docs/OPTICS.md §1.1 values, a 72 x 96 panel) for the examples.
#define HT_EXAMPLE_CALIBRATION                                                                           \
  R"("calibration":{"pitch":52.594383239746094,"slope":-7.21152925491333,"center":0.40277382731437683,)" \
  R"("viewCone":40,"invView":1,"DPI":324,"screenW":72,"screenH":96,"flipImageX":0,"flipImageY":0,"flipSubp":0})"

const DisplayModelRow kRows[] = {
    {DisplayModel::Lenticular, "lenticular", true, "", nullptr, nullptr, fromConfig<makeLenticularParams>,
     lenticularShape, writeParams<gpu_shared::LenticularParams, &CameraBlock::lenticular>, noQuilt,
     R"({"model":"lenticular",)" HT_EXAMPLE_CALIBRATION "}"},
    {DisplayModel::Pinhole, "pinhole", true, "", nullptr, nullptr, fromConfig<makePinholeParams>, pinholeShape,
     writeParams<gpu_shared::PinholeParams, &CameraBlock::pinhole>, noQuilt,
     R"({"model":"pinhole","pinhole":{"width":32,"height":24,"eye":[0,0.3,3],"lookAt":[0,0,0]}})"},
    {DisplayModel::Quilt, "quilt", false, "", nullptr, nullptr, quiltCamera, quiltShape,
     writeParams<gpu_shared::QuiltParams, &CameraBlock::quilt>, deviceQuilt,
     R"({"model":"lenticular",)" HT_EXAMPLE_CALIBRATION "}"},
    {DisplayModel::ProjectorArray, "projector-array", true, "projectorArray",
     parseInto<&DisplayConfig::projectorArray, parseProjectorArray>, has<&DisplayConfig::projectorArray>,
     fromConfig<makeProjectorArrayParams>, projectorArrayShape,
     writeParams<gpu_shared::ProjectorArrayParams, &CameraBlock::projectors>, noQuilt,
     R"({"model":"projector-array","projectorArray":{"screen":{"width":800,"height":600},"observerDistance":2500,)"
     R"("image":{"width":20,"height":15},"projectors":[{"position":[-300,0,-1500]},{"position":[300,0,-1500]}]}})"},
    {DisplayModel::Integral, "integral", true, "integral", parseInto<&DisplayConfig::integral, parseIntegral>,
     has<&DisplayConfig::integral>, fromConfig<makeIntegralParams>, integralShape,
     writeParams<gpu_shared::IntegralParams, &CameraBlock::integral>, noQuilt,
     R"({"model":"integral","integral":{"panelWidth":32,"panelHeight":24,"pixelPitch":0.1,"lensPitch":0.77,)"
     R"("gap":2.0,"focalLength":2.5,"viewerDistance":500}})"},
    {DisplayModel::CaptureGrid, "capture-grid", true, "captureGrid",
     parseInto<&DisplayConfig::captureGrid, parseCaptureGrid>, has<&DisplayConfig::captureGrid>,
     fromConfig<makeCaptureGridParams>, captureGridShape,
     writeParams<gpu_shared::CaptureGridParams, &CameraBlock::captureGrid>, gridQuilt<gpu_shared::CaptureGridParams>,
     R"({"model":"capture-grid","captureGrid":{"columns":3,"rows":2,"spacing":[0.1,0.1],"distance":2.5,)"
     R"("window":{"width":1.6,"height":1.2},"image":{"width":16,"height":12}}})"},
    {DisplayModel::Oblique, "oblique", true, "oblique", parseInto<&DisplayConfig::oblique, parseOblique>,
     has<&DisplayConfig::oblique>, fromConfig<makeObliqueParams>, obliqueShape,
     writeParams<gpu_shared::ObliqueParams, &CameraBlock::oblique>, gridQuilt<gpu_shared::ObliqueParams>,
     R"({"model":"oblique","oblique":{"columns":3,"rows":2,"horizontalConeDeg":40,"verticalConeDeg":20,)"
     R"("image":{"width":12,"height":12}}})"},
    {DisplayModel::RayTable, "ray-table", true, "rayTable", parseRayTableSection, has<&DisplayConfig::rayTable>,
     rayTableCamera, rayTableShape, writeRayTable, noQuilt, R"({"model":"ray-table","rayTable":{"file":"table.exr"}})"},
};
#undef HT_EXAMPLE_CALIBRATION

static_assert(std::size(kRows) == gpu_shared::HT_MODEL_COUNT, "one registry row per model id");

}  // namespace

std::span<const DisplayModelRow> displayModels() { return kRows; }

const DisplayModelRow& displayModelRow(DisplayModel model) {
  const auto index = static_cast<std::size_t>(model);
  if (index >= std::size(kRows) || kRows[index].model != model) {
    throw ConfigError("(display model registry)", "model", std::to_string(index),
                      "a model id below " + std::to_string(std::size(kRows)) + " with its row at that index");
  }
  return kRows[index];
}

const DisplayModelRow* findConfigModel(std::string_view name) {
  for (const DisplayModelRow& row : kRows) {
    if (row.inConfigs && row.name == name) return &row;
  }
  return nullptr;
}

std::string_view displayModelName(DisplayModel model) { return displayModelRow(model).name; }

FrameShape frameShape(const FrameCamera& camera) { return displayModelRow(cameraModel(camera)).shape(camera); }

gpu_shared::CameraBlock cameraBlock(const FrameCamera& camera) {
  CameraBlock block{};
  displayModelRow(cameraModel(camera)).writeBlock(camera, block);
  return block;
}

}  // namespace ht
