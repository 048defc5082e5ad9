// work_plan.h - how a cluster render cuts its frames into work units (sort-first: every unit is a set of whole
// pixels, rendered with gpu::RenderSettings::region bit-identical to the same pixels of a whole frame):
//   a sequence of frames (capture)  one unit per frame
//   a multi-view frame              one unit per view (quilt view, projector, capture camera)
//   a single image (panel)          bands of rows, about kBandsPerRank per rank, at least kMinBandRows rows each;
//                                   one whole-frame unit when adaptive refinement is on (it compares neighbour rows)
// Units are listed frame by frame, top to bottom; rank 0 hands them out in that order (work_dispatch.h).
#pragma once
#include <cstdint>
#include <vector>

#include "gpu/renderer.h"

namespace ht::cluster {

inline constexpr std::uint32_t kBandsPerRank = 4;
inline constexpr std::uint32_t kMinBandRows = 4;

struct WorkUnit {
  std::uint32_t frame = 0;   // index in the sequence
  gpu::RenderRegion region;  // counts resolved (never 0)
  std::uint64_t pixels(std::uint32_t width) const { return std::uint64_t{width} * region.rowCount * region.viewCount; }
};

enum class WorkGrain {
  Auto,         // as listed above
  WholeViews,   // never cut a view into bands (adaptive refinement on)
  WholeFrames,  // one unit per frame whatever the sequence length (ranks write the frames they render)
};

// The units of `frames` frames of `shape` for `ranks` ranks.
std::vector<WorkUnit> planWork(const gpu::FrameShape& shape, std::uint32_t frames, int ranks, WorkGrain grain);

// Static assignment, for comparison with rank 0's dynamic hand-out: unit i goes to rank i * ranks / units
// (contiguous blocks of the ordered list).
int staticOwner(std::size_t unit, std::size_t units, int ranks);

}  // namespace ht::cluster
