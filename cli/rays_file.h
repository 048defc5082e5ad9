// rays_file.h - ray batches in and hit records out for `holotrace raycast`.
//
// Binary format (all little-endian; the x86-64/ARM64 hosts holotrace runs on store it natively):
//   rays file:  header 16 bytes = magic "HTRY" (4 bytes), version u32 = 1, count u64;
//               then count records of 32 bytes: origin x y z f32, tmin f32, dir x y z f32, tmax f32
//               (dir need not be unit length; t is measured in units of |dir|).
//   hits file:  header 16 bytes = magic "HTHT", version u16 = 1, kind u16 (0 = closest, 1 = any), count u64;
//               closest: count records of 16 bytes: t f32 (tmax on a miss), triangle id u32 (0xFFFFFFFF on a
//               miss, 0xFFFFFFFE for a refused ray with t = NaN; else the index into the scene's triangle list),
//               u f32, v f32 (barycentrics of vertices 1, 2);
//               any: count records of 4 bytes: u32 1 = occluded in [tmin, tmax], 0 = not, 2 = refused.
//               Which rays are refused: cli/ray_batch.h.
// CSV (chosen by the .csv extension), for small batches:
//   rays: one ray per line "ox,oy,oz,tmin,dx,dy,dz,tmax"; an optional first header line starting with a
//         letter; blank lines and lines starting with '#' are skipped.
//   hits: header "t,triangle,u,v" (closest; triangle -1 on a miss, -2 refused) or "occluded" (any: 0, 1, 2 =
//         refused), one line per ray.
// Every file error is an ht::IoError naming the file and the offending record (binary) or line (CSV). A binary
// header whose count disagrees with the file size is refused before anything is allocated. The values of a ray
// (NaN, Inf, tmin > tmax) are not file errors: raycast refuses such a ray alone (cli/ray_batch.h).
#pragma once
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "bvh/ray_types.h"

namespace ht::cli {

inline constexpr std::uint32_t kRaysFileVersion = 1;
inline constexpr std::uint64_t kRaysHeaderBytes = 16;
inline constexpr std::uint64_t kRayRecordBytes = 32;
inline constexpr std::uint64_t kHitRecordBytes = 16;

// Reads a rays file (binary, or CSV when the extension is .csv).
std::vector<gpu_shared::HtRay> readRaysFile(const std::filesystem::path& path);
// Writes a rays file (binary or CSV by extension), atomically.
void writeRaysFile(const std::filesystem::path& path, std::span<const gpu_shared::HtRay> rays);

// Writes closest-hit records (binary or CSV by extension), atomically.
void writeHitsFile(const std::filesystem::path& path, std::span<const gpu_shared::HtHit> hits);
// Writes any-hit (occlusion) flags, atomically.
void writeOcclusionFile(const std::filesystem::path& path, std::span<const std::uint32_t> occluded);

// Reads a closest-hit file back (tests, tools). Throws IoError for an any-hit file.
std::vector<gpu_shared::HtHit> readHitsFile(const std::filesystem::path& path);

}  // namespace ht::cli
