// parallel_chunks.h - run a function over consecutive chunks of a flat range [0, count) on N std::threads, chunks
// handed out in order from an atomic counter (neighbouring items stay on one thread, coherent rays together).
// Host-side CPU loops only (the quilt interleave, the simulated viewer, the benchmark tracers); no global pool.
#pragma once
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace ht {

// Runs function(begin, end) over [0, count) in chunks of `chunk` consecutive items (the last one may be shorter) on
// max(threads, 1) threads, the calling thread included.
template <class ChunkFunction>
void forEachChunkParallel(std::size_t count, std::size_t chunk, unsigned threads, const ChunkFunction& function) {
  chunk = std::max<std::size_t>(chunk, 1);
  const std::size_t chunkCount = (count + chunk - 1) / chunk;
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < chunkCount; i = next++) function(i * chunk, std::min(count, (i + 1) * chunk));
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < std::max(threads, 1u); ++t) pool.emplace_back(worker);
  worker();
  for (auto& thread : pool) thread.join();
}

// The machine's thread count (at least 1): the default for CPU image loops.
inline unsigned hardwareThreads() { return std::max(1u, std::thread::hardware_concurrency()); }

}  // namespace ht
