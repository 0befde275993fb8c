// The error of renders against a reference, by render/image_error.h's definition (the RMSE
// of the tone-mapped 8-bit images, over 255), for images from any renderer: the linear RGB
// of EXR files (the first three channels, or R, G, B where named). With --png, each image
// is also written tone-mapped the way exacity render writes its PNG. The Cycles
// comparison (benchmarks/cycles/) measures both renderers with it.
//
//   build/release/benchmarks/exacity_image_error REFERENCE.exr IMAGE.exr... [--png] [--exposure 0.25]
//
// --exposure scales the radiance before the curve (a night view's camera opened up, as
// still.json's night_stops and metered_ev say: 0.25 × 2^stops).
// Prints one line per image: its path and its RMSE; IMAGE.png beside IMAGE.exr with --png.
#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "render/image_error.h"

using namespace render;

namespace {

std::optional<Image> read_beauty(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return std::nullopt;
  const OIIO::ImageSpec& spec = in->spec();
  int r = spec.channelindex("R"), g = spec.channelindex("G"), b = spec.channelindex("B");
  if (r < 0 || g < 0 || b < 0) r = 0, g = 1, b = 2;
  if (spec.nchannels < 3) return std::nullopt;
  std::vector<float> all(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data())) return std::nullopt;
  Image img;
  img.width = spec.width, img.height = spec.height;
  img.beauty.resize(static_cast<std::size_t>(spec.width) * spec.height);
  for (std::size_t i = 0; i < img.beauty.size(); ++i) {
    const float* p = &all[i * static_cast<std::size_t>(spec.nchannels)];
    img.beauty[i] = {p[r], p[g], p[b]};
  }
  return img;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> paths;
  bool png = false;
  float exposure = 0.25f;  // exacity render's default
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--png"))
      png = true;
    else if (!std::strcmp(argv[i], "--exposure") && i + 1 < argc)
      exposure = std::stof(argv[++i]);
    else
      paths.push_back(argv[i]);
  }
  if (paths.size() < 2) {
    std::fprintf(stderr, "usage: exacity_image_error REFERENCE.exr IMAGE.exr... [--png] [--exposure X]\n");
    return 2;
  }
  const std::optional<Image> reference = read_beauty(paths[0]);
  if (!reference) {
    std::fprintf(stderr, "%s: cannot read its RGB channels\n", paths[0].c_str());
    return 2;
  }
  for (std::size_t k = 1; k < paths.size(); ++k) {
    const std::optional<Image> img = read_beauty(paths[k]);
    if (!img || img->width != reference->width || img->height != reference->height) {
      std::fprintf(stderr, "%s: cannot read its RGB channels, or not the reference's size\n", paths[k].c_str());
      return 2;
    }
    std::printf("%s %.6f\n", paths[k].c_str(), display_rmse(*img, *reference, exposure));
    if (png) write_png(tone_map(*img, exposure), std::filesystem::path(paths[k]).replace_extension(".png"));
  }
  if (png) write_png(tone_map(*reference, exposure), std::filesystem::path(paths[0]).replace_extension(".png"));
  return 0;
}
