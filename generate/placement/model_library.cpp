#include "generate/placement/model_library.h"

#include <cmath>

#include <nlohmann/json.hpp>

#include "generate/errors.h"
#include "generate/input_file.h"
#include "generate/city/format_number.h"
#include "geom/grid.h"
#include "geom/outline.h"
#include "geom/polygon_check.h"

namespace exacity {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr std::string_view kKindNames[] = {"building", "street", "tree", "lamp", "sign", "traffic_light", "bench", "hydrant"};

}  // namespace

const char* name(ModelKind k) { return kKindNames[static_cast<int>(k)].data(); }

bool is_clutter(ModelKind k) { return k != ModelKind::Building && k != ModelKind::Street; }

std::vector<int> ModelLibrary::choices(ZoneType zone, ModelKind kind) const {
  std::vector<int> out;
  for (std::size_t i = 0; i < models.size(); ++i)
    if (models[i].kind == kind && std::find(models[i].zones.begin(), models[i].zones.end(), zone) != models[i].zones.end())
      out.push_back(static_cast<int>(i));
  return out;
}

std::vector<int> ModelLibrary::lot_choices(ZoneType zone) const {
  std::vector<int> out;
  for (int i : choices(zone, ModelKind::Building))
    if (models[i].has_lot()) out.push_back(i);
  return out;
}

Choices choices_at(const std::vector<int>& models, const ModelLibrary& lib, const Channels* channels, geom::Vec2 p) {
  Choices out{models, {}};
  for (int m : models)
    out.weights.push_back(lib.models[m].weight * (channels ? channels->affinity(lib.models[m].channels, p) : 1.0));
  return out;
}

std::optional<int> pick(const Choices& choices, Random& rng) {
  double total = 0;
  for (double w : choices.weights) total += w;
  double r = rng.uniform() * total;
  if (!(total > 0)) return std::nullopt;
  std::optional<int> last;
  for (std::size_t i = 0; i < choices.models.size(); ++i) {
    if (choices.weights[i] <= 0) continue;
    last = choices.models[i];
    if ((r -= choices.weights[i]) < 0) return last;
  }
  return last;
}

void ModelLibrary::check_channels(const std::vector<ChannelSpec>& channels) const {
  for (std::size_t i = 0; i < models.size(); ++i)
    for (const auto& named : models[i].channels) {
      // Not a structured binding: clang 14 (the fuzz preset's) cannot capture one in a lambda.
      const std::string& channel = named.first;
      if (std::none_of(channels.begin(), channels.end(), [&](const ChannelSpec& c) { return c.name == channel; }))
        throw UserError(file.string() + " models[" + std::to_string(i) + "]: channels names \"" + channel +
                        "\", which the sketch does not define; define it in the sketch's \"exacity\".channels, or remove it");
    }
}

namespace {

// The file's axis as a vector in the file's own axes.
Vec3 axis(const std::string& name) {
  Vec3 v{0, 0, 0};
  v[name[1] - 'x'] = name[0] == '-' ? -1 : 1;
  return v;
}

}  // namespace

