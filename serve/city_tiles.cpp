#include "serve/city_tiles.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <map>
#include <string>

#include "generate/cancellable_invoke.h"
#include "generate/errors.h"
#include "generate/mesh/building_mesh.h"
#include "generate/export/gltf_export.h"
#include "generate/placement/buildings.h"
#include "generate/regenerate.h"
#include "render/facade.h"

namespace exacity::serve {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// Levels switch by the camera's distance to a tile's box, in tile sides: close enough to
// tell one building from its box, and to tell a box from its block's.
constexpr double kFullUntil = 3, kBoxesUntil = 8;

struct Bounds3 {
  geom::Box box = geom::Box::none();
  double bottom = INFINITY, top = -INFINITY;
  void add(double x, double y, double z) {
    box.add(geom::Vec2{x, y});
    bottom = std::min(bottom, z), top = std::max(top, z);
  }
  void add(const Bounds3& b) {
    box.add(b.box);
    bottom = std::min(bottom, b.bottom), top = std::max(top, b.top);
  }
};

Bounds3 mesh_bounds(const Mesh& mesh) {
  Bounds3 b;
  for (const Vec3& p : mesh.points) b.add(p[0], p[1], p[2]);
  return b;
}

// A block's structures of one zone in a tile: their box, and their tops weighed by footprint.
struct BlockPart {
  Bounds3 bounds;
  double area = 0, area_times_top = 0;
};

struct Tile {
  std::vector<Building> buildings;
  std::vector<ModelInstance> models, clutter;
  std::vector<StructureBox> boxes;
  std::map<std::pair<int, ZoneType>, BlockPart> blocks;
  Bounds3 bounds;
};

}  // namespace

double tile_size(const geom::Box& city) {
  const double extent = std::max(city.width(), city.height());
  return std::max(250.0, std::ceil(extent / 16 / 50) * 50);
}

