// A model's diffuse texture (an MTL's map_Kd): the image file's bytes, which city.glb
// embeds as they are, and its pixels, which the renderer samples. Each file is read once,
// however many materials and models name it (docs/design.md, Textured models).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace exacity {

struct TextureImage {
  std::filesystem::path file;
  std::string mime_type;             // "image/png" or "image/jpeg": the formats glTF embeds
  std::vector<unsigned char> bytes;  // the file as read
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // sRGB, 3 a pixel, row 0 at the top of the image; alpha dropped
};

// The images read so far, by file, so a file named by many materials is one image.
class TextureImages {
 public:
  // Throws UserError starting with `named_by` (the MTL file and line) when the file is
  // missing, is not a PNG or JPEG, cannot be decoded or is too large.
  std::shared_ptr<const TextureImage> read(const std::filesystem::path& file, const std::string& named_by);

 private:
  std::map<std::filesystem::path, std::shared_ptr<const TextureImage>> read_;
};

inline constexpr int kMaxTextureSide = 16384;

}  // namespace exacity
