#include "generate/placement/builtin_models.h"

#include <algorithm>
#include <cmath>

namespace exacity {
namespace {

// Linear RGB, as a .mtl's Kd would give them.
constexpr Vec3 kBark{0.20, 0.13, 0.08};
constexpr Vec3 kLeaves{0.09, 0.22, 0.05};
constexpr Vec3 kNeedles{0.04, 0.13, 0.05};
constexpr Vec3 kMetal{0.12, 0.13, 0.14};
constexpr Vec3 kLampGlass{0.85, 0.82, 0.65};

// Builds a mesh part by part, each part in one material.
class MeshBuilder {
 public:
  int material(const std::string& name, Vec3 colour) {
    mesh_.materials.push_back({name, colour});
    return static_cast<int>(mesh_.materials.size()) - 1;
  }
  int vertex(Vec3 v) {
    mesh_.vertices.push_back(v);
    return static_cast<int>(mesh_.vertices.size()) - 1;
  }
  void triangle(int a, int b, int c, int m) {
    mesh_.triangles.push_back({a, b, c});
    mesh_.material.push_back(m);
  }
  // A ring of n points around (x, y) at height z, starting at `phase` radians.
  std::vector<int> ring(double x, double y, double z, double r, int n, double phase = 0) {
    std::vector<int> out;
    for (int i = 0; i < n; ++i) {
      const double a = phase + 2 * M_PI * i / n;
      out.push_back(vertex({x + r * std::cos(a), y + r * std::sin(a), z}));
    }
    return out;
  }
  // The band between two rings of equal size, the lower one first: counter-clockwise from
  // outside.
  void band(const std::vector<int>& lo, const std::vector<int>& hi, int m) {
    const std::size_t n = lo.size();
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t j = (i + 1) % n;
      triangle(lo[i], lo[j], hi[j], m), triangle(lo[i], hi[j], hi[i], m);
    }
  }
  // A fan closing a ring at a point: up (a roof or tip) or down (a floor).
  void cap(const std::vector<int>& ring, Vec3 at, bool up, int m) {
    const int c = vertex(at);
    const std::size_t n = ring.size();
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t j = (i + 1) % n;
      if (up)
        triangle(ring[i], ring[j], c, m);
      else
        triangle(ring[j], ring[i], c, m);
    }
  }
  // A closed n-sided prism.
  void prism(double x, double y, double r, double z0, double z1, int n, int m) {
    const std::vector<int> lo = ring(x, y, z0, r, n), hi = ring(x, y, z1, r, n);
    band(lo, hi, m);
    cap(lo, {x, y, z0}, false, m), cap(hi, {x, y, z1}, true, m);
  }
  // A closed box.
  void box(Vec3 lo, Vec3 hi, int m) {
    const std::vector<int> bottom{vertex({lo[0], lo[1], lo[2]}), vertex({hi[0], lo[1], lo[2]}),
                                  vertex({hi[0], hi[1], lo[2]}), vertex({lo[0], hi[1], lo[2]})};
    const std::vector<int> top{vertex({lo[0], lo[1], hi[2]}), vertex({hi[0], lo[1], hi[2]}),
                               vertex({hi[0], hi[1], hi[2]}), vertex({lo[0], hi[1], hi[2]})};
    band(bottom, top, m);
    triangle(bottom[0], bottom[2], bottom[1], m), triangle(bottom[0], bottom[3], bottom[2], m);
    triangle(top[0], top[1], top[2], m), triangle(top[0], top[2], top[3], m);
  }
  TriangleMesh take() { return std::move(mesh_); }

 private:
  TriangleMesh mesh_;
};

Model builtin(TriangleMesh mesh, const std::string& name, ModelKind kind, std::vector<ZoneType> zones, double weight,
              double min_scale, double max_scale) {
  Model m = normalise_model(std::move(mesh), "z", "-y", 1, "built-in model " + name);
  m.name = name;
  m.kind = kind;
  m.zones = std::move(zones);
  m.weight = weight;
  m.min_scale = min_scale, m.max_scale = max_scale;
  return m;
}

