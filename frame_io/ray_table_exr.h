// ray_table_exr.h - per-pixel ray tables (camera_models/ray_table.h, model "ray-table") as OpenEXR files. The file
// format lives in frame_io, so camera_models stays free of image libraries.
//
// Layout: one pixel per table entry, float32 channels origin.X, origin.Y, origin.Z, direction.X, direction.Y,
// direction.Z (+ an optional per-pixel view phase "phase"), lossless zip compression. EXR scanline 0 is the TOP row,
// i.e. table row y = height - 1 (the table counts y from the bottom), as for holotrace's images.
#pragma once
#include <filesystem>
#include <span>
#include <vector>

#include "camera_models/ray_table.h"

namespace ht::frame_io {

inline constexpr const char* kRayTablePhaseChannel = "phase";

// Validates the table (RayTable::validate: ConfigError naming the entry), then writes it atomically
// (frame_io/atomic_output_file.h: never a partial file). `phase` is empty or width*height values (row-major, y from the
// bottom, as the table). Throws IoError on write failures or a phase of the wrong size.
void writeRayTableExr(const std::filesystem::path& path, const RayTable& table, std::span<const float> phase = {});

// Reads and validates a table; directions are normalised (RayTable::normalizeDirections, unit ones unchanged, so a
// written table reads back bit-exactly). If `phase` is given it receives the phase channel (empty if the file has
// none). Throws IoError if the file cannot be opened or read; ConfigError naming the file for a missing or
// non-float32 channel, a size outside 1..16384 per side (checked before allocating) or invalid values (NaN, zero
// direction, ...).
RayTable readRayTableExr(const std::filesystem::path& path, std::vector<float>* phase = nullptr);

// The table of a "ray-table" display config (config.rayTable->file, already resolved against the config's directory).
// A missing or unreadable file is a ConfigError on the config's field rayTable.file; errors inside the table name the
// table file. Throws ConfigError if the config is not a ray-table display.
RayTable loadDisplayRayTable(const DisplayConfig& config);

}  // namespace ht::frame_io
