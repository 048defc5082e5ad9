// quality_points.cpp - see quality_points.h.
#include "bench/quality_points.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include "bench/output_file.h"
#include "bench/timing_series.h"

namespace ht::bench {
namespace {

std::string fixed(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

std::string optionalText(const std::optional<double>& v, int digits) { return v ? fixed(*v, digits) : ""; }

// "+1.25 dB" / "-0.40 dB", or what the comparison lacks.
std::string gainText(const std::optional<double>& db) {
  return db ? (*db >= 0 ? "+" : "") + fixed(*db, 2) + " dB" : "n/a (outside)";
}

// The direct points, sorted by time.
std::vector<const QualityPoint*> directCurve(const std::vector<QualityPoint>& points) {
  std::vector<const QualityPoint*> curve;
  for (const QualityPoint& p : points) {
    if (p.path == "direct") curve.push_back(&p);
  }
  std::sort(curve.begin(), curve.end(), [](auto* a, auto* b) { return a->frameMs() < b->frameMs(); });
  return curve;
}

// Pareto front of the adaptive and the direct points, sorted by time: each point is better than every faster one. A
// direct frame at N spp is the adaptive path refining every target (threshold 0), so the direct points belong to the
// same family; empty when there is no adaptive point.
std::vector<const QualityPoint*> adaptiveCurve(const std::vector<QualityPoint>& points) {
  std::vector<const QualityPoint*> candidates;
  for (const QualityPoint& p : points) {
    if (p.path == "adaptive" || p.path == "direct") candidates.push_back(&p);
  }
  if (std::none_of(candidates.begin(), candidates.end(), [](auto* p) { return p->path == "adaptive"; })) return {};
  std::sort(candidates.begin(), candidates.end(), [](auto* a, auto* b) { return a->frameMs() < b->frameMs(); });
  std::vector<const QualityPoint*> front;
  for (const QualityPoint* p : candidates) {
    if (front.empty() || p->psnrCorrectedDb > front.back()->psnrCorrectedDb) front.push_back(p);
  }
  return front;
}

// PSNR of the direct curve at time ms (log2-time interpolation), nullopt outside its time range.
std::optional<double> psnrAtTime(const std::vector<const QualityPoint*>& curve, double ms) {
  for (std::size_t i = 0; i + 1 < curve.size(); ++i) {
    const double t0 = std::log2(curve[i]->frameMs()), t1 = std::log2(curve[i + 1]->frameMs());
    const double t = std::log2(ms);
    if (t >= t0 && t <= t1 && t1 > t0) {
      const double w = (t - t0) / (t1 - t0);
      return curve[i]->psnrCorrectedDb * (1 - w) + curve[i + 1]->psnrCorrectedDb * w;
    }
  }
  return std::nullopt;
}

// Time at which the direct curve first reaches psnr (log2-time interpolation), nullopt if it never does.
std::optional<double> timeAtPsnr(const std::vector<const QualityPoint*>& curve, double psnr) {
  if (!curve.empty() && curve[0]->psnrCorrectedDb >= psnr) return curve[0]->frameMs();
  for (std::size_t i = 0; i + 1 < curve.size(); ++i) {
    const double p0 = curve[i]->psnrCorrectedDb, p1 = curve[i + 1]->psnrCorrectedDb;
    if (p0 < psnr && p1 >= psnr) {
      const double w = (psnr - p0) / (p1 - p0);
      return std::exp2(std::log2(curve[i]->frameMs()) * (1 - w) + std::log2(curve[i + 1]->frameMs()) * w);
    }
  }
  return std::nullopt;
}

// The points with every time on quilt q's time scale: the median over the runs of the point's time / q's time in
// the same run, times q's median time. One run (or a point timed fewer times): its own time.
std::vector<QualityPoint> onQuiltScale(const std::vector<QualityPoint>& points, const QualityPoint& q) {
  std::vector<QualityPoint> scaled = points;
  for (QualityPoint& p : scaled) {
    if (p.runMs.size() < 2 || p.runMs.size() != q.runMs.size()) continue;
    std::vector<double> ratios;
    for (std::size_t r = 0; r < p.runMs.size(); ++r) ratios.push_back(p.runMs[r] / q.runMs[r]);
    p.renderMs = median(ratios) * q.frameMs();
    p.runMs.clear();
  }
  return scaled;
}

// The points as timed in run r alone.
std::vector<QualityPoint> inRun(const std::vector<QualityPoint>& points, std::size_t r) {
  std::vector<QualityPoint> run = points;
  for (QualityPoint& p : run) {
    if (r < p.runMs.size()) p.renderMs = p.runMs[r];
    p.runMs.clear();
  }
  return run;
}

nlohmann::json optionalJson(const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); }

nlohmann::json pointJson(const QualityPoint& p) {
  return {{"path", p.path},
          {"spp", p.spp},
          {"quilt", p.quilt},
          {"filter", p.filter},
          {"render_ms", p.renderMs},
          {"gpu_stage_ms", p.gpuMs},
          {"interleave_cpu_ms", p.interleaveMs},
          {"frame_ms", p.frameMs()},
          {"rmse", p.metrics.rmse},
          {"psnr_db", p.metrics.psnrDb},
          {"psnr_corrected_db", p.psnrCorrectedDb},
          {"ssim", p.metrics.ssim},
          {"refine_spp", p.refineSpp},
          {"refine_contrast", p.refineContrast},
          {"refined_fraction", p.refinedFraction},
          {"run_ms", p.runMs}};
}

}  // namespace

double QualityPoint::frameMs() const { return runMs.size() > 1 ? median(runMs) : renderMs; }

std::vector<EqualComparison> DisplayQuality::compare() const {
  std::vector<EqualComparison> out;
  for (const QualityPoint& q : points) {
    if (q.path != "quilt") continue;
    const std::vector<QualityPoint> scaled = onQuiltScale(points, q);
    const auto curve = directCurve(scaled);
    const auto adaptive = adaptiveCurve(scaled);
    EqualComparison c{&q, std::nullopt, std::nullopt, std::nullopt, std::nullopt, {}};
    const double ms = q.frameMs(), psnr = q.psnrCorrectedDb;
    if (auto at = psnrAtTime(curve, ms)) c.directGainDb = *at - psnr;
    if (auto t = timeAtPsnr(curve, psnr)) c.speedup = ms / *t;
    if (auto at = psnrAtTime(adaptive, ms)) c.adaptiveGainDb = *at - psnr;
    if (auto t = timeAtPsnr(adaptive, psnr)) c.adaptiveSpeedup = ms / *t;
    for (std::size_t r = 0; q.runMs.size() > 1 && r < q.runMs.size(); ++r) {
      const std::vector<QualityPoint> run = inRun(points, r);
      const auto at = psnrAtTime(adaptiveCurve(run), q.runMs[r]);
      c.adaptiveGainDbEachRun.push_back(at ? std::optional<double>(*at - psnr) : std::nullopt);
    }
    out.push_back(c);
  }
  return out;
}

void printQualityReport(std::ostream& out, const QualityReport& r) {
  out << "device: " << r.device << ", scene " << r.scene << ", depth " << r.maxDepth << "\n";
  for (const DisplayQuality& d : r.displays) {
    out << "\n"
        << d.display << " (" << d.panelWidth << "x" << d.panelHeight << "), reference spp " << d.refSpp << " ("
        << fixed(d.refMs / 1000, 1) << " s, own noise PSNR " << fixed(psnrFromMse(d.refNoiseMse), 2) << " dB)"
        << (d.runs > 1 ? ", frame ms = median of " + std::to_string(d.runs) + " runs" : "") << "\n";
    out << "  path      spp  quilt / refinement          filter        frame ms   RMSE     PSNR  PSNRcorr  SSIM\n";
    for (const QualityPoint& p : d.points) {
      char line[256];
      const std::string variant = p.path == "adaptive"
                                      ? "refine " + std::to_string(p.refineSpp) + " >= " + fixed(p.refineContrast, 3) +
                                            " (" + fixed(100.0 * p.refinedFraction, 1) + " %)"
                                      : p.quilt;
      std::snprintf(line, sizeof line, "  %-8s %4u  %-26s  %-12s %9.1f  %.5f  %6.2f  %6.2f  %.4f\n", p.path.c_str(),
                    p.spp, variant.c_str(), p.filter.c_str(), p.frameMs(), p.metrics.rmse, p.metrics.psnrDb,
                    p.psnrCorrectedDb, p.metrics.ssim);
      out << line;
    }
    for (const EqualComparison& c : d.compare()) {
      out << "  vs quilt " << c.quilt->quilt << " spp " << c.quilt->spp << " " << c.quilt->filter
          << ": direct at equal time " << gainText(c.directGainDb) << ", at equal PSNR "
          << (c.speedup ? fixed(*c.speedup, 2) + "x faster" : "n/a (not reached)") << "; adaptive at equal time "
          << gainText(c.adaptiveGainDb) << ", at equal PSNR "
          << (c.adaptiveSpeedup ? fixed(*c.adaptiveSpeedup, 2) + "x faster" : "n/a (not reached)");
      if (!c.adaptiveGainDbEachRun.empty()) {
        out << "; adaptive at equal time in each run:";
        for (const auto& gain : c.adaptiveGainDbEachRun) out << " " << (gain ? fixed(*gain, 2) : "n/a");
      }
      out << "\n";
    }
  }
}

void writeQualityCsv(const std::string& path, const QualityReport& r) {
  std::ostringstream csv;
  csv << "display,path,spp,quilt,filter,render_ms,gpu_stage_ms,interleave_cpu_ms,frame_ms,rmse,psnr_db,"
         "psnr_corrected_db,ssim,refine_spp,refine_contrast,refined_fraction\n";
  for (const DisplayQuality& d : r.displays) {
    for (const QualityPoint& p : d.points) {
      csv << d.display << "," << p.path << "," << p.spp << "," << p.quilt << "," << p.filter << ","
          << fixed(p.renderMs, 1) << "," << fixed(p.gpuMs, 1) << "," << fixed(p.interleaveMs, 1) << ","
          << fixed(p.frameMs(), 1) << "," << fixed(p.metrics.rmse, 6) << "," << fixed(p.metrics.psnrDb, 3) << ","
          << fixed(p.psnrCorrectedDb, 3) << "," << fixed(p.metrics.ssim, 5) << "," << p.refineSpp << ","
          << fixed(p.refineContrast, 4) << "," << fixed(p.refinedFraction, 5) << "\n";
    }
  }
  writeTextFile(path, csv.str());
}

void writeQualitySummaryCsv(const std::string& path, const QualityReport& r) {
  std::ostringstream csv;
  csv << "display,quilt,quilt_spp,filter,quilt_frame_ms,quilt_psnr_corrected_db,direct_gain_db_at_equal_time,"
         "direct_speedup_at_equal_psnr,adaptive_gain_db_at_equal_time,adaptive_speedup_at_equal_psnr\n";
  for (const DisplayQuality& d : r.displays) {
    for (const EqualComparison& c : d.compare()) {
      csv << d.display << "," << c.quilt->quilt << "," << c.quilt->spp << "," << c.quilt->filter << ","
          << fixed(c.quilt->frameMs(), 1) << "," << fixed(c.quilt->psnrCorrectedDb, 3) << ","
          << optionalText(c.directGainDb, 3) << "," << optionalText(c.speedup, 3) << ","
          << optionalText(c.adaptiveGainDb, 3) << "," << optionalText(c.adaptiveSpeedup, 3) << "\n";
    }
  }
  writeTextFile(path, csv.str());
}

void writeQualityJson(const std::string& path, const QualityReport& r) {
  nlohmann::json displays = nlohmann::json::array();
  for (const DisplayQuality& d : r.displays) {
    nlohmann::json points = nlohmann::json::array(), comparisons = nlohmann::json::array();
    for (const QualityPoint& p : d.points) points.push_back(pointJson(p));
    for (const EqualComparison& c : d.compare()) {
      comparisons.push_back({{"quilt", c.quilt->quilt},
                             {"spp", c.quilt->spp},
                             {"filter", c.quilt->filter},
                             {"direct_gain_db_at_equal_time", optionalJson(c.directGainDb)},
                             {"direct_speedup_at_equal_psnr", optionalJson(c.speedup)},
                             {"adaptive_gain_db_at_equal_time", optionalJson(c.adaptiveGainDb)},
                             {"adaptive_speedup_at_equal_psnr", optionalJson(c.adaptiveSpeedup)}});
      nlohmann::json eachRun = nlohmann::json::array();
      for (const auto& gain : c.adaptiveGainDbEachRun) eachRun.push_back(optionalJson(gain));
      comparisons.back()["adaptive_gain_db_at_equal_time_each_run"] = eachRun;
    }
    displays.push_back({{"display", d.display},
                        {"panel", {d.panelWidth, d.panelHeight}},
                        {"ref_spp", d.refSpp},
                        {"runs", d.runs},
                        {"ref_ms", d.refMs},
                        {"ref_noise_mse", d.refNoiseMse},
                        {"points", points},
                        {"comparisons", comparisons}});
  }
  const nlohmann::json doc = {{"benchmark", "holotrace-bench-quality"},
                              {"date", r.date},
                              {"device", r.device},
                              {"scene", r.scene},
                              {"max_depth", r.maxDepth},
                              {"metric_space", "sRGB-encoded, clamped [0,1]"},
                              {"displays", displays}};
  writeTextFile(path, doc.dump(2) + "\n");
}

}  // namespace ht::bench
