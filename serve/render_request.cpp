#include "serve/render_request.h"

#include <algorithm>
#include <sstream>

#include "generate/errors.h"
#include "render/camera_spec.h"

namespace exacity::serve {

namespace {

// The largest image a page may ask for: the CLI allows 16384 a side, but one request here
// should not hold the worker for hours (docs/design.md, Serving).
constexpr int kMaxSide = 4096, kMaxSamples = 4096;

}  // namespace

std::uint64_t render_samples(const RenderAsk& ask) {
  const std::uint64_t spp = static_cast<std::uint64_t>(ask.spp), side = std::max(ask.width, ask.height);
  std::uint64_t samples = static_cast<std::uint64_t>(ask.width) * ask.height * spp;
  if (ask.overview) samples += side * side * spp;
  if (ask.minimap) samples += std::uint64_t{256} * 256 * std::max<std::uint64_t>(1, spp / 4);
  return samples;
}

RenderAsk parse_render_ask(const std::string& body, std::uint64_t max_samples) {
  const nlohmann::json j = nlohmann::json::parse(body.empty() ? "{}" : body, nullptr, false);
  if (j.is_discarded() || !j.is_object())
    throw UserError(
        "the render request is not a JSON object; send e.g. {\"camera\": \"orbit:target=0,0,0,azimuth=225,"
        "elevation=35,distance=900\", \"size\": \"640x360\", \"spp\": 16}");
  for (const auto& [key, value] : j.items())
    if (key != "camera" && key != "size" && key != "spp" && key != "fov" && key != "overview" && key != "minimap")
      throw UserError("render request: unknown key \"" + key + "\"; known: camera, size, spp, fov, overview, minimap");
  RenderAsk ask;
  if (j.contains("camera")) {
    if (!j["camera"].is_string()) throw UserError("render request: \"camera\" must be a string such as \"orbit:...\"");
    ask.camera = j["camera"].get<std::string>();
  }
  if (j.contains("size")) {
    const std::string size = j["size"].is_string() ? j["size"].get<std::string>() : j["size"].dump();
    std::istringstream in(size);
    char x = 0;
    if (!(in >> ask.width >> x >> ask.height) || x != 'x' || !in.eof() || ask.width < 8 || ask.height < 8 ||
        ask.width > kMaxSide || ask.height > kMaxSide)
      throw UserError("render request: \"size\" " + size + ": expected WIDTHxHEIGHT such as 640x360 (8 to " +
                      std::to_string(kMaxSide) + " each)");
  }
  if (j.contains("spp")) {
    if (!j["spp"].is_number_integer() || j["spp"].get<long long>() < 1 || j["spp"].get<long long>() > kMaxSamples)
      throw UserError("render request: \"spp\" must be a whole number of samples per pixel, 1 to " +
                      std::to_string(kMaxSamples));
    ask.spp = j["spp"].get<int>();
  }
  if (j.contains("fov")) {
    if (!j["fov"].is_number() || j["fov"].get<double>() < 5 || j["fov"].get<double>() > 150)
      throw UserError("render request: \"fov\" must be a vertical field of view in degrees, 5 to 150");
    ask.fov = j["fov"].get<float>();
  }
  for (const char* flag : {"overview", "minimap"})
    if (j.contains(flag) && !j[flag].is_boolean())
      throw UserError(std::string("render request: \"") + flag + "\" must be true or false");
  ask.overview = j.value("overview", false);
  ask.minimap = j.value("minimap", false);
  if (const std::uint64_t samples = render_samples(ask); samples > max_samples)
    throw UserError("render request: " + std::to_string(ask.width) + "x" + std::to_string(ask.height) + " at " +
                    std::to_string(ask.spp) + " samples per pixel" + (ask.overview ? " with the overview" : "") +
                    " is " + std::to_string(samples) + " samples; this server renders at most " +
                    std::to_string(max_samples) +
                    " (exacity serve --max-render); ask for a smaller size or fewer samples");
  // Checked now, so a bad camera is a 400 rather than a failed job.
  if (!ask.camera.empty()) {
    try {
      render::parse_camera_spec(ask.camera, ask.fov);
    } catch (const std::invalid_argument& e) {
      throw UserError(
          "render request: \"camera\" \"" + ask.camera + "\": " + e.what() +
          "; e.g. orbit:target=0,0,0,azimuth=225,elevation=35,distance=900 or look:from=0,-500,200,to=0,0,0");
    }
  }
  return ask;
}

render::RenderRequest render_request(const City& city, const RenderAsk& ask) {
  render::RenderRequest r;
  r.width = ask.width, r.height = ask.height, r.spp = ask.spp;
  const std::string spec = !ask.camera.empty() ? ask.camera : city.camera;
  try {
    r.camera = spec.empty() ? render::default_camera(city)
                            : render::place_camera(render::parse_camera_spec(spec, ask.fov), city);
  } catch (const std::invalid_argument& e) {
    throw UserError((!ask.camera.empty() ? std::string("render request: \"camera\"")
                                          : city.settings.path.string() + ": \"exacity\".camera") +
                    " \"" + spec + "\": " + e.what());
  }
  if (spec.empty()) r.camera.fov_y = ask.fov;
  r.overview = ask.overview, r.minimap = ask.minimap;
  return r;
}

}  // namespace exacity::serve
