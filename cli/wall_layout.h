// wall_layout.h - which projectors each rank of a live wall shows, and where (docs/CLUSTER.md §7).
//
// On a real wall one node's GPU outputs feed its group of projectors. Here a rank presents through one display sink
// (present/panel_sink.h): one window on one RandR monitor, in which its projectors' images are tiled left to right,
// top to bottom, `columns` per row, each at the projector's native size, 1:1. A layout file says, per rank:
//
//   {"ranks": [
//     {"projectors": [0, 1, 2], "monitor": "WALL-0", "columns": 3},
//     {"projectors": {"first": 3, "count": 3}, "geometry": "96x24+96+0", "x_display": ":1"}
//   ]}
//
// `projectors` (required): view indices of the display, or a contiguous range; `columns` (default: all in one row);
// `monitor` (RandR output or monitor name) or `geometry` (WxH+X+Y), else the monitor picker's own rules (the single
// monitor of the tiled size); `x_display` (default: --x-display, else $DISPLAY). Without a file, the views are split
// into contiguous near-equal groups in rank order, one row each, on the monitor of that size.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "present/randr_snapshot.h"

namespace ht::cli {

struct RankScreen {
  std::vector<std::uint32_t> projectors;  // view indices, tiled in this order
  std::uint32_t columns = 1;
  std::optional<std::string> monitor;
  std::optional<present::Rect> geometry;
  std::optional<std::string> xDisplay;

  std::uint32_t rows() const { return (std::uint32_t(projectors.size()) + columns - 1) / columns; }
};

struct WallLayout {
  std::vector<RankScreen> ranks;
  std::string source;  // the file, or "default layout"
};

// Throws UsageError naming the file, the field and the value for anything wrong: not `ranks` entries for each of
// the job's `rankCount` ranks, a projector outside 0..views-1 or given twice, bad columns, monitor and geometry both.
WallLayout parseWallLayout(const std::string& text, const std::string& source, std::uint32_t views,
                           std::uint32_t rankCount);
WallLayout loadWallLayout(const std::filesystem::path& path, std::uint32_t views, std::uint32_t rankCount);
// Contiguous near-equal groups in rank order (the first views % ranks groups one larger), one row each. Throws
// UsageError when there are more ranks than views.
WallLayout defaultWallLayout(std::uint32_t views, std::uint32_t rankCount);
// A canonical text of the layout, for the start-up check that every rank uses the same.
std::string describeWallLayout(const WallLayout& layout);

}  // namespace ht::cli
