// rank_identity.h - the start-up check of a cluster render: every rank states which build it runs and SHA-256
// digests of the display camera it resolved, the scene it decoded and its render settings; the ranks exchange them
// (one MPI_Allgather) and, if any differs from rank 0's, every rank stops with the same message before rendering.
#pragma once
#include <string>
#include <vector>

#include "cluster/communicator.h"
#include "gpu/display_camera.h"
#include "gpu/renderer.h"

namespace ht::cluster {

struct RankIdentity {
  std::string build;     // version, commit, compiler, build type (buildId())
  std::string display;   // displayDigest()
  std::string scene;     // SHA-256 of the scene bytes (scene_bytes.h)
  std::string settings;  // settingsDigest()
};

// This build: "holotrace <version> <commit> <compiler> <build type>".
std::string buildId();

// Digest of what a rank renders for a display: its name, the camera's model parameters (ray table included), the
// frame shape and the quilt layout. Equal digests mean the ranks trace the same rays.
std::string displayDigest(const std::string& displayName, const gpu::DisplayCamera& camera);

// Digest of the settings that change pixels (spp, filter, depth, seed, refinement, specialisation).
std::string settingsDigest(const gpu::RenderSettings& settings);

// The first difference between each rank's identity and rank 0's, one line per differing rank (empty: all agree).
std::vector<std::string> identityMismatches(const std::vector<RankIdentity>& ranks);

// Exchanges the identities; throws RankMismatchError on every rank when any differs, naming the ranks and what.
void checkRankIdentities(Communicator& comm, const RankIdentity& mine);

}  // namespace ht::cluster
