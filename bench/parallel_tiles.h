// parallel_tiles.h - run a function over the square tiles of a width x height grid (or over chunks of a flat
// range) on N std::threads, handed out in order from an atomic counter (coherent rays stay together).
#pragma once
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

namespace ht::bench {

struct Tile {
  std::uint32_t x0, y0, x1, y1;  // half-open pixel rectangle
};

template <class TileFunction>
void forEachTileParallel(std::uint32_t width, std::uint32_t height, std::uint32_t tileSize, unsigned threads,
                         const TileFunction& function) {
  const std::uint32_t tilesX = (width + tileSize - 1) / tileSize;
  const std::uint32_t tilesY = (height + tileSize - 1) / tileSize;
  const std::uint32_t tileCount = tilesX * tilesY;
  std::atomic<std::uint32_t> next{0};
  auto worker = [&] {
    for (std::uint32_t i = next++; i < tileCount; i = next++) {
      const std::uint32_t tx = i % tilesX, ty = i / tilesX;
      function(Tile{tx * tileSize, ty * tileSize, std::min(width, (tx + 1) * tileSize),
                    std::min(height, (ty + 1) * tileSize)});
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < std::max(threads, 1u); ++t) pool.emplace_back(worker);
  worker();
  for (auto& thread : pool) thread.join();
}

// Runs function(begin, end) over [0, count) in chunks of `chunk` consecutive items, chunks handed out in order.
template <class ChunkFunction>
void forEachChunkParallel(std::size_t count, std::size_t chunk, unsigned threads, const ChunkFunction& function) {
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

}  // namespace ht::bench