Model normalise_model(TriangleMesh mesh, const std::string& up, const std::string& front, double unit,
                      const std::string& where) {
  // Y-up files turn to z up by (x, y, z) -> (x, -z, y), which keeps handedness.
  auto to_z_up = [&](Vec3 v) { return up == "y" ? Vec3{v[0], -v[2], v[1]} : v; };
  Vec3 f = to_z_up(axis(front));
  if (f[2] != 0) throw UserError(where + ": \"front\" " + front + " points up or down; give a horizontal axis");
  // Turn the front to -y: (fx, fy) -> (0, -1).
  const double c = -f[1], s = -f[0];  // cos and sin of the turn
  Model m;
  // Turned by a quarter turn at most: each coordinate is one of the file's, times the unit.
  for (Vec3& v : mesh.vertices) {
    Vec3 p = to_z_up(v);
    v = {(c * p[0] - s * p[1]) * unit, (s * p[0] + c * p[1]) * unit, p[2] * unit};
  }
  geom::Box box = geom::Box::none();
  double bottom = INFINITY, top = -INFINITY;
  bool finite = true;
  for (const Vec3& v : mesh.vertices) {
    finite = finite && std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
    box.add(geom::Vec2{v[0], v[1]}), bottom = std::min(bottom, v[2]), top = std::max(top, v[2]);
  }
  // The exact outline below works in the model's own coordinates: a wrong unit (or a stray
  // vertex far out) would overflow it, so the size is checked first.
  if (!finite || !(box.width() <= kMaxModelSize && box.height() <= kMaxModelSize && top - bottom <= kMaxModelSize))
    throw UserError(where + ": the model is " + format_number(box.width()) + " x " + format_number(box.height()) + " x " +
                    format_number(top - bottom) + " m at \"unit\" " + format_number(unit) + ", more than the " +
                    std::to_string(static_cast<long>(kMaxModelSize)) + " m a side a model may be; check \"unit\" (\"mm\" for millimetres) " +
                    "and vertices far from the rest");
  const double cx = (box.min_x + box.max_x) / 2, cy = (box.min_y + box.max_y) / 2;
  for (Vec3& v : mesh.vertices) v = {v[0] - cx, v[1] - cy, v[2] - bottom};
  m.width = box.width(), m.depth = box.height(), m.height = top - bottom;
  if (!(m.height > 0))
    throw UserError(where + ": the model is flat (every vertex at one height); a model needs height: check its \"up\" axis");

  // The exact union of a heavy mesh's triangles costs seconds per 10,000 (real building
  // models have a few thousand); past kExactOutlineTriangles the hull of its vertices
  // stands in. Every placement tests the outline exactly, so it keeps at most
  // kOutlineCorners corners: a longer one becomes the polygon of kOutlineCorners sides
  // around it.
  std::vector<geom::Vec2> all;
  if (mesh.triangles.size() <= kExactOutlineTriangles) {
    std::vector<std::array<geom::Vec2, 3>> shadow;
    for (const auto& t : mesh.triangles) {
      std::array<geom::Vec2, 3> tri;
      for (int k = 0; k < 3; ++k) tri[k] = {mesh.vertices[t[k]][0], mesh.vertices[t[k]][1]};
      shadow.push_back(tri);
    }
    std::vector<geom::Polygon> pieces = geom::union_of_triangles(shadow);
    if (pieces.size() == 1 && pieces[0].holes.empty()) m.outline = pieces[0].outer;
    for (const auto& p : pieces) all.insert(all.end(), p.outer.begin(), p.outer.end());
  } else {
    for (const Vec3& v : mesh.vertices) all.push_back(geom::snap(geom::Vec2{v[0], v[1]}));
  }
  if (m.outline.empty()) m.outline = geom::convex_hull(all);
  if (m.outline.size() > kOutlineCorners) m.outline = geom::polygon_around(m.outline, kOutlineCorners);
  if (m.outline.size() < 3)
    throw UserError(where + ": the model has no area seen from above; check its \"up\" axis and \"unit\"");
  m.mesh = std::move(mesh);
  return m;
}

void cut_slabs(ModelLibrary& library) {
  for (Model& m : library.models)
    if (m.kind == ModelKind::Building && m.slabs.empty()) m.slabs = model_slabs(m.mesh, m.outline, m.height);
}

namespace {

[[noreturn]] void fail(const std::string& where, const std::string& what) { throw UserError(where + ": " + what); }

json read_manifest(const fs::path& manifest) {
  json doc = json::parse(read_input(manifest, kMaxSettingsFileBytes, "the model library",
                                    "check the sketch's \"models\" path, or generate's --models"),
                         nullptr, false);
  if (doc.is_discarded() || !doc.is_object() || !doc.contains("models") || !doc["models"].is_array())
    throw UserError(manifest.string() + ": not a model library; it must be JSON like {\"models\": [{\"file\": ..., \"zones\": [...]}]}");
  return doc;
}

void check_keys(const json& e, const std::string& where) {
  if (!e.is_object()) fail(where, "expected an object with \"file\" and \"zones\"");
  static const std::vector<std::string> known{"name",  "file",  "zones",   "kind",   "up",   "unit",     "front",
                                              "weight", "scale", "spacing", "offset", "side", "channels", "lot"};
  for (const auto& [key, value] : e.items())
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      fail(where, "unknown key \"" + key + "\"; known: " + list);
    }
}

// Metres per file unit.
double read_unit(const json& e, const std::string& where) {
  double unit = 1;
  if (e.contains("unit")) {
    const json& u = e["unit"];
    if (u == "m") unit = 1;
    else if (u == "cm") unit = 0.01;
    else if (u == "mm") unit = 0.001;
    else if (u.is_number() && u.get<double>() > 0 && std::isfinite(u.get<double>())) unit = u.get<double>();
    else fail(where, "\"unit\" must be \"m\", \"cm\", \"mm\" or metres per file unit (a positive number)");
  }
  return unit;
}

