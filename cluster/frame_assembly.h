// frame_assembly.h - rank 0 puts the pixels of finished work units where they belong in their frame, and hands out
// each frame once all its units are in. A frame's buffer exists only while its units arrive, so a long capture holds
// the frames in flight, not the sequence.
#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "cluster/work_plan.h"
#include "gpu/renderer.h"

namespace ht::cluster {

class FrameAssembly {
 public:
  FrameAssembly(const gpu::FrameShape& shape, std::vector<WorkUnit> units);

  // Copies unit `unit`'s RGBA floats (its views, each its band's rows top to bottom) into its frame; returns the
  // frame's index when that frame is now complete. Throws ClusterError for a wrong size or a unit placed twice.
  std::optional<std::uint32_t> place(std::size_t unit, std::span<const float> rgba);
  // The complete frame `frame` (after place() returned it), moved out.
  gpu::RenderResult take(std::uint32_t frame);

 private:
  struct Pending {
    gpu::RenderResult frame;
    std::size_t unitsLeft = 0;
  };
  gpu::FrameShape shape_;
  std::vector<WorkUnit> units_;
  std::vector<bool> placed_;
  std::map<std::uint32_t, std::size_t> unitsPerFrame_;
  std::map<std::uint32_t, Pending> pending_;
};

}  // namespace ht::cluster
