// render_report.cpp - see render_report.h.
#include "cli/render_report.h"

#include <iomanip>
#include <sstream>
#include <string>

namespace ht::cli {
namespace {

std::string fixed(double value, int decimals) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(decimals) << value;
  return s.str();
}

std::string label(const std::string& text) {
  return "  " + text + std::string(text.size() < 14 ? 14 - text.size() : 1, ' ');
}

double mraysPerSecond(std::uint64_t rays, double ms) { return ms > 0.0 ? double(rays) / (ms * 1e3) : 0.0; }

}  // namespace

std::string formatMs(double ms) { return fixed(ms, 1) + " ms"; }

std::string featureList(const SceneFeatures& f) {
  std::string list;
  auto add = [&](bool on, const char* name) {
    if (on) list += (list.empty() ? "" : ", ") + std::string(name);
  };
  add(f.lights, "lights");
  add(f.mirrors, "mirrors");
  add(f.glass, "glass");
  add(f.textures, "textures");
  add(f.emissive, "emissive");
  return list.empty() ? "none" : list;
}

void printDevice(std::ostream& out, const gpu::DeviceInfo& d) {
  out << "device: [" << d.index << "] " << d.name << " (" << d.type << ", Vulkan " << d.apiVersion << ", " << d.driver
      << ")\n";
}

void printScene(std::ostream& out, const Scene& scene, const SceneFeatures& features) {
  out << "scene: " << scene.name << "\n"
      << label("triangles") << scene.triangleCount() << "\n"
      << label("materials") << scene.materials.size() << "\n"
      << label("textures") << scene.textures.size() << "\n"
      << label("lights") << scene.lights.size() << "\n"
      << label("features") << featureList(features) << "\n";
}

void printBvh(std::ostream& out, const bvh::BuildReport& r) {
  out << "bvh:\n"
      << label("build") << fixed(r.buildMs, 1) << " ms\n"
      << label("SAH cost") << fixed(r.sahCost, 2) << "\n"
      << label("nodes") << r.nodeCount << " (" << r.leafCount << " leaves, avg " << fixed(r.avgLeafSize, 2)
      << " triangles/leaf)\n"
      << label("max depth") << r.maxDepth << "\n"
      << label("triangles") << r.trianglesIn << " in, " << r.trianglesDropped
      << " dropped (degenerate or non-finite)\n";
}

void printFrame(std::ostream& out, const gpu::RenderResult& result) {
  out << "frame: " << result.width << "x" << result.height;
  if (result.views > 1) out << " x " << result.views << " views";
  out << "\n";
  double stageSum = 0.0;
  for (const auto& stage : result.stages) {
    out << label(stage.name) << fixed(stage.ms, 2) << " ms\n";
    stageSum += stage.ms;
  }
  out << label("stages total") << fixed(stageSum, 2) << " ms\n"
      << label("frame wall") << fixed(result.totalMs, 2) << " ms\n"
      << label("rays") << result.raysTraced << " traced, "
      << fixed(mraysPerSecond(result.raysTraced, result.totalMs), 2) << " Mrays/s (frame wall time), max "
      << result.maxTraversalSteps << " traversal steps/ray\n";
  if (result.refinedTargets > 0) out << label("refined") << result.refinedTargets << " targets traced again\n";
}

}  // namespace ht::cli
