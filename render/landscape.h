// The land beyond the city (docs/rendering.md, The land around the city): fields in rows
// of strips, as farmland is laid out, each a crop or a meadow, hedgerows along a share of
// their edges, and woods where a low-frequency noise groups fields; all procedural and
// deterministic from the city's seed, in scene coordinates. The city's own ground (its
// zones, roads and water, and a verge around them) stays grass.
#pragma once

#include <cstdint>
#include <vector>

#include "generate/city.h"
#include "geom/measure.h"
#include "render/vec.h"

namespace render {

// A tree or shrub of the landscape: the built-in broadleaf or conifer, scaled.
struct LandscapeTree {
  V3 at;  // its foot, on the terrain
  float width = 1, height = 1, angle = 0;
  bool conifer = false;
  int tint = 0;
};

// A strip the land beyond keeps clear of fields and trees, but for a grass verge: a road
// or river carried on past the city (render/onward.h), in scene coordinates.
struct Corridor {
  geom::Vec2 a, b;
  double half_width = 0;
};

class Landscape {
 public:
  // `city_box`: the city's ground in scene coordinates; `origin`: the scene's origin in the
  // city's (the ground's polygons are in the city's coordinates).
  Landscape(const exacity::Ground& ground, const geom::Box& city_box, geom::Vec2 origin, std::uint32_t seed,
            std::vector<Corridor> corridors = {});

  // 0 on the city's ground and its verge, 1 from 45 m past it, smoothly between.
  float beyond(float x, float y) const;
  // The ground's albedo at a point beyond the city (the field's crop, its rows, its margin).
  V3 albedo(float x, float y) const;
  // The trees of the woods and hedgerows standing in `region` (scene coordinates), their feet
  // at the height `ground_at` gives.
  template <class GroundAt>
  std::vector<LandscapeTree> trees(const geom::Box& region, const GroundAt& ground_at) const {
    std::vector<LandscapeTree> out = tree_spots(region);
    for (LandscapeTree& t : out) t.at.z = static_cast<float>(ground_at(t.at.x, t.at.y));
    return out;
  }

  enum class Crop : std::uint8_t { Pasture, Meadow, Wheat, Barley, Green, Ploughed, Rapeseed, Woods };
  struct Field {
    int column, row;
    Crop crop;
    float u0, u1, v0, v1;  // its sides in the fields' frame (u along the rows)
    float u, v;            // the point, in that frame
  };
  Field field_at(float x, float y) const;

 private:
  std::vector<LandscapeTree> tree_spots(const geom::Box& region) const;
  float row_edge(int row) const;
  float row_width(int row) const;  // the fields' typical width along a row
  float column_edge(int column, int row) const;
  bool hedged_column_edge(int column, int row) const;
  bool hedged_row_edge(int row, float u) const;
  bool woods_at(float u, float v) const;
  // How far (x, y) lies from the nearest corridor's side (negative inside it).
  double from_corridors(float x, float y) const;
  float hash(int a, int b, int salt) const;
  // The city's ground on a grid: the distance from it in metres, for beyond().
  geom::Box grid_box_;
  float cell_ = 4;
  int nx_ = 0, ny_ = 0;
  std::vector<float> distance_;
  std::uint32_t seed_;
  std::vector<Corridor> corridors_;
  float cos_ = 1, sin_ = 0;  // the fields' frame, turned by the seed
};

}  // namespace render