ModelKind read_kind(const json& e, const std::string& where) {
  const json& kind = e.contains("kind") ? e["kind"] : json("building");
  for (ModelKind k : kModelKinds)
    if (kind == name(k)) return k;
  std::string list;
  for (ModelKind k : kModelKinds) list += std::string(list.empty() ? "" : ", ") + "\"" + name(k) + "\"";
  fail(where, "\"kind\" is " + kind.dump() + "; expected one of " + list);
}

// Buildings and lot furniture stand in the zones listed; clutter and trees dress the streets
// of the zones listed, parks included, every zone but water when a clutter entry lists none.
void read_zones(const json& e, const std::string& where, Model& m) {
  const bool street_side = is_clutter(m.kind);
  if (!e.contains("zones") && street_side && m.kind != ModelKind::Tree) {
    m.zones = {ZoneType::Residential, ZoneType::Commercial, ZoneType::Industrial, ZoneType::Park};
    return;
  }
  if (!e.contains("zones") || !e["zones"].is_array() || e["zones"].empty()) fail(where, "\"zones\" must list zone types");
  for (const json& z : e["zones"]) {
    auto t = z.is_string() ? parse_zone_type(z.get<std::string>()) : std::nullopt;
    if (!t || *t == ZoneType::Water || (*t == ZoneType::Park && !street_side))
      fail(where, "\"zones\" lists " + z.dump() + "; " + name(m.kind) + " models stand in residential, commercial" +
                      (street_side ? ", industrial or park zones" : " or industrial zones"));
    m.zones.push_back(*t);
  }
}

// The spacing along a street a clutter model of the kind keeps unless its entry gives one.
double default_spacing(ModelKind k) {
  switch (k) {
    case ModelKind::Tree: return 12;
    case ModelKind::Bench: return 60;
    case ModelKind::Hydrant: return 100;
    default: return 30;
  }
}

// Street clutter's rules and channel values, and the lot library's lot.
void read_street_rules(const json& e, const std::string& where, Model& m) {
  m.offset = e.value("offset", m.kind == ModelKind::Tree || m.kind == ModelKind::Bench ? 1.5 : 0.5);
  if (!(m.offset >= 0) || m.offset > 50) fail(where, "\"offset\" must be metres from the kerb, 0 to 50");
  const json& side = e.contains("side") ? e["side"] : json("both");
  if (side != "both" && side != "alternate") fail(where, "\"side\" must be \"both\" or \"alternate\"");
  m.side = side == "both" ? StreetSide::Both : StreetSide::Alternate;
  if (e.contains("channels")) {
    if (!e["channels"].is_object()) fail(where, "\"channels\" must map channel names to values, like {\"downtown\": 0.8}");
    for (const auto& [channel, value] : e["channels"].items()) {
      if (!value.is_number() || !(value.get<double>() >= 0) || value.get<double>() > 1)
        fail(where, "channels." + channel + " is " + value.dump() + "; a channel value is a number from 0 to 1");
      m.channels.push_back({channel, value.get<double>()});
    }
  }
  if (e.contains("lot")) {
    const json& lot = e["lot"];
    if (m.kind != ModelKind::Building) fail(where, "\"lot\" is for building models; a " + std::string(name(m.kind)) + " has none");
    if (!lot.is_array() || lot.size() != 2 || !lot[0].is_number() || !lot[1].is_number() || !(lot[0].get<double>() >= 1) ||
        !(lot[1].get<double>() >= 1) || lot[0].get<double>() > 1000 || lot[1].get<double>() > 1000)
      fail(where, "\"lot\" must be [width along the street, depth] in metres, each 1 to 1000");
    m.lot_width = lot[0], m.lot_depth = lot[1];
    // Half a metre each side keeps the model strictly inside its lot (Occupancy).
    if (m.width * m.min_scale + 2 * kLotMargin > m.lot_width || m.depth * m.min_scale + 2 * kLotMargin > m.lot_depth)
      fail(where, "the model (" + format_number(m.width * m.min_scale) + " x " + format_number(m.depth * m.min_scale) +
                      " m at its smallest scale) does not fit its lot (" + format_number(m.lot_width) + " x " +
                      format_number(m.lot_depth) + " m) with half a metre each side; give a larger \"lot\" or a smaller \"scale\"");
  }
}

