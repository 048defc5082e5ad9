// quality_points.h - the measured points of holotrace-bench-quality, the equal-time / equal-error comparison of the
// direct path against each quilt point, and their CSV / JSON / text output.
#pragma once
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "bench/image_metrics.h"

namespace ht::bench {

struct QualityPoint {
  std::string path;  // "direct", "adaptive" or "quilt"
  std::uint32_t spp = 0;
  std::string quilt;        // quilt points: "8x6 420x560" (columns x rows, tile size); empty for direct
  std::string filter;       // quilt points: view filter name; empty for direct
  double renderMs = 0;      // RenderResult::totalMs (host wall time of the frame)
  double gpuMs = 0;         // sum of RenderResult::stages
  double interleaveMs = 0;  // CPU interleave (quilt only; reported, not in frameMs: a GPU does it in one gather pass)
  ImageMetrics metrics;
  double psnrCorrectedDb = 0;   // PSNR of max(MSE - reference noise, 1e-12)
  std::uint32_t refineSpp = 0;  // adaptive points: spp of the refined targets
  double refineContrast = 0;    // adaptive points: contrast threshold
  double refinedFraction = 0;   // adaptive points: refined targets / all targets
  std::vector<double> runMs;    // render wall time of each timing run (--runs), in run order; [0] = renderMs
  // Render wall time incl. readback, both paths: the median of the runs.
  double frameMs() const;
};

// Direct and adaptive paths vs one quilt point: PSNR gain at the quilt's time, speed-up at the quilt's PSNR (nullopt
// when the curve does not reach that far; both by linear interpolation in log2(time)). The adaptive curve is the
// Pareto front (faster points first, each better than every faster one) of the adaptive and the direct points (a
// direct frame is the adaptive path refining every target). With several timing runs a point's time is the median of
// its same-run ratios to the quilt's time, times the quilt's median (the host's drift between runs cancels), and the
// adaptive gain is also given for each run on its own.
struct EqualComparison {
  const QualityPoint* quilt = nullptr;
  std::optional<double> directGainDb;  // direct PSNR(corrected) at quilt time - quilt PSNR(corrected)
  std::optional<double> speedup;       // quilt time / direct time at the quilt's PSNR(corrected)
  std::optional<double> adaptiveGainDb;
  std::optional<double> adaptiveSpeedup;
  std::vector<std::optional<double>> adaptiveGainDbEachRun;  // runs > 1 only
};

struct DisplayQuality {
  std::string display;
  std::uint32_t panelWidth = 0, panelHeight = 0;
  std::uint32_t refSpp = 0;
  std::uint32_t runs = 1;             // timing runs of every point (--runs)
  double refMs = 0, refNoiseMse = 0;  // refNoiseMse = MSE(half A, half B) / 4, the reference's own noise
  std::vector<QualityPoint> points;
  std::vector<EqualComparison> compare() const;
};

struct QualityReport {
  std::string device, scene, date;
  std::uint32_t maxDepth = 0;
  std::vector<DisplayQuality> displays;
};

void printQualityReport(std::ostream& out, const QualityReport& report);
void writeQualityCsv(const std::string& path, const QualityReport& report);
void writeQualitySummaryCsv(const std::string& path, const QualityReport& report);
void writeQualityJson(const std::string& path, const QualityReport& report);

}  // namespace ht::bench
