// quilt_file.cpp - see quilt_file.h.
#include "frame_io/quilt_file.h"

#include "camera_models/lenticular_params.h"
#include "common/error.h"
#include "frame_io/quilt_metadata.h"

namespace ht::frame_io {
namespace {

std::string countsText(std::uint32_t columns, std::uint32_t rows) {
  return std::to_string(columns) + "x" + std::to_string(rows);
}

// The display's screenW/screenH, the aspect a short-tagged quilt is taken to have been rendered with.
double displayAspect(const DisplayConfig& display) {
  if (!display.calibration) return 1.0;  // not lenticular: checkQuiltFitsDisplay refuses the display by its model
  return double(display.calibration->screenW) / double(display.calibration->screenH);
}

// The name's quilt tag; nullopt for a name without one (GCC's maybe-uninitialized analysis wants this spelled out).
std::optional<QuiltName> nameTag(const std::string& fileName) {
  std::optional<QuiltName> tag;
  if (hasQuiltTag(fileName)) tag.emplace(parseQuiltName(fileName));
  return tag;
}

void checkHints(const QuiltLayoutHints& hints) {
  if (hints.columns.has_value() != hints.rows.has_value()) {
    throw UsageError("quilt layout: give both columns and rows (e.g. --columns 8 --rows 6) or neither");
  }
}

}  // namespace

QuiltFileLayout resolveQuiltLayout(const ImageHeader& header, const std::string& fileName,
                                   const QuiltLayoutHints& hints, const DisplayConfig& display) {
  checkHints(hints);
  if (header.views != 1) {
    throw ConfigError(fileName, "views", std::to_string(header.views),
                      "expected a quilt as one image with all views tiled in it, not a multi-view file");
  }
  const std::optional<QuiltName> tag = nameTag(fileName);
  const std::optional<QuiltName> meta = readQuiltMetadataLayout(header.attribute("ImageDescription"), fileName);
  if (tag && meta && (tag->columns != meta->columns || tag->rows != meta->rows)) {
    throw ConfigError(fileName, "quilt name", countsText(tag->columns, tag->rows),
                      "the file's embedded metadata says " + countsText(meta->columns, meta->rows) +
                          " views; rename the file or give --columns and --rows");
  }
  QuiltFileLayout result;
  std::uint32_t columns = 0, rows = 0;
  if (hints.columns) {
    columns = *hints.columns, rows = *hints.rows, result.source = "options";
  } else if (tag) {
    columns = tag->columns, rows = tag->rows, result.source = "file name";
  } else if (meta) {
    columns = meta->columns, rows = meta->rows, result.source = "metadata";
  } else {
    throw ConfigError(fileName, "quilt name", "\"" + fileName + "\"",
                      "no quilt layout: expected a `_qs{columns}x{rows}a{aspect}` tag in the name (e.g. "
                      "take_qs8x6a0.75.png), holotrace quilt metadata in the file, or --columns and --rows");
  }
  double aspect = displayAspect(display);
  if (hints.aspect)
    aspect = *hints.aspect;
  else if (tag && tag->aspect)
    aspect = *tag->aspect;
  else if (meta && meta->aspect)
    aspect = *meta->aspect;
  result.layout = makeQuiltLayout(columns, rows, header.width, header.height, aspect);
  return result;
}

InterleavedQuilt interleaveQuiltFile(const std::filesystem::path& path, const DisplayConfig& display,
                                     const QuiltLayoutHints& hints, QuiltViewFilter filter, unsigned threads) {
  const std::string fileName = path.filename().string();
  InterleavedQuilt result;
  result.layout = resolveQuiltLayout(readImageHeader(path), fileName, hints, display);
  checkQuiltFitsDisplay(result.layout.layout, display, path.string());
  const ImageFile quilt = readImageFile(path);
  const gpu_shared::LenticularParams params = makeLenticularParams(display, Bounds3{});
  result.width = display.calibration->screenW;
  result.height = display.calibration->screenH;
  result.rgba = interleaveQuilt(quiltImageViews(result.layout.layout, quilt.rgba), params, filter, threads);
  return result;
}

}  // namespace ht::frame_io