bool has_kind(const std::optional<ModelLibrary>& library, ModelKind kind) {
  return library &&
         std::any_of(library->models.begin(), library->models.end(), [&](const Model& m) { return m.kind == kind; });
}

}  // namespace

TriangleMesh broadleaf_mesh() {
  MeshBuilder b;
  const int bark = b.material("bark", kBark), leaves = b.material("leaves", kLeaves);
  b.prism(0, 0, 0.16, 0, 2.6, 6, bark);
  // The crown: a sphere of 2.2 m, a little flattened, of 7 rings of 10 points between its
  // poles, each ring turned half a step from the last so its faces are not all aligned.
  constexpr int kRings = 7, kSides = 10;
  constexpr double kCentre = 4.3, kRadius = 2.2, kFlat = 0.9;
  std::vector<std::vector<int>> rings;
  for (int i = 1; i <= kRings; ++i) {
    const double polar = M_PI * i / (kRings + 1);
    rings.push_back(b.ring(0, 0, kCentre - kRadius * kFlat * std::cos(polar), kRadius * std::sin(polar), kSides,
                           (i % 2) * M_PI / kSides));
  }
  for (int i = 0; i + 1 < kRings; ++i) b.band(rings[i], rings[i + 1], leaves);
  b.cap(rings.front(), {0, 0, kCentre - kRadius * kFlat}, false, leaves);
  b.cap(rings.back(), {0, 0, kCentre + kRadius * kFlat}, true, leaves);
  return b.take();
}

TriangleMesh conifer_mesh() {
  MeshBuilder b;
  const int bark = b.material("bark", kBark), needles = b.material("needles", kNeedles);
  b.prism(0, 0, 0.14, 0, 1.4, 6, bark);
  // Three cones, each overlapping the one below, narrowing upwards.
  const double tiers[3][3] = {{1.0, 1.9, 5.0}, {3.2, 1.45, 7.2}, {5.4, 1.0, 9.0}};  // base, radius, tip
  for (int t = 0; t < 3; ++t) {
    const std::vector<int> base = b.ring(0, 0, tiers[t][0], tiers[t][1], 9, t * 0.35);
    b.cap(base, {0, 0, tiers[t][0]}, false, needles);
    b.cap(base, {0, 0, tiers[t][2]}, true, needles);
  }
  return b.take();
}

TriangleMesh lamp_mesh() {
  MeshBuilder b;
  const int metal = b.material("metal", kMetal), glass = b.material("lamp_glass", kLampGlass);
  b.prism(0, 0, 0.14, 0, 0.5, 8, metal);  // the foot
  b.prism(0, 0, 0.07, 0.5, 6.0, 8, metal);
  b.box({-0.04, -1.3, 5.85}, {0.04, 0, 5.95}, metal);     // the arm, towards the road
  b.box({-0.16, -1.6, 5.72}, {0.16, -1.0, 5.88}, glass);  // the head
  return b.take();
}

void add_builtin_models(std::optional<ModelLibrary>& library, bool trees, bool lamps) {
  std::vector<Model> added;
  if (trees && !has_kind(library, ModelKind::Tree)) {
    added.push_back(builtin(broadleaf_mesh(), "exacity_broadleaf", ModelKind::Tree,
                            {ZoneType::Residential, ZoneType::Park}, 2, 0.75, 1.25));
    added.push_back(builtin(conifer_mesh(), "exacity_conifer", ModelKind::Tree, {ZoneType::Residential, ZoneType::Park},
                            1, 0.8, 1.2));
    for (Model& m : added) m.spacing = 12, m.offset = 0.5;  // the library's defaults for trees
  }
  if (lamps && !has_kind(library, ModelKind::Lamp)) {
    Model lamp = builtin(lamp_mesh(), "exacity_lamp", ModelKind::Lamp,
                         {ZoneType::Residential, ZoneType::Commercial, ZoneType::Industrial, ZoneType::Park}, 1, 1, 1);
    lamp.spacing = 30, lamp.offset = 0.5;
    added.push_back(std::move(lamp));
  }
  if (added.empty()) return;
  if (!library) library.emplace();
  for (Model& m : added) library->models.push_back(std::move(m));
}

}  // namespace exacity
