// embree_handles.h - the Embree device and scene behind an EmbreeTracer (private to bench/embree_*.cpp).
#pragma once
#include <embree3/rtcore.h>

#include "bench/embree_tracer.h"

namespace ht::bench {

struct EmbreeTracer::Handles {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  ~Handles() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

}  // namespace ht::bench
