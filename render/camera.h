// Cameras (docs/design.md, Algorithms): a spherical orbit bound to the upper hemisphere or a look-at
// camera, perspective or orthographic; the overview camera that sees the whole city; and
// the ground region a camera sees, for the minimap.
#pragma once

#include <string>
#include <vector>

#include "geom/plain.h"
#include "render/vec.h"

namespace render {

// Depth of field (render/README.md, Depth of field): a thin lens `aperture` metres across
// (0: a pinhole, everything sharp) focused on a plane `focus_distance` metres ahead (0: the
// distance to the camera's target), turned by `focus_tilt` degrees about the image's
// horizontal axis (tilt-shift: 90 less the view's angle below the horizon lays it on flat
// ground). Perspective cameras only.
struct DepthOfField {
  float aperture = 0, focus_distance = 0, focus_tilt = 0;
};

// The least distance from a camera's eye to its target: closer, the view's direction is
// rounding noise (a NaN ray, which Embree aborts on).
constexpr float kNearestTarget = 0.01f;  // m
// The farthest a camera's coordinates may be from the origin: Embree refuses rays from past
// about 1.8e18 (it aborts); a kilometre's million is room enough for any city.
constexpr float kLargestCameraNumber = 1e9f;  // m

struct Camera {
  V3 from, to;
  float fov_y = 50;  // degrees, vertical
  bool orthographic = false;
  float ortho_height = 100;  // m the image spans vertically, orthographic only
  DepthOfField depth_of_field = {};

  // From `target`: azimuth counter-clockwise from east, elevation above the horizon
  // (kept within 1..90 degrees, the upper hemisphere), distance in metres.
  static Camera orbit(V3 target, float azimuth_deg, float elevation_deg, float distance, float fov_y = 50);
  static Camera look(V3 from, V3 to, float fov_y = 50);
  // "orbit:target=X,Y,Z,azimuth=DEG,elevation=DEG,distance=M" or "look:from=X,Y,Z,to=X,Y,Z";
  // throws std::invalid_argument with what is wrong.
  static Camera parse(const std::string& spec, float fov_y);

  V3 forward() const { return normalize(to - from); }
  V3 right() const;
  V3 up() const { return cross(right(), forward()); }
  // The ray through the image point (px, py), pixels from the top-left corner.
  void ray(float px, float py, int width, int height, V3& origin, V3& direction) const;
};

// A camera spec's text, "kind:key=a,b,c,key=d" (a number after a comma continues the
// previous key's list), split into its kind and keys; throws std::invalid_argument.
struct CameraSpecText {
  std::string kind;
  std::vector<std::pair<std::string, std::vector<float>>> keys;
  static CameraSpecText split(const std::string& spec);
  bool has(const std::string& key) const;
  // The key's numbers, which must be n; throws when it is missing or has another count.
  std::vector<float> get(const std::string& key, std::size_t n) const;
  // The key's one number, or `otherwise` when it is not given.
  float get_or(const std::string& key, float otherwise) const;
  // Throws for a key not among `known`.
  void only(const std::vector<std::string>& known) const;
};

// A camera's rays for one image size, its frame worked out once.
class Lens {
 public:
  Lens(const Camera& camera, int width, int height);
  // Through the lens's centre (a pinhole's ray).
  void ray(float px, float py, V3& origin, V3& direction) const;
  // Through the lens point that (u, v) in [0, 1)^2 maps to (concentric disk), towards where
  // the centre's ray meets the plane in focus; the centre's ray when there is no aperture.
  void ray(float px, float py, float u, float v, V3& origin, V3& direction) const;
  bool thin_lens() const { return radius_ > 0; }

 private:
  V3 from_, forward_, right_, up_;
  float width_, height_, half_x_, half_y_;
  bool orthographic_;
  float radius_ = 0;          // m, half the aperture
  V3 focus_normal_{0, 0, 1};  // the plane in focus: dot(focus_normal_, p - from_) = focus_offset_
  float focus_offset_ = 0;
};

// The overview, an air photo: straight down over the city's centre, at the height where the whole map
// is seen: height = map height / (2 tan(fov_y / 2)), the map height being the box's extent
// north-south or its east-west extent over the aspect ratio, whichever is more; counted
// from `top`, the highest point of the city. Orthographic: the map height is spanned.
Camera overview_camera(const geom::Box& city, float top, float fov_y, float aspect, bool orthographic);
float overview_height(const geom::Box& city, float fov_y, float aspect);

// Where the image's corner rays meet the ground plane z = ground, as a quadrilateral
// (bottom-left, bottom-right, top-right, top-left). Where an upper ray points at or above
// the horizon, the lower ray on its side is followed on along the ground to the edge of
// `bounds` instead (a view near the horizon).
std::vector<geom::Vec2> ground_footprint(const Camera& camera, int width, int height, float ground,
                                         const geom::Box& bounds);

}  // namespace render
