#include "generate/regenerate.h"

#include <filesystem>
#include <system_error>

#include <tbb/parallel_for.h>

#include "generate/cancel.h"

namespace exacity {
namespace fs = std::filesystem;

namespace {

void append_file(std::string& key, const fs::path& file) {
  std::error_code error;
  const auto size = fs::file_size(file, error);
  const auto time = fs::last_write_time(file, error);
  key += "file " + file.string() + " " + std::to_string(error ? 0 : size) + " " +
         std::to_string(error ? 0 : time.time_since_epoch().count()) + " ";
}

}  // namespace

std::string shared_input(const Sketch& sketch) {
  std::string key = sketch.settings_text;
  for (const RoadFeature& road : sketch.roads) {
    key += " road " + std::to_string(static_cast<int>(road.road_class)) + " ";
    append_key(key, road.width);
    for (const geom::Polyline& line : road.lines) {
      key += "line ";
      for (geom::Vec2 p : line) append_key(key, p.x), append_key(key, p.y);
    }
  }
  if (sketch.terrain) append_file(key, sketch.terrain->heightmap);
  for (const ChannelSpec& channel : sketch.channels) append_file(key, channel.image);
  if (!sketch.models.empty()) append_file(key, sketch.models);
  return key;
}

void RegionCache::next_build(const Sketch& sketch) {
  const std::string shared =
      sketch.settings_text.empty() ? "unknown settings " + std::to_string(++unknown_) : shared_input(sketch);
  road_plans.next_build(shared);
  lot_plans.next_build(shared);
  block_lots.next_build(shared);
  placements.next_build(shared);
  meshes.next_build(shared);
  ground_pieces.next_build(shared);
  tiles.next_build(shared);
}

std::vector<GroundLayer> city_ground_layers(const City& city) {
  return ground_layers(city.ground, city.heightmap(), city.regions ? &city.regions->ground_pieces : nullptr);
}

std::vector<Mesh> city_meshes(const City& city, std::vector<std::string>* keys) {
  const ModelLibrary* library = city.model_library();
  if (!city.regions) return structure_meshes(city.buildings, city.models, library);
  Memo<Mesh>& memo = city.regions->meshes;
  std::vector<Mesh> meshes(city.buildings.size() + city.models.size());
  if (keys) keys->assign(meshes.size(), {});
  const CancelCheck cancel;
  // Each key is what building_mesh or model_mesh reads of the structure (the library is the memo's context).
  tbb::parallel_for(std::size_t(0), city.buildings.size(), [&](std::size_t i) {
    cancel.check();
    const Building& b = city.buildings[i];
    std::string key = "building ";
    for (double v : {b.base, b.floor, b.eaves}) append_key(key, v);
    append_key(key, b.polygon);
    auto append_faces = [&](const std::vector<geom::Face3>& faces) {
      for (const geom::Face3& f : faces) {
        key += "face ";
        for (const geom::Vec3& p : f) append_key(key, p[0]), append_key(key, p[1]), append_key(key, p[2]);
      }
    };
    append_faces(b.roof_faces);
    for (const BuildingPart& part : b.parts) {
      key += "part ";
      for (double v : {part.bottom, part.eaves}) append_key(key, v);
      append_key(key, part.polygon);
      append_faces(part.roof_faces);
    }
    meshes[b.id] = memo.get(key, [&] { return building_mesh(b); });
    if (keys) (*keys)[b.id] = std::move(key);
  });
  const ModelMeshes model_meshes(library);
  tbb::parallel_for(std::size_t(0), city.models.size(), [&](std::size_t i) {
    cancel.check();
    const ModelInstance& m = city.models[i];
    std::string key = "model " + std::to_string(library ? m.placed.model : -1) + " ";
    for (double v : {m.base, m.floor, m.placed.position.x, m.placed.position.y, m.placed.angle, m.placed.scale})
      append_key(key, v);
    if (m.floor > m.base) append_key(key, m.polygon);
    meshes[m.id] = memo.get(key, [&] { return model_meshes(m); });
    if (keys) (*keys)[m.id] = std::move(key);
  });
  return meshes;
}

nlohmann::ordered_json reuse_report(const RegionCache& cache) {
  auto counts = [](const auto& memo) {
    return nlohmann::ordered_json{{"reused", memo.hits()}, {"of", memo.hits() + memo.misses()}};
  };
  return {{"region_plans", counts(cache.road_plans)},
          {"block_plans", counts(cache.lot_plans)},
          {"block_lots", counts(cache.block_lots)},
          {"lot_placements", counts(cache.placements)},
          {"structure_meshes", counts(cache.meshes)},
          {"ground_pieces", counts(cache.ground_pieces)}};
}

City regenerate(const City& previous, const Sketch& edited, StageClock& clock) {
  return build_city(edited, clock, previous.regions ? previous.regions : std::make_shared<RegionCache>());
}

}  // namespace exacity
