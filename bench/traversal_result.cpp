// traversal_result.cpp - see traversal_result.h.
#include "bench/traversal_result.h"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <tuple>

#include <nlohmann/json.hpp>

#include "bench/output_file.h"

namespace ht::bench {
namespace {

double mrays(const TimingSeries& series, std::uint64_t rays) { return series.medianMraysPerSecond(rays); }

std::string fixed(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

nlohmann::json costJson(const TraversalCost& c) {
  return {{"rays", c.rays},
          {"node_visits_per_ray", c.nodesPerRay()},
          {"triangle_tests_per_ray", c.trianglesPerRay()},
          {"cost_per_ray", c.costPerRay()},
          {"hits", c.hits}};
}

nlohmann::json treeJson(const TreeFigures& t) {
  return {{"build_ms_median", t.buildMs.medianMs()},
          {"build_ms_runs", t.buildMs.ms},
          {"sah_cost", t.sahCost},
          {"nodes", t.nodes},
          {"leaves", t.leaves},
          {"max_depth", t.maxDepth}};
}

nlohmann::json setJson(const SetThroughput& s) {
  return {{"set", s.set},
          {"query", s.query},
          {"rays", s.rays},
          {"gpu_ms_runs", s.gpu.ms},
          {"embree1_ms_runs", s.embree1.ms},
          {"embree8_ms_runs", s.embree8.ms},
          {"gpu_mrays", mrays(s.gpu, s.rays)},
          {"embree1_mrays", mrays(s.embree1, s.rays)},
          {"embree8_mrays", mrays(s.embree8, s.rays)},
          {"ratio_gpu_embree1", median(s.ratio1)},
          {"ratio_gpu_embree8", median(s.ratio8)},
          {"gpu_hits", s.vsEmbree1.hitsA},
          {"embree_hits", s.vsEmbree1.hitsB},
          {"hit_miss_flips_vs_embree1", s.vsEmbree1.hitMissFlips},
          {"hit_miss_flips_vs_embree8", s.vsEmbree8.hitMissFlips},
          {"gpu_max_steps", s.gpuMaxSteps}};
}

}  // namespace

void printTraversalReport(std::ostream& out, const TraversalReport& r) {
  out << "device: " << r.device << ", Embree " << r.embreeVersion << " (" << r.threads << " threads), " << r.size
      << "^2 primary rays, medians of " << r.runs << " runs\n";
  for (const MeshResult& m : r.meshes) {
    out << "\n" << m.mesh << " (" << m.triangles << " triangles)\n";
    out << "  set       rays      GPU Mr/s  E1 Mr/s  E8 Mr/s  GPU/E1  GPU/E8  flips(E1)\n";
    for (const SetThroughput& s : m.sets) {
      char line[200];
      std::snprintf(line, sizeof line, "  %-8s %9llu  %8.2f  %7.2f  %7.2f  %6.3f  %6.3f  %llu\n", s.set.c_str(),
                    (unsigned long long)s.rays, mrays(s.gpu, s.rays), mrays(s.embree1, s.rays),
                    mrays(s.embree8, s.rays), median(s.ratio1), median(s.ratio8),
                    (unsigned long long)s.vsEmbree1.hitMissFlips);
      out << line;
    }
    out << "  BVH ours:   build " << fixed(m.ours.buildMs.medianMs(), 1) << " ms, SAH " << fixed(m.ours.sahCost, 3)
        << ", " << m.ours.nodes << " nodes, depth " << m.ours.maxDepth << "\n";
    out << "  BVH Embree: build " << fixed(m.embree.buildMs.medianMs(), 1) << " ms, SAH " << fixed(m.embree.sahCost, 3)
        << ", " << m.embree.nodes << " nodes, depth " << m.embree.maxDepth << "  -> SAH ratio ours/Embree "
        << fixed(m.ours.sahCost / m.embree.sahCost, 4) << "\n";
    for (std::size_t i = 0; i < m.sets.size(); ++i) {
      const TraversalCost& a = m.ours.costs[i];
      const TraversalCost& b = m.embree.costs[i];
      out << "  cost/ray " << m.sets[i].set << ": ours " << fixed(a.nodesPerRay(), 2) << " nodes + "
          << fixed(a.trianglesPerRay(), 2) << " tris = " << fixed(a.costPerRay(), 2) << ", Embree tree "
          << fixed(b.nodesPerRay(), 2) << " + " << fixed(b.trianglesPerRay(), 2) << " = " << fixed(b.costPerRay(), 2)
          << "; SIMD-8 lane efficiency (our tree) " << fixed(m.ours.lanes[i].laneEfficiency(), 3) << "\n";
    }
  }
}

void writeTraversalCsv(const std::string& prefix, const TraversalReport& r) {
  std::ostringstream tp, bvh, cost;
  tp << "mesh,triangles,set,query,rays,gpu_mrays,embree1_mrays,embree8_mrays,ratio_gpu_embree1,ratio_gpu_embree8,"
        "hit_miss_flips_e1,hit_miss_flips_e8,gpu_max_steps\n";
  bvh << "mesh,triangles,ours_build_ms,ours_sah,ours_nodes,ours_depth,embree_build_ms,embree_sah,embree_nodes,"
         "embree_depth,sah_ratio\n";
  cost << "mesh,set,tree,nodes_per_ray,triangles_per_ray,cost_per_ray,steps_per_ray,lane_efficiency_8\n";
  for (const MeshResult& m : r.meshes) {
    for (std::size_t i = 0; i < m.sets.size(); ++i) {
      const SetThroughput& s = m.sets[i];
      tp << m.mesh << "," << m.triangles << "," << s.set << "," << s.query << "," << s.rays << ","
         << fixed(mrays(s.gpu, s.rays), 3) << "," << fixed(mrays(s.embree1, s.rays), 3) << ","
         << fixed(mrays(s.embree8, s.rays), 3) << "," << fixed(median(s.ratio1), 4) << "," << fixed(median(s.ratio8), 4)
         << "," << s.vsEmbree1.hitMissFlips << "," << s.vsEmbree8.hitMissFlips << "," << s.gpuMaxSteps << "\n";
      for (const auto& [tree, c, lanes] : {std::tuple{"ours", m.ours.costs[i], m.ours.lanes[i]},
                                           std::tuple{"embree", m.embree.costs[i], m.embree.lanes[i]}}) {
        cost << m.mesh << "," << s.set << "," << tree << "," << fixed(c.nodesPerRay(), 3) << ","
             << fixed(c.trianglesPerRay(), 3) << "," << fixed(c.costPerRay(), 3) << ","
             << fixed(lanes.rays ? double(lanes.steps) / double(lanes.rays) : 0.0, 3) << ","
             << fixed(lanes.laneEfficiency(), 4) << "\n";
      }
    }
    bvh << m.mesh << "," << m.triangles << "," << fixed(m.ours.buildMs.medianMs(), 2) << "," << fixed(m.ours.sahCost, 4)
        << "," << m.ours.nodes << "," << m.ours.maxDepth << "," << fixed(m.embree.buildMs.medianMs(), 2) << ","
        << fixed(m.embree.sahCost, 4) << "," << m.embree.nodes << "," << m.embree.maxDepth << ","
        << fixed(m.ours.sahCost / m.embree.sahCost, 4) << "\n";
  }
  writeTextFile(prefix + "_throughput.csv", tp.str());
  writeTextFile(prefix + "_bvh.csv", bvh.str());
  writeTextFile(prefix + "_cost.csv", cost.str());
}

void writeTraversalJson(const std::string& path, const TraversalReport& r) {
  nlohmann::json meshes = nlohmann::json::array();
  for (const MeshResult& m : r.meshes) {
    nlohmann::json sets = nlohmann::json::array();
    for (std::size_t i = 0; i < m.sets.size(); ++i) {
      nlohmann::json s = setJson(m.sets[i]);
      s["cost_ours_tree"] = costJson(m.ours.costs[i]);
      s["cost_embree_tree"] = costJson(m.embree.costs[i]);
      sets.push_back(s);
    }
    meshes.push_back({{"mesh", m.mesh},
                      {"triangles", m.triangles},
                      {"sets", sets},
                      {"bvh_ours", treeJson(m.ours)},
                      {"bvh_embree", treeJson(m.embree)},
                      {"sah_ratio_ours_over_embree", m.ours.sahCost / m.embree.sahCost}});
  }
  const nlohmann::json doc = {{"benchmark", "holotrace-bench-traversal"},
                              {"date", r.date},
                              {"device", r.device},
                              {"embree_version", r.embreeVersion},
                              {"threads", r.threads},
                              {"size", r.size},
                              {"runs", r.runs},
                              {"cost_stride", r.costStride},
                              {"meshes", meshes}};
  writeTextFile(path, doc.dump(2) + "\n");
}

}  // namespace ht::bench
