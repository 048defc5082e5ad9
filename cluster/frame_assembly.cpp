// frame_assembly.cpp - see frame_assembly.h.
#include "cluster/frame_assembly.h"

#include <algorithm>
#include <string>

#include "cluster/cluster_error.h"

namespace ht::cluster {

FrameAssembly::FrameAssembly(const gpu::FrameShape& shape, std::vector<WorkUnit> units)
    : shape_(shape), units_(std::move(units)), placed_(units_.size(), false) {
  for (const WorkUnit& u : units_) ++unitsPerFrame_[u.frame];
}

std::optional<std::uint32_t> FrameAssembly::place(std::size_t unit, std::span<const float> rgba) {
  if (unit >= units_.size() || placed_[unit]) {
    throw ClusterError("work unit " + std::to_string(unit) + " arrived twice or does not exist");
  }
  const WorkUnit& u = units_[unit];
  if (rgba.size() != u.pixels(shape_.width) * 4) {
    throw ClusterError("work unit " + std::to_string(unit) + " brought " + std::to_string(rgba.size()) +
                       " floats, not " + std::to_string(u.pixels(shape_.width) * 4));
  }
  placed_[unit] = true;
  auto [it, fresh] = pending_.try_emplace(u.frame);
  Pending& p = it->second;
  if (fresh) {
    p.frame.width = shape_.width;
    p.frame.height = shape_.height;
    p.frame.views = shape_.views;
    p.frame.rgba.resize(std::size_t{shape_.width} * shape_.height * shape_.views * 4);
    p.unitsLeft = unitsPerFrame_[u.frame];
  }
  const std::size_t rowFloats = std::size_t{shape_.width} * 4;
  const std::size_t bandFloats = rowFloats * u.region.rowCount;
  for (std::uint32_t v = 0; v < u.region.viewCount; ++v) {
    const std::size_t view = u.region.viewFirst + v;
    float* target = p.frame.rgba.data() + (view * shape_.height + u.region.rowFirst) * rowFloats;
    std::copy_n(rgba.data() + v * bandFloats, bandFloats, target);
  }
  if (--p.unitsLeft > 0) return std::nullopt;
  return u.frame;
}

gpu::RenderResult FrameAssembly::take(std::uint32_t frame) {
  auto it = pending_.find(frame);
  if (it == pending_.end() || it->second.unitsLeft > 0) {
    throw ClusterError("frame " + std::to_string(frame) + " is not complete");
  }
  gpu::RenderResult result = std::move(it->second.frame);
  pending_.erase(it);
  return result;
}

}  // namespace ht::cluster
