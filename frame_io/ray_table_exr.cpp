// ray_table_exr.cpp - see ray_table_exr.h.
#include "frame_io/ray_table_exr.h"

#include <OpenImageIO/imageio.h>

#include <array>
#include <string>

#include "common/error.h"
#include "frame_io/atomic_output_file.h"
#include "frame_io/image_encoding.h"

namespace ht::frame_io {
namespace fs = std::filesystem;
namespace {

constexpr std::array<const char*, 6> kChannels = {"origin.X",    "origin.Y",    "origin.Z",
                                                  "direction.X", "direction.Y", "direction.Z"};
constexpr int kMaxFileChannels = 64;  // a ray table needs 6 or 7; more means a different kind of file

std::string oiioDetail(std::string detail) {
  if (detail.empty()) detail = OIIO::geterror();
  return detail.empty() ? "unknown OpenImageIO error" : detail;
}

std::string requiredChannelList() {
  std::string list;
  for (const char* name : kChannels) list += (list.empty() ? "" : ", ") + std::string(name);
  return list;
}

}  // namespace

void writeRayTableExr(const fs::path& path, const RayTable& table, std::span<const float> phase) {
  table.validate(path.string());
  const std::size_t count = std::size_t(table.width) * table.height;
  if (!phase.empty() && phase.size() != count)
    throw IoError("cannot write '" + path.string() + "': phase has " + std::to_string(phase.size()) +
                  " values, expected width*height = " + std::to_string(count) + " (or none)");
  const int channels = phase.empty() ? 6 : 7;
  std::vector<std::string> names(kChannels.begin(), kChannels.end());
  if (!phase.empty()) names.push_back(kRayTablePhaseChannel);
  // Scanline order, top row first.
  std::vector<float> pixels(count * std::size_t(channels));
  for (std::uint32_t row = 0; row < table.height; ++row) {
    const std::uint32_t y = table.height - 1 - row;
    for (std::uint32_t x = 0; x < table.width; ++x) {
      const std::size_t i = table.index(x, y);
      float* p = &pixels[(std::size_t(row) * table.width + x) * std::size_t(channels)];
      for (int c = 0; c < 3; ++c) {
        p[c] = table.origins[i][c];
        p[3 + c] = table.directions[i][c];
      }
      if (!phase.empty()) p[6] = phase[i];
    }
  }
  std::vector<std::uint8_t> bytes;
  try {  // float32 with lossless zip compression: the table reads back bit-exactly
    bytes = encodeExrChannels(
        table.width, table.height, names, pixels, ImageFormat::ExrFloat,
        {{"holotrace:content", "ray table: origin, direction per pixel; row 0 = top (y = height - 1)"}});
  } catch (const IoError& e) { throw IoError("cannot write '" + path.string() + "': " + e.what()); }
  const OutputFile file{path, std::move(bytes)};
  writeFilesAtomically({&file, 1});
}

RayTable readRayTableExr(const fs::path& path, std::vector<float>* phase) {
  const std::string source = path.string();
  auto in = OIIO::ImageInput::open(source);
  if (!in)
    throw IoError("cannot read ray table '" + source + "': " + oiioDetail("") +
                  " (expected an existing OpenEXR file with channels " + requiredChannelList() + ")");
  const OIIO::ImageSpec spec = in->spec();
  if (spec.deep || spec.depth > 1)
    throw ConfigError(source, "(image)", spec.deep ? "deep" : "volume", "expected a flat 2D OpenEXR image");
  if (spec.x != 0 || spec.y != 0)
    throw ConfigError(source, "dataWindow", std::to_string(spec.x) + "," + std::to_string(spec.y),
                      "expected a data window starting at 0,0 (one pixel per table entry)");
  // Sizes first, before any allocation of pixel memory.
  checkRayTableSize(spec.width < 0 ? 0 : std::uint64_t(spec.width), spec.height < 0 ? 0 : std::uint64_t(spec.height),
                    source);
  if (spec.nchannels < 6 || spec.nchannels > kMaxFileChannels)
    throw ConfigError(source, "channels", std::to_string(spec.nchannels),
                      "expected 6 or 7 channels: " + requiredChannelList() + " (+ " + kRayTablePhaseChannel + ")");
  std::array<int, 6> index{};
  for (std::size_t k = 0; k < kChannels.size(); ++k) {
    index[k] = spec.channelindex(kChannels[k]);
    if (index[k] < 0) {
      std::string present;
      for (const std::string& name : spec.channelnames) present += (present.empty() ? "" : ", ") + name;
      throw ConfigError(source, kChannels[k], "(missing)",
                        "expected float32 channels " + requiredChannelList() + "; the file has " + present);
    }
    if (spec.channelformat(index[k]) != OIIO::TypeDesc::FLOAT)
      throw ConfigError(source, kChannels[k], spec.channelformat(index[k]).c_str(),
                        "expected float32 (a half or integer channel cannot hold calibrated rays exactly)");
  }
  const int phaseIndex = spec.channelindex(kRayTablePhaseChannel);

  RayTable table;
  table.width = std::uint32_t(spec.width);
  table.height = std::uint32_t(spec.height);
  const std::size_t count = std::size_t(table.width) * table.height;
  const auto channels = std::size_t(spec.nchannels);
  std::vector<float> pixels(count * channels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()))
    throw IoError("cannot read ray table '" + source + "': " + oiioDetail(in->geterror()));
  in->close();
  table.origins.resize(count);
  table.directions.resize(count);
  if (phase != nullptr) phase->assign(phaseIndex >= 0 ? count : 0, 0.0f);
  for (std::uint32_t row = 0; row < table.height; ++row) {
    const std::uint32_t y = table.height - 1 - row;
    for (std::uint32_t x = 0; x < table.width; ++x) {
      const float* p = &pixels[(std::size_t(row) * table.width + x) * channels];
      const std::size_t i = table.index(x, y);
      table.origins[i] = glm::vec3(p[index[0]], p[index[1]], p[index[2]]);
      table.directions[i] = glm::vec3(p[index[3]], p[index[4]], p[index[5]]);
      if (phase != nullptr && phaseIndex >= 0) (*phase)[i] = p[phaseIndex];
    }
  }
  table.validate(source);
  table.normalizeDirections();
  return table;
}

RayTable loadDisplayRayTable(const DisplayConfig& config) {
  if (config.model != DisplayModel::RayTable || !config.rayTable)
    throw ConfigError(config.sourcePath, "model", "\"" + std::string(displayModelName(config.model)) + "\"",
                      "expected model \"ray-table\" with a rayTable section");
  const fs::path& file = config.rayTable->file;
  std::error_code ignored;
  if (!fs::is_regular_file(file, ignored))
    throw ConfigError(config.sourcePath, "rayTable.file", "\"" + file.string() + "\"",
                      "expected an existing ray-table EXR (path relative to the config file)");
  return readRayTableExr(file);
}

}  // namespace ht::frame_io
