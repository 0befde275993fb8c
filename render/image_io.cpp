#include "render/image_io.h"

#include <Imath/half.h>
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

namespace render {
namespace fs = std::filesystem;

namespace {

void write(const fs::path& file, const OIIO::ImageSpec& spec, const void* data) {
  const fs::path temporary = file.string() + ".partial" + file.extension().string();
  auto out = OIIO::ImageOutput::create(file.string());
  if (!out || !out->open(temporary.string(), spec) || !out->write_image(OIIO::TypeUnknown, data) || !out->close())
    throw std::runtime_error(file.string() + ": cannot write the image (" + OIIO::geterror() + ")");
  fs::rename(temporary, file);
}

std::uint8_t to_srgb8(float linear) {
  linear = std::clamp(linear, 0.0f, 1.0f);
  float s = linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1 / 2.4f) - 0.055f;
  return static_cast<std::uint8_t>(std::lround(s * 255));
}

}  // namespace

void Rgb8::set(int x, int y, V3 c) {
  if (x < 0 || y < 0 || x >= width || y >= height) return;
  std::uint8_t* p = &pixels[(static_cast<std::size_t>(y) * width + x) * 3];
  p[0] = to_srgb8(c.x), p[1] = to_srgb8(c.y), p[2] = to_srgb8(c.z);
}

void write_exr(const Image& img, const fs::path& file) {
  // One interleaved buffer in the file's own channel types.
  OIIO::ImageSpec spec(img.width, img.height, 11);
  spec.channelnames = {"R", "G", "B", "Z", "N.X", "N.Y", "N.Z", "albedo.R", "albedo.G", "albedo.B", "id"};
  spec.channelformats = {OIIO::TypeDesc::HALF,  OIIO::TypeDesc::HALF,  OIIO::TypeDesc::HALF,  OIIO::TypeDesc::FLOAT,
                         OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::FLOAT,
                         OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::FLOAT, OIIO::TypeDesc::UINT};
  spec.z_channel = 3;
  spec.attribute("compression", "zip");
  // The writer stamps the time otherwise, and the same city must give the same bytes.
  spec.attribute("DateTime", "");
  const std::size_t n = img.beauty.size();
  // 3 halves, 7 floats, 1 uint: 6 + 28 + 4 bytes.
  constexpr std::size_t kPixel = 38;
  std::vector<unsigned char> data(n * kPixel);
  for (std::size_t i = 0; i < n; ++i) {
    unsigned char* p = &data[i * kPixel];
    auto half = [&](float v, int at) {
      Imath::half h(v);
      std::memcpy(p + at, &h, 2);
    };
    auto single = [&](float v, int at) { std::memcpy(p + at, &v, 4); };
    half(img.beauty[i].x, 0), half(img.beauty[i].y, 2), half(img.beauty[i].z, 4);
    single(img.depth[i], 6), single(img.normal[i].x, 10), single(img.normal[i].y, 14), single(img.normal[i].z, 18);
    single(img.albedo[i].x, 22), single(img.albedo[i].y, 26), single(img.albedo[i].z, 30);
    std::memcpy(p + 34, &img.id[i], 4);
  }
  write(file, spec, data.data());
}

Rgb8 tone_map(const Image& img, float exposure, V3 gains) {
  Rgb8 out{img.width, img.height, std::vector<std::uint8_t>(img.beauty.size() * 3)};
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      V3 c = img.beauty[static_cast<std::size_t>(y) * img.width + x] * gains * exposure;
      auto aces = [](float v) { return v * (2.51f * v + 0.03f) / (v * (2.43f * v + 0.59f) + 0.14f); };
      out.set(x, y, {aces(c.x), aces(c.y), aces(c.z)});
    }
  return out;
}

float metered_stops(const Image& img) {
  // The log-average luminance of the town's default still (exacity render out/town).
  constexpr double kSunlitTown = 0.66;
  if (img.beauty.empty()) return 0;
  double logs = 0;
  for (const V3& c : img.beauty) logs += std::log(1e-4 + std::max(0.0f, luminance(c)));
  const double average = std::exp(logs / static_cast<double>(img.beauty.size()));
  return static_cast<float>(std::clamp(std::log2(kSunlitTown / average), 0.0, double{kMostMeteredStops}));
}

void write_png(const Rgb8& img, const fs::path& file) {
  OIIO::ImageSpec spec(img.width, img.height, 3, OIIO::TypeDesc::UINT8);
  write(file, spec, img.pixels.data());
}

}  // namespace render
