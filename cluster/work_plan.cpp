// work_plan.cpp - see work_plan.h.
#include "cluster/work_plan.h"

#include <algorithm>

namespace ht::cluster {
namespace {

void addViewsOf(std::vector<WorkUnit>& units, std::uint32_t frame, const gpu::FrameShape& shape) {
  for (std::uint32_t v = 0; v < shape.views; ++v) units.push_back({frame, {v, 1, 0, shape.height}});
}

void addBandsOf(std::vector<WorkUnit>& units, std::uint32_t frame, const gpu::FrameShape& shape, int ranks) {
  const std::uint32_t wanted = kBandsPerRank * static_cast<std::uint32_t>(std::max(ranks, 1));
  const std::uint32_t bands = std::clamp(shape.height / kMinBandRows, 1u, wanted);
  // Rows spread evenly: the first (height % bands) bands get one row more.
  std::uint32_t row = 0;
  for (std::uint32_t b = 0; b < bands; ++b) {
    const std::uint32_t rows = shape.height / bands + (b < shape.height % bands ? 1u : 0u);
    units.push_back({frame, {0, 1, row, rows}});
    row += rows;
  }
}

}  // namespace

std::vector<WorkUnit> planWork(const gpu::FrameShape& shape, std::uint32_t frames, int ranks, WorkGrain grain) {
  std::vector<WorkUnit> units;
  for (std::uint32_t f = 0; f < frames; ++f) {
    if (frames > 1 || grain == WorkGrain::WholeFrames)
      units.push_back({f, {0, shape.views, 0, shape.height}});
    else if (shape.views > 1)
      addViewsOf(units, f, shape);
    else if (grain == WorkGrain::WholeViews)
      units.push_back({f, {0, 1, 0, shape.height}});
    else
      addBandsOf(units, f, shape, ranks);
  }
  return units;
}

int staticOwner(std::size_t unit, std::size_t units, int ranks) {
  return static_cast<int>(unit * static_cast<std::size_t>(ranks) / std::max<std::size_t>(units, 1));
}

}  // namespace ht::cluster
