// POST /api/render's body as a render request, checked as `exacity render` checks its
// options, with the CLI's messages (docs/rendering.md).
#pragma once

#include <cstdint>
#include <string>

#include "generate/city.h"
#include "render/render.h"

namespace exacity::serve {

// What the page asked for, checked before a job starts; the camera needs the city.
struct RenderAsk {
  std::string camera;  // empty: the sketch's, else the default
  float fov = 45;
  int width = 640, height = 360, spp = 16;
  bool overview = false, minimap = false;
};

// {"camera": "orbit:..."|"look:...", "size": "WxH", "spp": N, "fov": DEG, "overview": bool,
// "minimap": bool}, every key optional. Throws UserError naming the key, or saying the
// render's samples (render_samples) are more than `max_samples`.
RenderAsk parse_render_ask(const std::string& body, std::uint64_t max_samples);

// The samples a render traces, its cost: the still's pixels times its samples per pixel,
// and the overview's and the minimap's when asked for (render/render.cpp sizes them).
std::uint64_t render_samples(const RenderAsk& ask);

// The request for `city`, files not yet named. Throws UserError for a bad camera.
render::RenderRequest render_request(const City& city, const RenderAsk& ask);

}  // namespace exacity::serve
