// bench_skipping_main.cpp - holotrace-bench-skipping: what scene specialisation saves. The same frame (pinhole
// camera of the display's placement, N x N pixels) is rendered with the scene's specialised pipeline and with
// RenderSettings::forceAllFeatures = true, interleaved, --runs times after one warm-up of each; per-pass GPU times
// (RenderResult::stages) and the frame totals are reported as medians, the ratio per run within the run.
#include <algorithm>
#include <array>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/bench_main.h"
#include "bench/output_file.h"
#include "bench/timing_series.h"
#include "camera_models/display_config.h"
#include "camera_models/pinhole_params.h"
#include "cli/arguments.h"
#include "common/error.h"
#include "gpu/renderer.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"

namespace ht::bench {
namespace {

const char* const kCommand = "holotrace-bench-skipping";

struct SkipOptions {
  std::vector<std::string> scenes{"builtin:plain", "/usr/share/glmark2/models/bunny.obj", "builtin:showcase"};
  std::string display = "builtin:portrait";
  std::uint32_t size = 512, spp = 4, runs = 5;
  int deviceIndex = -1;
  std::optional<std::string> csvPath, jsonPath;
};

const std::array<cli::OptionSpec, 9> kSpecs = {{
    {"--scenes", "", "LIST", "comma-separated scenes (default builtin:plain,<glmark2 bunny>,builtin:showcase)"},
    {"--display", "", "SPEC", "display whose camera placement frames the scene (default builtin:portrait)"},
    {"--size", "", "N", "pinhole image N x N pixels (default 512)"},
    {"--spp", "", "N", "samples per pixel (default 4)"},
    {"--runs", "", "N", "timed runs of each variant, interleaved, after one warm-up (default 5)"},
    {"--quick", "", "", "smoke test: --size 128 --runs 3 (explicit options win)"},
    {"--device", "", "N", "Vulkan device index (default: automatic)"},
    {"--csv", "", "PATH", "one row per scene and stage"},
    {"--json", "", "PATH", "every run as JSON"},
}};

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) {
    if (!item.empty()) items.push_back(item);
  }
  if (items.empty()) throw UsageError(cli::usageMessage(kCommand, "--scenes is empty"));
  return items;
}

std::optional<SkipOptions> parseOptions(std::span<const std::string> args) {
  if (cli::wantsHelp(args)) {
    std::cout << "Usage: " << kCommand << " [options]\n\n"
              << "Renders each scene with its specialised pipeline and with forceAllFeatures = true (all shading\n"
                 "features on), interleaved; prints per-pass GPU medians and the frame-time ratio.\n\nOptions:\n"
              << cli::formatOptions(kSpecs);
    return std::nullopt;
  }
  const cli::ParsedArguments parsed = cli::parseArguments(kCommand, kSpecs, args);
  SkipOptions o;
  const bool quick = parsed.has("--quick");
  if (auto scenes = parsed.text("--scenes")) o.scenes = splitList(*scenes);
  o.display = parsed.textOr("--display", o.display);
  o.size = parsed.unsignedValue("--size", 8, 8192).value_or(quick ? 128 : o.size);
  o.spp = parsed.unsignedValue("--spp", 1, 4096).value_or(o.spp);
  o.runs = parsed.unsignedValue("--runs", 1, 1000).value_or(quick ? 3 : o.runs);
  if (auto device = parsed.unsignedValue("--device", 0, 255)) o.deviceIndex = int(*device);
  o.csvPath = parsed.text("--csv");
  o.jsonPath = parsed.text("--json");
  return o;
}

struct Variant {
  std::map<std::string, TimingSeries> stages;  // per-pass GPU ms per run
  TimingSeries frame, gpuSum;                  // host wall ms, sum of the stages
};

struct SceneSkip {
  std::string scene, features;
  Variant specialised, allFeatures;
  std::vector<double> frameRatio, gpuRatio;  // per run: all-features / specialised
};

void record(Variant& v, const gpu::RenderResult& r) {
  double sum = 0.0;
  for (const auto& stage : r.stages) {
    v.stages[stage.name].ms.push_back(stage.ms);
    sum += stage.ms;
  }
  v.frame.ms.push_back(r.totalMs);
  v.gpuSum.ms.push_back(sum);
}

std::string featureText(const SceneFeatures& f) {
  std::string text;
  for (auto [on, name] : {std::pair{f.lights, "lights"},
                          {f.mirrors, "mirrors"},
                          {f.glass, "glass"},
                          {f.textures, "textures"},
                          {f.emissive, "emissive"}}) {
    if (on) text += (text.empty() ? "" : "+") + std::string(name);
  }
  return text.empty() ? "none" : text;
}

