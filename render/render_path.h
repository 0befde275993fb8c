// Renders frames of a camera path (render/README.md, Camera paths): frame n is the still
// of the path's camera at n / fps, into DIR/frame_NNNN.png with its EXR and JSON beside,
// a job of its own that depends on nothing but the city, the request and n, so frames
// rendered in any ranges (a Slurm job array's) are the same bytes as one run's.
#pragma once

#include <filesystem>
#include <string>

#include "render/camera_path.h"
#include "render/render.h"

namespace render {

// Part `part` (0 to parts - 1) of frames first..last cut into `parts` runs of consecutive
// frames, their lengths differing by one at most, the longer first: a Slurm job array's
// task's share (scripts/render_path.sbatch). Empty (first > last) when there are more
// parts than frames.
std::pair<int, int> frame_share(int first, int last, int part, int parts);

// "frame_0042.png"
std::string frame_file_name(int n);

// Frames first..last (inclusive) of `path` (placed on `city` here unless it was already),
// each with `request`'s image settings and depth of field and the path's camera (city
// coordinates); no overview or minimap. Returns the frames' reports.
nlohmann::ordered_json render_path_frames(const exacity::City& city, const CameraPath& path, int first, int last,
                                          const RenderRequest& request, const std::filesystem::path& dir,
                                          const RenderProgress& progress = nullptr);

}  // namespace render
