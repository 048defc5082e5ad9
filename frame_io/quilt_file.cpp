// quilt_file.cpp - see quilt_file.h.
#include "frame_io/quilt_file.h"

#include <algorithm>
#include <cctype>

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

// Columns, rows and render aspect from the file name's tag or, failing that, the metadata (the aspect from whichever
// has one); nullopt when neither gives columns and rows. Throws ConfigError when both give them and disagree.
std::optional<QuiltName> fileQuiltLayout(const ImageHeader& header, const std::string& fileName, std::string& source) {
  if (header.views != 1) {
    throw ConfigError(fileName, "views", std::to_string(header.views),
                      "expected a quilt as one image with all views tiled in it, not a multi-view file");
  }
  const std::optional<QuiltName> tag = nameTag(fileName);
  const std::optional<QuiltName> meta = readQuiltMetadataLayout(header.attribute("ImageDescription"), fileName);
  if (tag && meta && (tag->columns != meta->columns || tag->rows != meta->rows)) {
    throw ConfigError(fileName, "quilt name", countsText(tag->columns, tag->rows),
                      "the file's embedded metadata says " + countsText(meta->columns, meta->rows) +
                          " views; rename the file to the metadata's _qs tag (or give interleave --columns and "
                          "--rows)");
  }
  if (!tag && !meta) return std::nullopt;
  QuiltName layout = tag ? *tag : *meta;
  source = tag ? "file name" : "metadata";
  if (!layout.aspect && meta) layout.aspect = meta->aspect;
  return layout;
}

ConfigError noQuiltLayout(const std::string& fileName) {
  return ConfigError(fileName, "quilt name", "\"" + fileName + "\"",
                     "no quilt layout: expected a `_qs{columns}x{rows}a{aspect}` tag in the name (e.g. "
                     "take_qs8x6a0.75.png), holotrace quilt metadata in the file, or interleave's --columns and "
                     "--rows");
}

}  // namespace

QuiltFileLayout resolveQuiltLayout(const ImageHeader& header, const std::string& fileName,
                                   const QuiltLayoutHints& hints, const DisplayConfig& display) {
  checkHints(hints);
  QuiltFileLayout result;
  const std::optional<QuiltName> fromFile = fileQuiltLayout(header, fileName, result.source);
  std::uint32_t columns = 0, rows = 0;
  if (hints.columns) {
    columns = *hints.columns, rows = *hints.rows, result.source = "options";
  } else if (fromFile) {
    columns = fromFile->columns, rows = fromFile->rows;
  } else {
    throw noQuiltLayout(fileName);
  }
  double aspect = displayAspect(display);
  if (hints.aspect)
    aspect = *hints.aspect;
  else if (fromFile && fromFile->aspect)
    aspect = *fromFile->aspect;
  result.layout = makeQuiltLayout(columns, rows, header.width, header.height, aspect);
  return result;
}

QuiltLayout quiltLayoutOfFile(const ImageHeader& header, const std::string& fileName) {
  std::string source;
  const std::optional<QuiltName> fromFile = fileQuiltLayout(header, fileName, source);
  if (!fromFile) throw noQuiltLayout(fileName);
  // A short tag's aspect comes from the display later; the tile checks do not depend on it.
  const QuiltLayout layout =
      makeQuiltLayout(fromFile->columns, fromFile->rows, header.width, header.height, fromFile->aspect.value_or(1.0));
  checkQuiltTiles(layout, fileName);
  return layout;
}

InterleavedQuilt interleaveQuiltFile(const std::filesystem::path& path, const DisplayConfig& display,
                                     const QuiltLayoutHints& hints, QuiltViewFilter filter, unsigned threads) {
  const std::string fileName = path.filename().string();
  const QuiltFileLayout layout = resolveQuiltLayout(readImageHeader(path), fileName, hints, display);
  checkQuiltFitsDisplay(layout.layout, display, path.string());  // before the pixels are read
  return interleaveQuiltImage(readImageFile(path), fileName, display, hints, filter, threads);
}

InterleavedQuilt interleaveQuiltImage(const ImageFile& image, const std::string& fileName, const DisplayConfig& display,
                                      const QuiltLayoutHints& hints, QuiltViewFilter filter, unsigned threads) {
  InterleavedQuilt result;
  result.layout = resolveQuiltLayout(image, fileName, hints, display);
  checkQuiltFitsDisplay(result.layout.layout, display, fileName);
  const gpu_shared::LenticularParams params = makeLenticularParams(display, Bounds3{});
  result.width = display.calibration->screenW;
  result.height = display.calibration->screenH;
  result.rgba = interleaveQuilt(quiltImageViews(result.layout.layout, image.rgba), params, filter, threads);
  return result;
}

bool isQuiltImageFile(const std::string& spec) {
  std::string ext = std::filesystem::path(spec).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".png" || ext == ".exr";
}

}  // namespace ht::frame_io
