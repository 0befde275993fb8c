// A camera as the user names it (render/README.md, Cameras): orbit and look stand where
// their numbers say; a pedestrian and a flyer stand on the city's ground, so they are
// placed once the city is known: the pedestrian's eye at eye height over the terrain,
// on a road's centre line or at a point, the flyer at a height over it.
#pragma once

#include <string>

#include "generate/city.h"
#include "render/camera.h"

namespace render {

struct CameraSpec {
  enum class Kind { Fixed, Pedestrian, Flyer };
  Kind kind = Kind::Fixed;
  std::string text;  // as given, for messages
  Camera fixed;      // orbit, look
  // A pedestrian on centre line `road` (its id in vector/roads.geojson), `along` metres
  // from its first point, looking at the point `ahead` metres on along it (negative:
  // back), at eye height there too; road -1: standing at (x, y).
  int road = -1;
  double along = 0, ahead = 20;
  // Standing at (x, y) (pedestrian without a road, flyer): heading counter-clockwise from
  // east as the orbit's azimuth, pitch above the horizon (negative: down).
  double x = 0, y = 0, heading = 0, pitch = 0;
  double height = 1.7;  // m over the terrain: the pedestrian's eye, the flyer's height
  float fov_y = 45;

  bool on_ground() const { return kind != Kind::Fixed; }
};

// "orbit:...", "look:...",
// "pedestrian:road=ID,along=M[,ahead=M][,eye=M]" or "pedestrian:at=X,Y,heading=DEG[,pitch=DEG][,eye=M]",
// "flyer:at=X,Y,height=M,heading=DEG[,pitch=DEG]".
// Throws std::invalid_argument with what is wrong.
CameraSpec parse_camera_spec(const std::string& text, float fov_y);

// The ground's height at (x, y): the terrain's, 0 without one.
double ground_height(const exacity::City& city, double x, double y);

// The camera in the city's coordinates. Throws std::invalid_argument for a road the city
// does not have.
Camera place_camera(const CameraSpec& spec, const exacity::City& city);

}  // namespace render