// Weight, scale range and spacing, and a size check that catches a wrong unit.
void read_placement(const json& e, const std::string& where, Model& m) {
  m.weight = e.value("weight", 1.0);
  if (!(m.weight > 0) || !std::isfinite(m.weight)) fail(where, "\"weight\" must be a positive number");
  if (e.contains("scale")) {
    const json& s = e["scale"];
    if (!s.is_array() || s.size() != 2 || !s[0].is_number() || !s[1].is_number() || !(s[0].get<double>() > 0) ||
        s[1].get<double>() < s[0].get<double>() || s[1].get<double>() > 100)
      fail(where, "\"scale\" must be [min, max] with 0 < min <= max <= 100");
    m.min_scale = s[0], m.max_scale = s[1];
  }
  m.spacing = e.value("spacing", default_spacing(m.kind));
  // Stations along every street, and a park's tree spots, number length / spacing and
  // area / spacing²: the smallest spacing bounds that work.
  if (!(m.spacing >= kMinSpacing) || !std::isfinite(m.spacing))
    fail(where, "\"spacing\" is " + (e.contains("spacing") ? e["spacing"].dump() : format_number(m.spacing)) +
                    "; it must be metres between models along a street, at least " + format_number(kMinSpacing));
  if (m.width * m.max_scale > 1000 || m.depth * m.max_scale > 1000 || m.height * m.max_scale > 2000)
    fail(where, "the model is " + format_number(m.width * m.max_scale) + " x " + format_number(m.depth * m.max_scale) +
                    " x " + format_number(m.height * m.max_scale) +
                    " m at its largest \"scale\", more than a placed model's 1000 x 1000 x 2000 m; check \"unit\" "
                    "(\"mm\" for millimetres) and \"scale\"");
}

// One entry of the manifest. The checks run in the order their errors are reported: the
// axes and unit before the OBJ file is read, the kind, zones and placement after.
Model read_model(const json& e, const fs::path& manifest, const std::string& where, TextureImages& textures) {
  check_keys(e, where);
  if (!e.contains("file") || !e["file"].is_string()) fail(where, "\"file\" must name an OBJ file");
  const fs::path file = manifest.parent_path() / e["file"].get<std::string>();
  // The manifest may name an OBJ anywhere, as the command line may name a sketch; what the
  // OBJ names in turn (MTL, textures: a downloaded model's words) stays below the manifest's
  // folder, or below the OBJ's own where the manifest named one outside it.
  const fs::path library_folder = fs::absolute(manifest).parent_path();
  const fs::path folder = lies_within(file, library_folder) ? library_folder : fs::absolute(file).lexically_normal().parent_path();
  const std::string up = e.value("up", "y");
  if (up != "y" && up != "z") fail(where, "\"up\" must be \"y\" or \"z\"");
  const std::string front = e.value("front", up == "y" ? "+z" : "-y");
  if (front.size() != 2 || (front[0] != '+' && front[0] != '-') || front[1] < 'x' || front[1] > 'z')
    fail(where, "\"front\" must be an axis such as \"+z\" or \"-y\"");
  const double unit = read_unit(e, where);
  Model m = normalise_model(read_obj(file, &textures, folder), up, front, unit, where);
  m.name = e.value("name", file.stem().string());
  m.kind = read_kind(e, where);
  read_zones(e, where, m);
  read_placement(e, where, m);
  read_street_rules(e, where, m);
  return m;
}

}  // namespace

ModelLibrary load_model_library(const fs::path& manifest) {
  json doc = read_manifest(manifest);
  ModelLibrary lib;
  lib.file = manifest;
  TextureImages textures;  // an image several models name is read once, and shared
  for (std::size_t i = 0; i < doc["models"].size(); ++i) {
    const std::string where = manifest.string() + " models[" + std::to_string(i) + "]";
    try {
      lib.models.push_back(read_model(doc["models"][i], manifest, where, textures));
    } catch (const json::exception& x) {
      fail(where, std::string("a value has the wrong type (") + x.what() + "); see docs/models.md");
    }
  }
  if (lib.models.empty()) throw UserError(manifest.string() + ": the library lists no models");
  return lib;
}

}  // namespace exacity
