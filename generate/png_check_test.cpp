// A PNG is decoded once by libpng before OpenImageIO reads it, to catch its messages; an
// image larger than its reader takes is refused by its header's size, before its rows are
// inflated (a small file of compressed rows can be gigabytes of them).
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "generate/city/grey_image.h"
#include "generate/errors.h"
#include "generate/placement/texture_image.h"
#include "tests/test_util.h"

using namespace exacity;
namespace fs = std::filesystem;

namespace {

std::uint32_t crc32(const std::string& bytes) {
  std::uint32_t c = 0xffffffffu;
  for (unsigned char b : bytes) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return ~c;
}

std::string big_endian(std::uint32_t v) {
  return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8), static_cast<char>(v)};
}

std::string chunk(const std::string& type, const std::string& data) {
  return big_endian(static_cast<std::uint32_t>(data.size())) + type + data + big_endian(crc32(type + data));
}

// A grey PNG whose header says `width` x `height` and whose pixels stop after a few rows:
// decoded, it fails on its missing rows; by its header, it is too large.
fs::path cut_short_png(const std::string& name, std::uint32_t width, std::uint32_t height) {
  const fs::path file = testing_util::temp_dir("png-check") / (name + ".png");
  const std::string header = big_endian(width) + big_endian(height) + std::string{8, 0, 0, 0, 0};
  // zlib's stored block of 5 bytes: rows of filter 0 and zeros, then nothing.
  const std::string pixels = std::string{0x78, 0x01, 0x00, 0x05, 0x00, static_cast<char>(0xfa), static_cast<char>(0xff)} +
                             std::string(5, '\0');
  std::ofstream(file, std::ios::binary) << "\x89PNG\r\n\x1a\n" + chunk("IHDR", header) + chunk("IDAT", pixels) +
                                               chunk("IEND", "");
  return file;
}

std::string error_of(const auto& f) {
  try {
    f();
  } catch (const UserError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(PngCheck, AHeightmapLargerThanTheLimitIsRefusedByItsSizeNotDecoded) {
  const fs::path file = cut_short_png("heightmap", 10000, 10000);
  EXPECT_EQ(error_of([&] { read_grey_image(file, "the heightmap", "\"terrain\".heightmap"); }),
            file.string() + ": the heightmap is 10000 x 10000 pixels, more than the 33554432 an image may have; scale it down");
}

TEST(PngCheck, ATextureLargerThanTheLimitIsRefusedByItsSizeNotDecoded) {
  const fs::path file = cut_short_png("texture", 20000, 20000);
  TextureImages images;
  EXPECT_EQ(error_of([&] { images.read(file, "box.mtl line 3"); }),
            "box.mtl line 3: map_Kd " + file.string() + " is 20000 x 20000 pixels; textures up to 16384 a side are read: scale it down");
}

TEST(PngCheck, ACutShortPngWithinTheLimitsIsRefusedWithLibpngsReason) {
  const fs::path file = cut_short_png("small", 64, 64);
  const std::string message = error_of([&] { read_grey_image(file, "the heightmap", "\"terrain\".heightmap"); });
  EXPECT_EQ(message.rfind(file.string() + ": the heightmap is unreadable (", 0), 0u) << message;
}
