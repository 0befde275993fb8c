// Google Benchmark kernels for the exact geometry: batch against one-by-one insertion
// (docs/design.md, Exactness rule 4), growing roads in a cell, splitting a cell by them.
#include <benchmark/benchmark.h>

#include <cmath>

#include "generate/city/random.h"
#include "geom/cell.h"
#include "geom/grid.h"
#include "geom/planar_map.h"

namespace {

// n segments across a 1 km square, crossing each other.
std::vector<std::pair<geom::Vec2, geom::Vec2>> crossing_segments(int n) {
  exacity::Random rng(42);
  std::vector<std::pair<geom::Vec2, geom::Vec2>> s;
  for (int i = 0; i < n; ++i)
    s.push_back({geom::snap({rng.uniform(0, 1000), rng.uniform(0, 1000)}), geom::snap({rng.uniform(0, 1000), rng.uniform(0, 1000)})});
  return s;
}

void BM_InsertInOneBatch(benchmark::State& state) {
  auto segments = crossing_segments(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    geom::PlanarMap map;
    for (auto [a, b] : segments) map.add_polyline({a, b}, 0);
    map.insert_batch();
    benchmark::DoNotOptimize(map.counts());
  }
}
BENCHMARK(BM_InsertInOneBatch)->Arg(100)->Arg(400)->Unit(benchmark::kMillisecond);

void BM_InsertOneByOne(benchmark::State& state) {
  auto segments = crossing_segments(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    geom::PlanarMap map;
    for (auto [a, b] : segments) {
      map.add_polyline({a, b}, 0);
      map.insert_batch();
    }
    benchmark::DoNotOptimize(map.counts());
  }
}
BENCHMARK(BM_InsertOneByOne)->Arg(100)->Arg(400)->Unit(benchmark::kMillisecond);

geom::Cell square_cell(double size) {
  geom::PlanarMap map;
  map.add_ring({{0, 0}, {size, 0}, {size, size}, {0, size}}, 0);
  map.insert_batch();
  map.label_faces([](const geom::Windings& w) { return geom::winding_of(w, 0) ? 1 : 0; });
  return map.cells({-1, 0}, {0, 0})[0];
}

// Four wandering roads of 40 m steps across a 1 km square, and the split they make.
std::vector<geom::Path> grow_four(const geom::Cell& cell) {
  exacity::Random rng(7);
  geom::Growth g(cell, 40);
  std::vector<geom::Path> roads;
  for (int i = 0; i < 4; ++i) {
    double theta = i * M_PI / 2;
    geom::Vec2 at{500, 500};
    g.begin(at);
    geom::Growth::Met met;
    do {
      theta += rng.uniform(-0.1, 0.1);
      at = geom::snap({at.x + 40 * std::cos(theta), at.y + 40 * std::sin(theta)});
      met = g.extend(at);
    } while (met.what == geom::Growth::Met::Nothing);
    roads.push_back(g.end());
  }
  return roads;
}

void BM_GrowFourRoads(benchmark::State& state) {
  geom::Cell cell = square_cell(1000);
  for (auto _ : state) benchmark::DoNotOptimize(grow_four(cell));
}
BENCHMARK(BM_GrowFourRoads)->Unit(benchmark::kMillisecond);

void BM_SplitCell(benchmark::State& state) {
  geom::Cell cell = square_cell(1000);
  auto roads = grow_four(cell);
  for (auto _ : state) benchmark::DoNotOptimize(geom::split_cell(cell, roads, 1));
}
BENCHMARK(BM_SplitCell)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