SceneSkip measureScene(gpu::VulkanContext& context, const std::string& spec, const SkipOptions& o) {
  const Scene scene = loadScene(spec);
  gpu::Renderer renderer(context, scene);
  DisplayConfig display = resolveDisplay(o.display);
  display.pinhole.width = o.size;
  display.pinhole.height = o.size;
  const auto params = makePinholeParams(display, scene.bounds());
  gpu::RenderSettings specialised, all;
  specialised.spp = all.spp = o.spp;
  all.forceAllFeatures = true;
  SceneSkip s{spec, featureText(renderer.features()), {}, {}, {}, {}};
  std::cout << kCommand << ": " << spec << " (features: " << s.features << ")" << std::endl;
  renderer.renderPinhole(params, specialised);  // warm-up (JIT) of both pipelines
  renderer.renderPinhole(params, all);
  for (std::uint32_t run = 0; run < o.runs; ++run) {
    const auto a = renderer.renderPinhole(params, specialised);
    const auto b = renderer.renderPinhole(params, all);
    record(s.specialised, a);
    record(s.allFeatures, b);
    s.frameRatio.push_back(b.totalMs / a.totalMs);
    s.gpuRatio.push_back(s.allFeatures.gpuSum.ms.back() / s.specialised.gpuSum.ms.back());
  }
  return s;
}

void print(const std::vector<SceneSkip>& results) {
  for (const SceneSkip& s : results) {
    std::cout << "\n" << s.scene << " (features: " << s.features << ")\n";
    for (const auto& [name, series] : s.allFeatures.stages) {
      const auto it = s.specialised.stages.find(name);
      const double spec = it == s.specialised.stages.end() ? 0.0 : it->second.medianMs();
      std::printf("  %-12s specialised %9.2f ms   all features %9.2f ms\n", name.c_str(), spec, series.medianMs());
    }
    std::printf("  frame wall: %.1f vs %.1f ms, ratio all/specialised %.3f (GPU stage sum ratio %.3f)\n",
                s.specialised.frame.medianMs(), s.allFeatures.frame.medianMs(), median(s.frameRatio),
                median(s.gpuRatio));
  }
}

void writeCsv(const std::string& path, const std::vector<SceneSkip>& results) {
  std::ostringstream csv;
  csv << "scene,features,stage,specialised_ms,all_features_ms\n";
  for (const SceneSkip& s : results) {
    for (const auto& [name, series] : s.allFeatures.stages) {
      const auto it = s.specialised.stages.find(name);
      csv << s.scene << "," << s.features << "," << name << ","
          << (it == s.specialised.stages.end() ? 0.0 : it->second.medianMs()) << "," << series.medianMs() << "\n";
    }
    csv << s.scene << "," << s.features << ",frame_wall," << s.specialised.frame.medianMs() << ","
        << s.allFeatures.frame.medianMs() << "\n";
    csv << s.scene << "," << s.features << ",ratio_frame_all_over_specialised,1," << median(s.frameRatio) << "\n";
    csv << s.scene << "," << s.features << ",ratio_gpu_all_over_specialised,1," << median(s.gpuRatio) << "\n";
  }
  writeTextFile(path, csv.str());
}

nlohmann::json variantJson(const Variant& v) {
  nlohmann::json stages;
  for (const auto& [name, series] : v.stages) stages[name] = series.ms;
  return {{"stages_ms_runs", stages}, {"frame_ms_runs", v.frame.ms}, {"gpu_sum_ms_runs", v.gpuSum.ms}};
}

void writeJson(const std::string& path, const std::vector<SceneSkip>& results, const SkipOptions& o,
               const std::string& device) {
  nlohmann::json scenes = nlohmann::json::array();
  for (const SceneSkip& s : results) {
    scenes.push_back({{"scene", s.scene},
                      {"features", s.features},
                      {"specialised", variantJson(s.specialised)},
                      {"all_features", variantJson(s.allFeatures)},
                      {"frame_ratio_median", median(s.frameRatio)},
                      {"gpu_ratio_median", median(s.gpuRatio)}});
  }
  const nlohmann::json doc = {{"benchmark", kCommand}, {"device", device}, {"display", o.display}, {"size", o.size},
                              {"spp", o.spp},          {"runs", o.runs},   {"scenes", scenes}};
  writeTextFile(path, doc.dump(2) + "\n");
}

int run(const SkipOptions& o) {
  gpu::VulkanContext context({o.deviceIndex, false});
  std::vector<SceneSkip> results;
  for (const std::string& scene : o.scenes) results.push_back(measureScene(context, scene, o));
  print(results);
  if (o.csvPath) writeCsv(*o.csvPath, results);
  if (o.jsonPath) writeJson(*o.jsonPath, results, o, context.device().name);
  return 0;
}

}  // namespace
}  // namespace ht::bench

int main(int argc, char** argv) {
  // parseOptions prints its own --help text.
  return ht::bench::benchMain(
      argc, argv, "holotrace-bench-skipping",
      [](const std::vector<std::string>& a, std::string*) { return ht::bench::parseOptions(a); },
      [](const auto& options) { return ht::bench::run(options); });
}
