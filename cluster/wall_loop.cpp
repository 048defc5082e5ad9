// wall_loop.cpp - see wall_loop.h.
#include "cluster/wall_loop.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "cluster/cluster_error.h"

namespace ht::cluster {
namespace {

// How long a catching-up rank waits for a barrier the others should already be in.
constexpr std::int64_t kProbeUs = 1000;

std::string ms(std::int64_t us) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f ms", double(us) / 1000.0);
  return text;
}

class WallRun {
 public:
  WallRun(Communicator& comm, const WallLoopOptions& options, const WallCallbacks& callbacks, JobClock& clock)
      : comm_(comm), options_(options), callbacks_(callbacks), clock_(clock), swap_(comm) {}

  std::vector<WallFrameRecord> run() {
    synchronizeJobClock(comm_, clock_);
    std::uint32_t next = 0;
    while (wantsFrame(next)) next = frame(next, isLast(next));
    const std::uint32_t end = agreeOnEnd(next);
    for (std::uint32_t f = next; f < end; ++f) skip(f);
    if (!options_.frames) frame(end, true);  // --seconds: one common last frame
    swap_.finish();
    for (std::uint32_t f = 0; f < records_.size(); ++f) {
      const auto r = swap_.result(f);
      records_[f].firstEntryUs = r->firstUs;
      records_[f].lastEntryUs = r->lastUs;
    }
    return std::move(records_);
  }

 private:
  bool wantsFrame(std::uint32_t f) const {
    if (options_.frames) return f < *options_.frames;
    return f == 0 || double(clock_.nowUs()) < *options_.seconds * 1e6;
  }
  bool isLast(std::uint32_t f) const { return options_.frames && f + 1 == *options_.frames; }
  // A late rank may skip `f` only if it is not the last frame of a --frames run.
  bool mayskip(std::uint32_t f) const { return options_.frames ? f + 1 < *options_.frames : wantsFrame(f); }
  WallFrameRecord& record(std::uint32_t f) {
    if (records_.size() <= f) records_.resize(f + 1);
    return records_[f];
  }

  // Renders, swaps and presents frame f; returns the next frame to render.
  std::uint32_t frame(std::uint32_t f, bool last) {
    const std::int64_t start = clock_.nowUs();
    callbacks_.render(f);
    WallFrameRecord& rec = record(f);
    rec.entryUs = clock_.nowUs();
    rec.renderUs = rec.entryUs - start;
    swap_.enter(f, rec.entryUs);
    const auto entries = swap_.waitUntil(f, rec.entryUs + options_.deadlineUs, clock_);
    rec.releaseUs = clock_.nowUs();
    if (entries && rec.entryUs > entries->firstUs + options_.deadlineUs) {
      rec.outcome = last ? WallOutcome::LateShown : WallOutcome::Late;
      rec.lateByUs = rec.entryUs - (entries->firstUs + options_.deadlineUs);
      missed_ = 0;
      callbacks_.warn("frame " + std::to_string(f) + ": late for the swap by " + ms(rec.lateByUs) + " (entered " +
                      ms(rec.entryUs - entries->firstUs) + " after the first rank, deadline " +
                      ms(options_.deadlineUs) +
                      (last ? "); the last frame: shown anyway" : "); not shown, catching up"));
      if (!last) return catchUp(f + 1);
      present(f);
      return f + 1;
    }
    rec.outcome = entries ? WallOutcome::OnTime : WallOutcome::TimedOut;
    present(f);
    if (entries) {
      missed_ = 0;
    } else {
      noteTimeout(f);
    }
    return f + 1;
  }

  void present(std::uint32_t f) {
    const std::int64_t start = clock_.nowUs();
    const std::int64_t flip = callbacks_.present(f);
    WallFrameRecord& rec = record(f);
    rec.flipUs = flip;
    rec.presentUs = clock_.nowUs() - start;
  }

  void noteTimeout(std::uint32_t f) {
    ++missed_;
    callbacks_.warn("frame " + std::to_string(f) + ": swap barrier not complete after " + ms(options_.deadlineUs) +
                    "; presented without the late rank(s)");
    if (options_.maxMissed > 0 && missed_ >= options_.maxMissed) {
      throw ClusterError("the swap barrier timed out on " + std::to_string(missed_) + " frames in a row (up to frame " +
                         std::to_string(f) + ", deadline " + ms(options_.deadlineUs) +
                         "): a rank does not keep up; raise --swap-timeout, lighten its projectors' load, or set "
                         "--max-missed 0 to keep the wall running without it");
    }
  }

  // Enters frame f's barrier without rendering it.
  std::int64_t skip(std::uint32_t f) {
    WallFrameRecord& rec = record(f);
    rec.outcome = WallOutcome::Skipped;
    rec.entryUs = clock_.nowUs();
    swap_.enter(f, rec.entryUs);
    return rec.entryUs;
  }

  // After a late frame: skips the frames the others are already past; returns the frame to render next.
  std::uint32_t catchUp(std::uint32_t g) {
    while (mayskip(g)) {
      const std::int64_t entry = skip(g);
      const auto entries = swap_.waitUntil(g, entry + kProbeUs, clock_);
      record(g).releaseUs = clock_.nowUs();
      if (entries) record(g).lateByUs = entry - (entries->firstUs + options_.deadlineUs);
      if (!entries || entry <= entries->firstUs + options_.deadlineUs) return g + 1;  // the others are at g
      ++g;
    }
    return g;
  }

  // --frames: every rank ends at N. --seconds: the furthest frame any rank reached.
  std::uint32_t agreeOnEnd(std::uint32_t next) {
    const std::uint64_t mine = next;
    const auto all = comm_.allGather(std::span(reinterpret_cast<const std::uint8_t*>(&mine), sizeof mine));
    std::uint64_t end = 0;
    for (std::size_t at = 0; at + sizeof end <= all.size(); at += sizeof end) {
      std::uint64_t value = 0;
      std::memcpy(&value, all.data() + at, sizeof value);
      end = std::max(end, value);
    }
    return static_cast<std::uint32_t>(end);
  }

  Communicator& comm_;
  const WallLoopOptions& options_;
  const WallCallbacks& callbacks_;
  JobClock& clock_;
  SwapBarrier swap_;
  std::vector<WallFrameRecord> records_;
  std::uint32_t missed_ = 0;
};

}  // namespace

const char* wallOutcomeName(WallOutcome outcome) {
  switch (outcome) {
    case WallOutcome::OnTime: return "on time";
    case WallOutcome::TimedOut: return "timed out";
    case WallOutcome::Late: return "late";
    case WallOutcome::Skipped: return "skipped";
    case WallOutcome::LateShown: return "late, shown (last frame)";
    default: return "missing";
  }
}

std::vector<WallFrameRecord> runWallLoop(Communicator& comm, const WallLoopOptions& options,
                                         const WallCallbacks& callbacks, JobClock& clock) {
  return WallRun(comm, options, callbacks, clock).run();
}

}  // namespace ht::cluster
