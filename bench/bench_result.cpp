// bench_result.cpp - see bench_result.h.
#include "bench/bench_result.h"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include <nlohmann/json.hpp>

#include "common/error.h"

namespace ht::bench {
namespace {

std::string fixed(double value, int decimals) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(decimals) << value;
  return s.str();
}

double ratio(const QueryResult& q, std::uint64_t rays) {
  const double embree = q.embree.medianMraysPerSecond(rays);
  return embree > 0.0 ? q.gpu.medianMraysPerSecond(rays) / embree : 0.0;
}

void printQuery(std::ostream& out, const char* name, const QueryResult& q, std::uint64_t rays) {
  out << name << "  holotrace GPU " << fixed(q.gpu.medianMraysPerSecond(rays), 2) << " Mrays/s ("
      << fixed(q.gpu.medianMs(), 1) << " ms)   Embree " << fixed(q.embree.medianMraysPerSecond(rays), 2) << " Mrays/s ("
      << fixed(q.embree.medianMs(), 1) << " ms)   GPU/Embree " << fixed(ratio(q, rays), 3) << "\n"
      << std::string(10, ' ') << "hits: holotrace " << q.hits.hitsA << ", Embree " << q.hits.hitsB << " (difference "
      << fixed(100.0 * q.hits.hitCountDifference(), 4) << " %, " << q.hits.hitMissFlips << " hit/miss flips";
  if (q.hits.differentTriangle || q.hits.maxRelativeTDiff > 0.0) {
    out << ", " << q.hits.differentTriangle << " other triangle, max |dt|/t " << q.hits.maxRelativeTDiff;
  }
  out << ")\n";
}

nlohmann::json queryJson(const QueryResult& q, std::uint64_t rays) {
  return {
      {"gpu",
       {{"median_ms", q.gpu.medianMs()},
        {"median_mrays_per_s", q.gpu.medianMraysPerSecond(rays)},
        {"runs_ms", q.gpu.ms},
        {"max_traversal_steps", q.gpuMaxSteps}}},
      {"embree",
       {{"median_ms", q.embree.medianMs()},
        {"median_mrays_per_s", q.embree.medianMraysPerSecond(rays)},
        {"runs_ms", q.embree.ms}}},
      {"gpu_over_embree", ratio(q, rays)},
      {"hits",
       {{"gpu", q.hits.hitsA},
        {"embree", q.hits.hitsB},
        {"relative_difference", q.hits.hitCountDifference()},
        {"hit_miss_flips", q.hits.hitMissFlips},
        {"different_triangle", q.hits.differentTriangle},
        {"max_relative_t_difference", q.hits.maxRelativeTDiff}}},
  };
}

}  // namespace

bool BenchResult::hitsAgree() const {
  return closest.hits.hitCountDifference() <= kHitCountTolerance &&
         occluded.hits.hitCountDifference() <= kHitCountTolerance;
}

void printResult(std::ostream& out, const BenchResult& r) {
  out << "mesh:     " << r.mesh << " (" << r.triangles << " triangles)\n"
      << "rays:     " << r.width << "x" << r.height << " pinhole primary rays, " << r.runs
      << " timed runs per tracer after a warm-up, interleaved\n"
      << "device:   " << r.device << "\n"
      << "BVH:      holotrace build " << fixed(r.bvhBuildMs, 1) << " ms, SAH cost " << fixed(r.bvhSahCost, 2) << ", "
      << r.bvhNodes << " nodes, depth " << r.bvhMaxDepth << "; Embree " << r.embreeVersion << " build "
      << fixed(r.embreeBuildMs, 1) << " ms (default flags, " << r.embreeThreads << " threads for tracing)\n";
  printQuery(out, "closest ", r.closest, r.rays());
  printQuery(out, "occluded", r.occluded, r.rays());
  out << "hit counts " << (r.hitsAgree() ? "agree" : "DISAGREE") << " (tolerance "
      << fixed(100.0 * kHitCountTolerance, 2) << " %)\n";
}

void writeResultJson(const std::string& path, const BenchResult& r) {
  const nlohmann::json doc = {
      {"benchmark", "holotrace-bench-primary"},
      {"mesh", r.mesh},
      {"triangles", r.triangles},
      {"width", r.width},
      {"height", r.height},
      {"rays", r.rays()},
      {"runs", r.runs},
      {"device", r.device},
      {"embree_threads", r.embreeThreads},
      {"bvh",
       {{"build_ms", r.bvhBuildMs}, {"sah_cost", r.bvhSahCost}, {"nodes", r.bvhNodes}, {"max_depth", r.bvhMaxDepth}}},
      {"embree_version", r.embreeVersion},
      {"embree_build_ms", r.embreeBuildMs},
      {"closest", queryJson(r.closest, r.rays())},
      {"occluded", queryJson(r.occluded, r.rays())},
      {"hits_agree", r.hitsAgree()},
  };
  const std::filesystem::path target(path);
  const std::filesystem::path temp = target.string() + ".tmp";
  std::error_code ec;
  if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path(), ec);
  {
    std::ofstream file(temp);
    file << doc.dump(2) << "\n";
    if (!file.flush()) {
      std::filesystem::remove(temp, ec);
      throw IoError("cannot write '" + path + "': write failed (check the directory exists and is writable)");
    }
  }
  std::filesystem::rename(temp, target, ec);
  if (ec) {
    const std::string reason = ec.message();
    std::filesystem::remove(temp, ec);
    throw IoError("cannot write '" + path + "': " + reason);
  }
}

}  // namespace ht::bench
