// ray_batch.cpp - see ray_batch.h.
#include "cli/ray_batch.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/error.h"

namespace ht::cli {
namespace {

using gpu_shared::HtHit;
using gpu_shared::HtRay;

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Traces rays [begin, end) of `rays`; on a GpuError splits the range until single rays are left, which are refused.
template <class Result>
void traceRange(std::span<const HtRay> rays, const std::vector<std::uint64_t>& index, std::size_t begin,
                std::size_t end, const TraceFunction<Result>& trace, std::vector<Result>& out, const Result& refused,
                std::vector<RayRefusal>& refusals, std::size_t& deviceRefusals) {
  if (begin == end) return;
  try {
    const std::vector<Result> results = trace(rays.subspan(begin, end - begin));
    std::copy(results.begin(), results.end(), out.begin() + static_cast<std::ptrdiff_t>(begin));
    return;
  } catch (const GpuError& e) {
    if (end - begin > 1) {
      const std::size_t mid = begin + (end - begin) / 2;
      traceRange(rays, index, begin, mid, trace, out, refused, refusals, deviceRefusals);
      traceRange(rays, index, mid, end, trace, out, refused, refusals, deviceRefusals);
      return;
    }
    if (++deviceRefusals > kMaxDeviceRefusals) throw;
    out[begin] = refused;
    refusals.push_back({index[begin],
                        "the device stopped it at the BVH traversal step limit (coordinates too "
                        "extreme for float32; bring the ray closer to the scene)"});
  }
}

template <class Result>
std::vector<Result> traceEach(std::span<const HtRay> rays, const TraceFunction<Result>& trace, const Result& refused,
                              std::vector<RayRefusal>& refusals) {
  std::vector<HtRay> accepted;
  std::vector<std::uint64_t> index;  // accepted[k] is record index[k]
  for (std::size_t i = 0; i < rays.size(); ++i) {
    if (const auto problem = rayProblem(rays[i])) {
      refusals.push_back({i, *problem});
    } else {
      accepted.push_back(rays[i]);
      index.push_back(i);
    }
  }
  std::vector<Result> tracedResults(accepted.size());
  std::size_t deviceRefusals = 0;
  traceRange<Result>(accepted, index, 0, accepted.size(), trace, tracedResults, refused, refusals, deviceRefusals);
  std::vector<Result> out(rays.size(), refused);
  for (std::size_t k = 0; k < accepted.size(); ++k) out[index[k]] = tracedResults[k];
  std::sort(refusals.begin(), refusals.end(),
            [](const RayRefusal& a, const RayRefusal& b) { return a.index < b.index; });
  return out;
}

}  // namespace

std::optional<std::string> rayProblem(const HtRay& ray) {
  if (!finite(ray.origin)) return "origin is not finite (NaN or Inf)";
  if (!finite(ray.dir)) return "direction is not finite (NaN or Inf)";
  if (ray.dir.x == 0.0f && ray.dir.y == 0.0f && ray.dir.z == 0.0f) return "direction is zero";
  if (std::isnan(ray.tmin) || std::isnan(ray.tmax)) return "tmin or tmax is NaN";
  if (ray.tmin > ray.tmax) return "tmin > tmax";
  return std::nullopt;
}

std::vector<HtHit> traceClosestEach(std::span<const HtRay> rays, const TraceFunction<HtHit>& trace,
                                    std::vector<RayRefusal>& refusals) {
  const HtHit refused{std::numeric_limits<float>::quiet_NaN(), kRefusedTriangle, 0.0f, 0.0f};
  return traceEach<HtHit>(rays, trace, refused, refusals);
}

std::vector<std::uint32_t> traceOccludedEach(std::span<const HtRay> rays, const TraceFunction<std::uint32_t>& trace,
                                             std::vector<RayRefusal>& refusals) {
  return traceEach<std::uint32_t>(rays, trace, kRefusedOcclusion, refusals);
}

std::string refusalSummary(const std::vector<RayRefusal>& refusals, std::size_t total) {
  if (refusals.empty()) return "";
  constexpr std::size_t kListed = 10;
  std::string text = "refused " + std::to_string(refusals.size()) + " of " + std::to_string(total) + " rays:";
  for (std::size_t i = 0; i < refusals.size() && i < kListed; ++i)
    text +=
        std::string(i ? "," : "") + " record " + std::to_string(refusals[i].index) + " (" + refusals[i].reason + ")";
  if (refusals.size() > kListed) text += ", ...";
  return text;
}

}  // namespace ht::cli