namespace {

// Each extruded building's windows as the renderer draws them (render/facade.h,
// facade_style, from the city's seed and the building's id, zone, floor and eaves), so the
// 3D view's walls have the still's rows and bays: {"fields": [...], "buildings": {"ID": [...]}}.
void write_facades(const City& city, const fs::path& file) {
  auto rounded = [](float v) { return std::round(static_cast<double>(v) * 1e4) / 1e4; };
  json buildings = json::object();
  for (const Building& b : city.buildings) {
    const render::FacadeStyle f = render::facade_style(b.zone, city.settings.seed, b.stable_id, static_cast<float>(b.floor),
                                                       static_cast<float>(b.floor + b.eaves));
    buildings[std::to_string(b.stable_id)] = {rounded(f.storey), rounded(f.bay),   rounded(f.window),
                                       rounded(f.sill),   rounded(f.head),  rounded(f.phase),
                                       rounded(f.floor),  rounded(f.eaves), f.shopfront ? 1 : 0,
                                       f.kind == render::FacadeKind::CurtainWall ? 1 : 0};
  }
  const json facades{{"fields", {"storey", "bay", "window", "sill", "head", "phase", "floor", "eaves", "shopfront",
                                 "curtain_wall"}},
                     {"buildings", buildings}};
  std::ofstream out(file, std::ios::binary);
  out << facades.dump() << "\n";
  if (!out) throw UserError(file.string() + ": write failed (disk full?)");
}

// A tile's key holds thousands of numbers (a piece of clutter and a box each hold several):
// each as its double's eight bytes, exact and cheaper than text.
void append_bits(std::string& key, std::initializer_list<double> values) {
  for (double v : values) key.append(reinterpret_cast<const char*>(&v), sizeof v);
}
void append_bits(std::string& key, std::initializer_list<int> values) {
  for (int v : values) key.append(reinterpret_cast<const char*>(&v), sizeof v);
}

// A placed model or a piece of clutter, all the tiles' files read of it.
void append_instance(std::string& key, const ModelInstance& m) {
  key += 'i';
  append_bits(key, {m.placed.model, m.placed.tint, static_cast<int>(m.zone), static_cast<int>(m.kind), m.stable_id});
  append_bits(key, {m.placed.position.x, m.placed.position.y, m.placed.angle, m.placed.scale, m.height, m.base, m.floor});
  auto ring = [&](const geom::Ring& r) {
    append_bits(key, {static_cast<int>(r.size())});
    for (geom::Vec2 p : r) append_bits(key, {p.x, p.y});
  };
  ring(m.polygon.outer);
  append_bits(key, {static_cast<int>(m.polygon.holes.size())});
  for (const geom::Ring& hole : m.polygon.holes) ring(hole);
}

void append_box(std::string& key, const StructureBox& b) {
  key += 'b';
  append_bits(key, {static_cast<int>(b.zone), b.id});
  append_bits(key, {b.box.min_x, b.box.min_y, b.box.max_x, b.box.max_y, b.bottom, b.top});
}

// All that a tile's files are made of but what every tile of the build shares (the city's
// seed and model library, the memo's context): the city's box (the frame), each structure
// as the full level merges it (its mesh's key, stable id and zone, in id order), the placed
// models and clutter in their order, and the boxes of the two far levels.
std::string tile_key(const geom::Box& city, const Tile& t, const std::vector<StructureBox>& blocks,
                     const std::vector<std::string>& mesh_keys) {
  std::string key;
  // Each mesh key's length first: a key's text then cannot run on into what follows.
  auto append_mesh = [&](int id) {
    append_bits(key, {static_cast<int>(mesh_keys[id].size())});
    key += mesh_keys[id];
  };
  append_bits(key, {city.min_x, city.min_y, city.max_x, city.max_y});
  for_each_by_id(
      t.buildings, t.models,
      [&](const Building& b) {
        key += 'B';
        append_bits(key, {b.stable_id, static_cast<int>(b.zone)});
        append_mesh(b.id);
      },
      [&](const ModelInstance& m) {
        key += 'M';
        append_mesh(m.id);
        append_instance(key, m);
      });
  key += 'C';
  for (const ModelInstance& c : t.clutter) append_instance(key, c);
  key += 'X';
  for (const StructureBox& b : t.boxes) append_box(key, b);
  key += 'K';
  for (const StructureBox& b : blocks) append_box(key, b);
  return key;
}

std::string file_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

json write_city_tiles(const City& city, const fs::path& dir) {
  const geom::Box box = city_box(city.ground);
  const double size = tile_size(box);
  const int columns = std::max(1, static_cast<int>(std::ceil(box.width() / size)));
  const int rows = std::max(1, static_cast<int>(std::ceil(box.height() / size)));
  auto tile_of = [&](double x, double y) {
    const int i = std::clamp(static_cast<int>(std::floor((x - box.min_x) / size)), 0, columns - 1);
    const int j = std::clamp(static_cast<int>(std::floor((y - box.min_y) / size)), 0, rows - 1);
    return std::make_pair(i, j);
  };
  const ModelLibrary* library = city.model_library();
  std::vector<std::string> mesh_keys;  // with the city's cache, whose tiles memo reads them
  const std::vector<Mesh> meshes = city_meshes(city, &mesh_keys);
  std::map<std::pair<int, int>, Tile> tiles;  // by column and row: the index's order
  // A lot's block (Lot::block: the city's lots are freed with the map) from the block piece
  // it lies in: a block's first piece has its index for id; a lot in no piece names it.
  std::unordered_map<int, int> block_of_piece;
  for (const BlockArea& b : city.ground.blocks) block_of_piece.emplace(b.id, b.block);
  auto block_of = [&](int piece) {
    const auto it = block_of_piece.find(piece);
    return it != block_of_piece.end() ? it->second : piece;
  };
  // `id` indexes the meshes; the box is coloured by the structure's stable id, as city.glb colours it.
  auto place = [&](int id, int stable_id, int lot, ZoneType zone, const geom::Polygon& outline, double floor,
                   double height) -> Tile& {
    Bounds3 b = mesh_bounds(meshes[id]);
    if (b.box.holds_nothing())  // no mesh to bound: its outline from its floor up to its height
      for (const geom::Vec2& p : outline.outer) b.add(p.x, p.y, floor), b.add(p.x, p.y, floor + height);
    Tile& t = tiles[tile_of((b.box.min_x + b.box.max_x) / 2, (b.box.min_y + b.box.max_y) / 2)];
    t.bounds.add(b);
    t.boxes.push_back({b.box, b.bottom, b.top, zone, stable_id});
    const int block = lot >= 0 ? block_of(city.ground.lots[lot].block) : -1;
    BlockPart& part = t.blocks[{block, zone}];
    part.bounds.add(b);
    const double area = b.box.width() * b.box.height();
    part.area += area, part.area_times_top += area * b.top;
    return t;
  };
  for (const Building& b : city.buildings)
    place(b.id, b.stable_id, b.lot, b.zone, b.polygon, b.floor, b.height).buildings.push_back(b);
  for (const ModelInstance& m : city.models)
    place(m.id, m.stable_id, m.lot, m.zone, m.polygon, m.floor, m.height).models.push_back(m);
  for (const Clutter& c : city.clutter.items) {
    Tile& t = tiles[tile_of(c.spot.x, c.spot.y)];
    t.clutter.push_back(c.instance);
    t.bounds.add(c.spot.x, c.spot.y, c.instance.floor);
    t.bounds.add(c.spot.x, c.spot.y, c.instance.floor + c.instance.height);
  }

  fs::create_directories(dir);
  std::vector<std::pair<const std::pair<int, int>, Tile>*> in_order;  // the index's
  for (auto& tile : tiles) in_order.push_back(&tile);
  std::vector<json> entries(in_order.size());
  GltfCounts ground;
  // The ground, each tile's three levels and the facades are files of their own, written at
  // once; the index lists the tiles in their order.
  for_each_cancellable(in_order.size() + 2, [&](std::size_t i) {
    if (i == in_order.size()) {
      ground = write_gltf({.ground = city.ground,
                           .ground_layers = city_ground_layers(city),
                           .buildings = {},
                           .models = {},
                           .meshes = {},
                           .clutter = {},
                           .crs = city.settings.crs,
                           .seed = city.settings.seed},
                          dir / "ground.glb");
      return;
    }
    if (i == in_order.size() + 1) return write_facades(city, dir / "facades.json");
    const auto& [at, t] = *in_order[i];
    const std::string name = std::to_string(at.first) + "_" + std::to_string(at.second);
    fs::create_directories(dir / name);
    // Blocks: the box of a block's structures, as high as their tops weighed by footprint.
    std::vector<StructureBox> blocks;
    for (const auto& [key, part] : t.blocks) {
      const Bounds3& b = part.bounds;
      blocks.push_back({b.box, b.bottom, part.area > 0 ? part.area_times_top / part.area : b.top, key.second, -1});
    }
    // A tile made of what a tile of the last build was made of is that tile's bytes again.
    auto write_levels = [&] {
      const std::array<fs::path, 3> files{dir / name / "0.glb", dir / name / "1.glb", dir / name / "2.glb"};
      TileFiles written{.bytes = {},
                        .triangles = {write_gltf_structures(box, t.buildings, t.models, meshes, city.settings.seed,
                                                            library, files[0], t.clutter)
                                          .triangles,
                                      write_gltf_boxes(box, t.boxes, city.settings.seed, files[1]).triangles,
                                      write_gltf_boxes(box, blocks, city.settings.seed, files[2]).triangles}};
      if (city.regions)
        for (const fs::path& file : files) written.bytes.push_back(file_bytes(file));
      return written;
    };
    TileFiles levels_written;
    if (!city.regions) {
      levels_written = write_levels();
    } else {
      bool computed = false;
      levels_written = city.regions->tiles.get(tile_key(box, t, blocks, mesh_keys), [&] {
        computed = true;
        return write_levels();
      });
      for (int level = 0; level < 3 && !computed; ++level) {
        const fs::path file = dir / name / (std::to_string(level) + ".glb");
        std::ofstream out(file, std::ios::binary);
        out.write(levels_written.bytes[level].data(), static_cast<std::streamsize>(levels_written.bytes[level].size()));
        if (!out) throw UserError(file.string() + ": write failed (disk full?)");
      }
    }
    json levels = json::array();
    for (int level = 0; level < 3; ++level)
      levels.push_back("/api/tiles/" + name + "/" + std::to_string(level) + ".glb");
    entries[i] = {{"name", name},
                  {"box",
                   {t.bounds.box.min_x, t.bounds.box.min_y, t.bounds.bottom, t.bounds.box.max_x, t.bounds.box.max_y,
                    t.bounds.top}},
                  {"buildings", t.buildings.size()},
                  {"models", t.models.size()},
                  {"clutter", t.clutter.size()},
                  {"levels", levels},
                  {"triangles", levels_written.triangles}};
  });
  json index{{"tile_size", size},
             {"bounds", {box.min_x, box.min_y, box.max_x, box.max_y}},
             {"ground", "/api/tiles/ground.glb"},
             {"ground_triangles", ground.triangles},
             {"levels",
              {{{"name", "full"}, {"until", kFullUntil * size}},
               {{"name", "boxes"}, {"until", kBoxesUntil * size}},
               {{"name", "blocks"}, {"until", nullptr}}}},
             {"tiles", std::move(entries)},
             {"facades", "/api/tiles/facades.json"}};
  std::ofstream out(dir / "index.json", std::ios::binary);
  out << index.dump(1) << "\n";
  if (!out) throw UserError((dir / "index.json").string() + ": write failed (disk full?)");
  return index;
}

}  // namespace exacity::serve
