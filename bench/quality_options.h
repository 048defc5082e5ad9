// quality_options.h - options of holotrace-bench-quality.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace ht::bench {

// One adaptive-refinement point: the frame at baseSpp, then refineSpp where the contrast reaches `contrast`.
struct AdaptivePoint {
  std::uint32_t baseSpp = 1, refineSpp = 8;
  float contrast = 0.08f;
};

struct QualityOptions {
  std::vector<std::string> displays{"builtin:portrait", "builtin:gen3-16-landscape"};
  std::string scene = "builtin:plain";
  std::uint32_t refSpp = 16;  // reference = two independent halves of refSpp/2 each
  std::vector<std::uint32_t> directSpp{1, 2, 4, 8};
  std::vector<AdaptivePoint> adaptive{{1, 8, 0.12f}, {1, 8, 0.08f}, {1, 8, 0.05f}, {1, 4, 0.08f}};
  std::vector<std::uint32_t> quiltSpp{1, 2};                         // at the device's standard quilt
  std::vector<std::uint32_t> quiltScaledSpp{1};                      // at the scaled quilt (--quilt-scale)
  std::optional<std::pair<std::uint32_t, std::uint32_t>> quiltSize;  // standard quilt texture size override
  double quiltScale = 2.0;  // pixel-count factor of the scaled quilt (tiles x sqrt(scale))
  std::uint32_t maxDepth = 4;
  std::uint32_t runs = 1;  // timing runs of every point (frames are deterministic: scored once)
  int deviceIndex = -1;
  std::optional<std::string> csvPath, summaryCsvPath, jsonPath;
};

// Returns nullopt after printing help (--help); throws UsageError for bad options.
std::optional<QualityOptions> parseQualityOptions(std::span<const std::string> args, std::string* helpText);

}  // namespace ht::bench
