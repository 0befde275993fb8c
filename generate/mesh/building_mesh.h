// Building meshes, double precision: a footprint extruded to its height, with walls, a flat
// roof and a ground face kept as separate surface classes. Built with OpenMesh (which joins
// faces at their shared edges and refuses a face that cannot join) and kept compact.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "generate/city/surface.h"
#include "generate/placement/buildings.h"

namespace exacity {

// A structure's mesh as the exports and the renderer read it: its points by index, and its
// faces in the order they were made, each its corners (indices into `points`, in the face's
// order) and its surface. Compact, since the 3D export holds every structure's at once
// (OpenMesh's halfedge structure of the 10 km city's meshes was about 900 MiB).
class Mesh {
 public:
  struct Face {
    Surface surface;
    std::span<const std::uint32_t> corners;
  };
  class FaceIterator {
   public:
    explicit FaceIterator(const std::uint32_t* at) : at_(at) {}
    Face operator*() const { return {static_cast<Surface>(at_[1]), {at_ + 2, at_[0]}}; }
    FaceIterator& operator++() { at_ += 2 + at_[0]; return *this; }
    bool operator==(const FaceIterator& other) const { return at_ == other.at_; }

   private:
    const std::uint32_t* at_;
  };
  struct Faces {
    const std::vector<std::uint32_t>& list;
    FaceIterator begin() const { return FaceIterator(list.data()); }
    FaceIterator end() const { return FaceIterator(list.data() + list.size()); }
  };

  std::vector<Vec3> points;
  Faces faces() const { return {faces_}; }
  std::size_t face_count() const;
  void add_face(Surface s, std::span<const std::uint32_t> corners);
  // Gives back the lists' spare capacity.
  void shrink();

 private:
  std::vector<std::uint32_t> faces_;  // each face: its corner count, its surface, its corners
};

// Meshes are z up, each face with its Surface.
// An extruded building's is closed and outward-facing, its walls reaching down to the
// terrain's lowest point under it.
// One with building:parts is their prisms, each closed on its own, and not its outline's.
Mesh building_mesh(const Building& b);
// A building:part's alone (CityJSON's BuildingPart).
Mesh building_part_mesh(const Building& b, const BuildingPart& part);
// A placed model's: its library mesh moved into place (faces classed by their slope) on a
// foundation where the ground slopes; without a library, only the foundation.
Mesh model_mesh(const ModelInstance& m, const ModelLibrary* library);
// model_mesh for many instances of a library's models: each model's triangles joined once.
class ModelMeshes {
 public:
  explicit ModelMeshes(const ModelLibrary* library);
  Mesh operator()(const ModelInstance& m) const;

 private:
  const ModelLibrary* library_;
  std::vector<Mesh> joined_;  // by model, in its own frame
};

// The mesh of every building and model, by id, in parallel; the exporters share them.
std::vector<Mesh> structure_meshes(const std::vector<Building>& buildings, const std::vector<ModelInstance>& models,
                                   const ModelLibrary* library);

// The mesh as triangles (faces triangulated in their plane): one per entry of `surface`.
struct MeshTriangles {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
  std::vector<Surface> surface;
};
MeshTriangles mesh_triangles(const Mesh& mesh);

}  // namespace exacity
