// A library of placed models (docs/models.md): a JSON manifest naming OBJ files, the
// zone types each suits, its axes and units, and how often to pick it. Each model is
// loaded once, brought to Exacity's frame, and placed many times by transforms.
//
//   {"models": [{"file": "house.obj", "zones": ["residential"], "kind": "building",
//                "up": "y", "unit": "m", "front": "+z", "weight": 2, "scale": [0.9, 1.1],
//                "channels": {"downtown": 0.2}, "lot": [14, 30]},
//               {"file": "lamp.obj", "kind": "lamp", "spacing": 25, "offset": 0.5, "side": "both"}]}
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "generate/placement/obj_file.h"
#include "generate/placement/slabs.h"
#include "generate/city/channels.h"
#include "generate/city/random.h"
#include "generate/city/features.h"
#include "generate/city/zone_type.h"
#include "geom/plain.h"

namespace exacity {

// Buildings fill lots; "street" furniture stands along a lot's frontage inside the setback;
// trees fill space left in lots and line residential streets. The rest are street
// clutter, which dresses the streets' sidewalks: lamps, stop signs, traffic lights,
// benches and hydrants.
enum class ModelKind { Building, Street, Tree, Lamp, Sign, TrafficLight, Bench, Hydrant };
inline constexpr ModelKind kModelKinds[] = {ModelKind::Building,     ModelKind::Street, ModelKind::Tree,
                                            ModelKind::Lamp,         ModelKind::Sign,   ModelKind::TrafficLight,
                                            ModelKind::Bench,        ModelKind::Hydrant};
const char* name(ModelKind k);
// Whether models of the kind dress streets (street clutter): trees and the clutter kinds.
bool is_clutter(ModelKind k);

// Whether a lamp model's material is its light: glass, a bulb, a lamp or a light by name.
inline bool is_lamp_light_material(const std::string& name) {
  for (const char* word : {"glass", "bulb", "lamp", "light"})
    if (name.find(word) != std::string::npos) return true;
  return false;
}

// Which sides of a street a clutter model stands on: both, or each in turn.
enum class StreetSide { Both, Alternate };

struct Model {
  std::string name;
  ModelKind kind = ModelKind::Building;
  std::vector<ZoneType> zones;
  double weight = 1;
  double min_scale = 0.9, max_scale = 1.1;  // random size variation
  double spacing = 30;                      // m between street furniture or clutter along a street
  double offset = 0.5;                      // m: clutter stands this far in from the kerb
  StreetSide side = StreetSide::Both;       // clutter: which sides of a street
  // Channel values ("channels": {"NAME": value in [0, 1]}), in the manifest's
  // order; the sketch's channels weigh the model by how near these are to theirs.
  std::vector<std::pair<std::string, double>> channels;
  // The lot library's lot ("lot": [width along the street, depth]), m: the lot the model needs in a
  // zone whose lots come from the library; 0 x 0 when the entry gives none.
  double lot_width = 0, lot_depth = 0;
  bool has_lot() const { return lot_width > 0; }
  // In metres, z up, its front facing -y, standing on z = 0, its outline's bounding box
  // centred on the origin.
  TriangleMesh mesh;
  // The footprint: the mesh's outline on the ground, counter-clockwise, on the grid. A
  // model whose outline falls apart in pieces, or has courtyards, or whose mesh has more
  // than kExactOutlineTriangles triangles, gets the convex hull; an outline of more than
  // kOutlineCorners corners, a polygon of that many sides around it.
  geom::Ring outline;
  double width = 0, depth = 0, height = 0;  // along x, y and z
  // Nesting's 3D occupancy grid, exactly (slabs.h): made by cut_slabs only when a zone type
  // asks for nesting; empty otherwise.
  std::vector<Slab> slabs;
};

// The model's slabs, or one slab of its whole outline where it has none.
inline std::vector<Slab> slabs_of(const Model& m) {
  return m.slabs.empty() ? std::vector<Slab>{{0, m.height, {m.outline}}} : m.slabs;
}

inline constexpr std::size_t kExactOutlineTriangles = 20000;
inline constexpr double kLotMargin = 0.5;  // m: a library lot's room around its model at its smallest, each side
inline constexpr std::size_t kOutlineCorners = 64;
// m: a model's largest width, depth or height in the library's frame (its "unit" applied),
// checked before its outline is computed; placing checks the tighter 1000 x 1000 x 2000 m at
// its largest "scale".
inline constexpr double kMaxModelSize = 100000;
// m: the least "spacing" between street furniture or clutter along a street.
inline constexpr double kMinSpacing = 1;

struct ModelLibrary {
  std::filesystem::path file;
  std::vector<Model> models;
  // The models for a zone type and kind, as indices.
  std::vector<int> choices(ZoneType zone, ModelKind kind) const;
  // The building models for a zone type that carry a "lot", as indices.
  std::vector<int> lot_choices(ZoneType zone) const;
  // Throws UserError naming the manifest and the entry when a model names a channel the
  // sketch does not define.
  void check_channels(const std::vector<ChannelSpec>& channels) const;
};

// Cuts every building model into slabs (model_slabs), for grid filling with nesting.
void cut_slabs(ModelLibrary& library);

// The models a placer or lot layout draws from, each with its weight where it draws: the
// library's weight times its channel affinity there (docs/design.md, Placement).
struct Choices {
  std::vector<int> models;
  std::vector<double> weights;
  bool empty() const { return models.empty(); }
};
// `channels` may be null (no channels: the library's weights).
Choices choices_at(const std::vector<int>& models, const ModelLibrary& library, const Channels* channels, geom::Vec2 p);

// One of the choices, drawn by weight; none when every weight is 0.
std::optional<int> pick(const Choices& choices, Random& rng);

// Throws UserError naming the manifest, the entry and the fix.
ModelLibrary load_model_library(const std::filesystem::path& manifest);

// A raw mesh brought to the library's frame: up axis "y" or "z"; front one of "+x",
// "-x", "+y", "-y", "+z", "-z" in the file's axes, horizontal; `unit` metres per file
// unit. Throws UserError (with `where`) when the front is not horizontal.
Model normalise_model(TriangleMesh mesh, const std::string& up, const std::string& front, double unit,
                      const std::string& where);

}  // namespace exacity
