// cluster_job.cpp - see cluster_job.h. The encoding is this build's own (every rank runs the same build, checked at
// start): a fixed head of trivially copyable fields, then the display id, the camera digest, the dropped versions
// and the scene bytes, whose lengths the head gives.
#include "server/cluster_job.h"

#include <cstring>
#include <type_traits>

#include "cluster/cluster_error.h"

namespace ht::server {
namespace {

struct JobHead {
  std::uint32_t kind = 0, path = 0;
  std::uint64_t sceneVersion = 0, sceneBytes = 0, dropCount = 0;
  std::uint32_t displayIdBytes = 0, digestBytes = 0;
  Bounds3 loadBounds;
  glm::dvec3 cameraTarget{0.0};
  double cameraSize = 0.0, observerDistance = 0.0, observerHeight = 0.0;
  std::uint32_t present = 0;  // bit 0 target, 1 size, 2 observer distance, 3 observer height
  std::uint32_t spp = 0, filter = 0, maxDepth = 0, seed = 0, refineSpp = 0, forceAllFeatures = 0;
  float refineContrast = 0.0f;
};
static_assert(std::is_trivially_copyable_v<JobHead>);
// A field added to RenderSettings changes pixels on every rank only if the job carries it: add it to JobHead,
// headOf() and jobOf(), then update this size. RenderSettings::reuse is not sent: a reused frame equals a full one
// bit for bit, and a rank's units are bands or groups of views, which keep no reuse state (nor, then, is
// RenderSettings::reuseMaxDirtyShare). Nor is RenderSettings::maxPathsPerBatch: batching does not change a frame's
// bits.
static_assert(sizeof(gpu::RenderSettings) == 96,
              "gpu::RenderSettings changed: send the new field in the cluster job (server/cluster_job.cpp)");

constexpr std::uint32_t kTarget = 1, kSize = 2, kObserverDistance = 4, kObserverHeight = 8;  // JobHead::present bits

JobHead headOf(const ClusterJob& job) {
  JobHead h{};
  h.kind = static_cast<std::uint32_t>(job.kind);
  h.path = static_cast<std::uint32_t>(job.path);
  h.sceneVersion = job.sceneVersion;
  h.sceneBytes = job.sceneBytes.size();
  h.dropCount = job.dropVersions.size();
  h.displayIdBytes = static_cast<std::uint32_t>(job.displayId.size());
  h.digestBytes = static_cast<std::uint32_t>(job.cameraDigest.size());
  h.loadBounds = job.loadBounds;
  h.present = (job.cameraTarget ? kTarget : 0) | (job.cameraSize ? kSize : 0) |
              (job.observerDistance ? kObserverDistance : 0) | (job.observerHeight ? kObserverHeight : 0);
  h.cameraTarget = job.cameraTarget.value_or(glm::dvec3(0.0));
  h.cameraSize = job.cameraSize.value_or(0.0);
  h.observerDistance = job.observerDistance.value_or(0.0);
  h.observerHeight = job.observerHeight.value_or(0.0);
  const gpu::RenderSettings& s = job.settings;
  h.spp = s.spp;
  h.filter = static_cast<std::uint32_t>(s.filter);
  h.maxDepth = s.maxDepth;
  h.seed = s.seed;
  h.refineSpp = s.refineSpp;
  h.forceAllFeatures = s.forceAllFeatures ? 1 : 0;
  h.refineContrast = s.refineContrast;
  return h;
}

template <typename T>
std::optional<T> when(bool present, T value) {
  return present ? std::optional<T>(value) : std::nullopt;
}

ClusterJob jobOf(const JobHead& h) {
  ClusterJob job;
  job.kind = static_cast<ClusterJob::Kind>(h.kind);
  job.path = static_cast<gpu::CameraPath>(h.path);
  job.sceneVersion = h.sceneVersion;
  job.loadBounds = h.loadBounds;
  job.cameraTarget = when((h.present & kTarget) != 0, h.cameraTarget);
  job.cameraSize = when((h.present & kSize) != 0, h.cameraSize);
  job.observerDistance = when((h.present & kObserverDistance) != 0, h.observerDistance);
  job.observerHeight = when((h.present & kObserverHeight) != 0, h.observerHeight);
  gpu::RenderSettings& s = job.settings;
  s.spp = h.spp;
  s.filter = static_cast<gpu::SampleFilter>(h.filter);
  s.maxDepth = h.maxDepth;
  s.seed = h.seed;
  s.refineSpp = h.refineSpp;
  s.forceAllFeatures = h.forceAllFeatures != 0;
  s.refineContrast = h.refineContrast;
  return job;
}

void append(std::vector<std::uint8_t>& out, const void* data, std::size_t bytes) {
  if (bytes == 0) return;
  const std::size_t at = out.size();
  out.resize(at + bytes);
  std::memcpy(out.data() + at, data, bytes);
}

// Reads the parts after the head in order; every length is checked against what is left before anything is sized.
class Parts {
 public:
  explicit Parts(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  void need(std::uint64_t n, const char* what) const {
    if (n <= bytes_.size() - at_) return;
    throw cluster::ClusterError(std::string("rank 0's frame job ends inside its ") + what + " (" +
                                std::to_string(bytes_.size()) + " bytes)");
  }
  void copy(void* to, std::uint64_t n, const char* what) {
    need(n, what);
    if (n > 0) std::memcpy(to, bytes_.data() + at_, static_cast<std::size_t>(n));
    at_ += static_cast<std::size_t>(n);
  }
  template <typename Container>
  void fill(Container& out, std::uint64_t count, const char* what) {
    constexpr std::uint64_t kSize = sizeof(typename Container::value_type);
    need(count > (bytes_.size() - at_) / kSize ? bytes_.size() - at_ + 1 : count * kSize, what);
    out.resize(static_cast<std::size_t>(count));
    copy(out.data(), count * kSize, what);
  }
  bool done() const { return at_ == bytes_.size(); }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t at_ = 0;
};

}  // namespace

std::vector<cluster::WorkUnit> clusterFrameUnits(const gpu::FrameShape& shape, const gpu::RenderSettings& settings,
                                                 int ranks) {
  const cluster::WorkGrain grain = settings.refineSpp > 0 ? cluster::WorkGrain::WholeViews : cluster::WorkGrain::Auto;
  return cluster::planWork(shape, 1, ranks, grain);
}

std::vector<float> renderClusterUnit(gpu::Renderer& renderer, const gpu::DisplayCamera& camera,
                                     const gpu::RenderSettings& settings, const cluster::WorkUnit& unit) {
  gpu::RenderSettings unitSettings = settings;
  unitSettings.region = unit.region;
  return renderer.render(camera.camera, unitSettings).rgba;
}

std::vector<std::uint8_t> encodeClusterJob(const ClusterJob& job) {
  const JobHead head = headOf(job);
  std::vector<std::uint8_t> out;
  append(out, &head, sizeof head);
  append(out, job.displayId.data(), job.displayId.size());
  append(out, job.cameraDigest.data(), job.cameraDigest.size());
  append(out, job.dropVersions.data(), job.dropVersions.size() * sizeof(std::uint64_t));
  append(out, job.sceneBytes.data(), job.sceneBytes.size());
  return out;
}

ClusterJob decodeClusterJob(std::span<const std::uint8_t> bytes) {
  Parts parts(bytes);
  JobHead head;
  parts.copy(&head, sizeof head, "head");
  if (head.kind != static_cast<std::uint32_t>(ClusterJob::Kind::Frame) &&
      head.kind != static_cast<std::uint32_t>(ClusterJob::Kind::Stop)) {
    throw cluster::ClusterError("rank 0 sent a job of unknown kind " + std::to_string(head.kind));
  }
  ClusterJob job = jobOf(head);
  parts.fill(job.displayId, head.displayIdBytes, "display id");
  parts.fill(job.cameraDigest, head.digestBytes, "camera digest");
  parts.fill(job.dropVersions, head.dropCount, "dropped versions");
  parts.fill(job.sceneBytes, head.sceneBytes, "scene bytes");
  if (!parts.done()) throw cluster::ClusterError("rank 0's frame job has bytes after its scene");
  return job;
}

}  // namespace ht::server
