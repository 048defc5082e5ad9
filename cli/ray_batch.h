// ray_batch.h - `holotrace raycast` answers or refuses every ray of a batch on its own (README.md, `raycast`).
// One rule for non-finite input: a ray is traced when its origin and direction are finite, the direction
// is not zero, tmin and tmax are not NaN (+-Inf are allowed: an unbounded ray) and tmin <= tmax; any other ray is
// refused with its record index and a reason, and the rest of the batch is traced. A ray the device cannot finish
// (the traversal step limit; e.g. origin 1e38, direction -1e38) is isolated by tracing the batch in halves and
// refused alone, instead of failing the batch.
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "bvh/ray_types.h"

namespace ht::cli {

// Marks a refused ray in the hits file: closest hits get triangle id kRefusedTriangle (CSV -2) and t = NaN; any-hit
// records get kRefusedOcclusion (2).
inline constexpr std::uint32_t kRefusedTriangle = 0xFFFFFFFEu;
inline constexpr std::uint32_t kRefusedOcclusion = 2u;
// More rays than this failing on the device is a broken scene or device, not a few extreme rays: the batch fails.
inline constexpr std::size_t kMaxDeviceRefusals = 64;

struct RayRefusal {
  std::uint64_t index = 0;  // record index in the rays file (0-based; CSV: the n-th ray)
  std::string reason;
};

// Why `ray` is refused by the rule above, or nullopt when it is traced.
std::optional<std::string> rayProblem(const gpu_shared::HtRay& ray);

template <class Result>
using TraceFunction = std::function<std::vector<Result>(std::span<const gpu_shared::HtRay>)>;

// One result per ray: `trace` for the rays the rule accepts, `refused` for the others (listed in `refusals`, in
// index order). `trace` throws GpuError when a ray exceeded the step limit; such rays are isolated and refused.
std::vector<gpu_shared::HtHit> traceClosestEach(std::span<const gpu_shared::HtRay> rays,
                                                const TraceFunction<gpu_shared::HtHit>& trace,
                                                std::vector<RayRefusal>& refusals);
std::vector<std::uint32_t> traceOccludedEach(std::span<const gpu_shared::HtRay> rays,
                                             const TraceFunction<std::uint32_t>& trace,
                                             std::vector<RayRefusal>& refusals);

// "refused 3 of 1000 rays: record 10 (origin is not finite), ..." (the first 10 listed), or "" when none.
std::string refusalSummary(const std::vector<RayRefusal>& refusals, std::size_t total);

}  // namespace ht::cli
