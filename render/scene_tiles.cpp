// Tiles and levels of detail: each building and model's tile, and what one view makes of
// each tile (culled, simple or detailed).
#include <algorithm>
#include <cmath>

#include "render/scene_build.h"

namespace render {

RenderScene::StructureTiles RenderScene::tile_structures(const exacity::City& city, const geom::Box& world, float tile_size) {
  StructureTiles tiles;
  tiles.nx = std::max(1, static_cast<int>(std::ceil(world.width() / tile_size)));
  tiles.ny = std::max(1, static_cast<int>(std::ceil(world.height() / tile_size)));
  tiles.tile_of.resize(city.buildings.size() + city.models.size());
  tiles.boxes.resize(static_cast<std::size_t>(tiles.nx * tiles.ny));
  // The tile of a structure's polygon, which grows to hold it from base to top_z.
  auto place = [&](const geom::Polygon& polygon, double base, double top_z) {
    geom::Box fb = geom::Box::none();
    for (auto p : polygon.outer) fb.add(p);
    const double cx = (fb.min_x + fb.max_x) / 2, cy = (fb.min_y + fb.max_y) / 2;
    const int tx = std::clamp(static_cast<int>((cx - world.min_x) / tile_size), 0, tiles.nx - 1);
    const int ty = std::clamp(static_cast<int>((cy - world.min_y) / tile_size), 0, tiles.ny - 1);
    const int k = ty * tiles.nx + tx;
    tiles.boxes[k].add(to_scene(fb.min_x, fb.min_y, base));
    tiles.boxes[k].add(to_scene(fb.max_x, fb.max_y, top_z));
    top = std::max(top, static_cast<float>(top_z));
    return k;
  };
  exacity::for_each_by_id(
      city.buildings, city.models,
      [&](const exacity::Building& b) { tiles.tile_of[b.id] = place(b.polygon, b.base, b.floor + b.height); },
      [&](const exacity::ModelInstance& m) { tiles.tile_of[m.id] = place(m.polygon, m.base, m.floor + m.height); });
  for (const exacity::Clutter& c : city.clutter.items)
    tiles.clutter_tile.push_back(place(c.instance.polygon, c.instance.base, c.instance.floor + c.instance.height));
  return tiles;
}

// Which tiles the view sees and which are near enough to be detailed; each non-empty
// tile's level is recorded in `tiles`.
RenderScene::TileView RenderScene::view_tiles(const std::vector<Box3>& boxes, const SceneOptions& options) {
  TileView v{std::vector<bool>(boxes.size(), options.view == nullptr), std::vector<bool>(boxes.size(), true)};
  Camera view;
  if (options.view) {
    view = to_scene(*options.view);
    TileBvh(boxes).visible(frustum(view, options.aspect), v.seen);
  }
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    if (boxes[k].lo.x > boxes[k].hi.x) continue;  // empty
    if (options.view) {
      const V3 c = (boxes[k].lo + boxes[k].hi) * 0.5f;
      v.detailed[k] = length(c - view.from) <= options.detail_distance;
    }
    tiles.push_back({static_cast<int>(k), !v.seen[k] ? "culled" : v.detailed[k] ? "detailed" : "simple"});
  }
  return v;
}

}  // namespace render
