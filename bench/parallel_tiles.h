// parallel_tiles.h - run a function over the square tiles of a width x height grid on N std::threads, handed out in
// order from an atomic counter (coherent rays stay together). Flat ranges: common/parallel_chunks.h.
#pragma once
#include <algorithm>
#include <cstdint>

#include "common/parallel_chunks.h"

namespace ht::bench {

struct Tile {
  std::uint32_t x0, y0, x1, y1;  // half-open pixel rectangle
};

template <class TileFunction>
void forEachTileParallel(std::uint32_t width, std::uint32_t height, std::uint32_t tileSize, unsigned threads,
                         const TileFunction& function) {
  const std::uint32_t tilesX = (width + tileSize - 1) / tileSize;
  const std::uint32_t tilesY = (height + tileSize - 1) / tileSize;
  forEachChunkParallel(std::size_t(tilesX) * tilesY, 1, threads, [&](std::size_t i, std::size_t) {
    const auto tx = std::uint32_t(i % tilesX), ty = std::uint32_t(i / tilesX);
    function(Tile{tx * tileSize, ty * tileSize, std::min(width, (tx + 1) * tileSize),
                  std::min(height, (ty + 1) * tileSize)});
  });
}

}  // namespace ht::bench
