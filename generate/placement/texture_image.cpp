#include "generate/placement/texture_image.h"

#include <OpenImageIO/imageio.h>

#include <iterator>

#include "generate/errors.h"
#include "generate/input_file.h"
#include "generate/png_check.h"

namespace exacity {
namespace fs = std::filesystem;

namespace {

// The type a file's first bytes say: glTF 2.0 embeds PNG and JPEG only.
std::string mime_type_of(const std::vector<unsigned char>& bytes) {
  static const unsigned char png[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() >= sizeof png && std::equal(std::begin(png), std::end(png), bytes.begin())) return "image/png";
  if (bytes.size() >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff) return "image/jpeg";
  return "";
}

// OpenImageIO's message, on one line.
std::string one_line(std::string message) {
  message = message.substr(0, message.find('\n'));
  return message.empty() ? "no reason given" : message;
}

TextureImage decode(const fs::path& file, const std::string& named_by) {
  const std::string where = named_by + ": map_Kd " + file.string();
  if (!fs::exists(file)) throw UserError(where + " does not exist; put the image there or fix the map_Kd line");
  TextureImage image;
  image.file = file;
  std::string bytes, why;
  if (!read_input(file, kMaxDataFileBytes, bytes, why))
    throw UserError(where + " cannot be read (" + why + "); name a PNG or JPEG file in the map_Kd line");
  image.bytes.assign(bytes.begin(), bytes.end());
  if (is_png(bytes))
    if (const std::string problem = png_problem(bytes, double{kMaxTextureSide} * kMaxTextureSide); !problem.empty())
      throw UserError(where + " cannot be decoded (" + problem + "); save it again as PNG");
  image.mime_type = mime_type_of(image.bytes);
  if (image.mime_type.empty())
    throw UserError(where + " is not a PNG or JPEG file, the formats glTF embeds; convert it to PNG");
  // Colours as stored: OpenImageIO would multiply them by alpha, darkening what alpha hides.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto input = OIIO::ImageInput::open(file.string(), &config);
  if (!input) throw UserError(where + " cannot be decoded (" + one_line(OIIO::geterror()) + "); save it again as PNG");
  const OIIO::ImageSpec& spec = input->spec();
  image.width = spec.width, image.height = spec.height;
  if (image.width < 1 || image.height < 1 || spec.nchannels < 1) throw UserError(where + " has no pixels");
  if (image.width > kMaxTextureSide || image.height > kMaxTextureSide)
    throw UserError(where + " is " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                    " pixels; textures up to " + std::to_string(kMaxTextureSide) + " a side are read: scale it down");
  // Grey images give their one channel to all three; a second or fourth channel is alpha,
  // which is not drawn (docs/design.md, Textured models).
  const int channels = spec.nchannels;
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(image.width) * image.height * channels);
  if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, pixels.data()))
    throw UserError(where + " cannot be decoded (" + one_line(input->geterror()) + "); save it again as PNG");
  input->close();
  image.rgb.resize(static_cast<std::size_t>(image.width) * image.height * 3);
  for (std::size_t i = 0; i < image.rgb.size() / 3; ++i)
    for (int k = 0; k < 3; ++k) image.rgb[3 * i + k] = pixels[i * channels + (channels >= 3 ? k : 0)];
  return image;
}

}  // namespace

std::shared_ptr<const TextureImage> TextureImages::read(const fs::path& file, const std::string& named_by) {
  std::error_code ec;
  fs::path key = fs::weakly_canonical(file, ec);
  if (ec) key = file.lexically_normal();
  auto it = read_.find(key);
  if (it == read_.end()) it = read_.emplace(key, std::make_shared<const TextureImage>(decode(file, named_by))).first;
  return it->second;
}

}  // namespace exacity
