#include "generate/png_check.h"

#include <csetjmp>
#include <cstring>
#include <vector>

#include <png.h>

namespace exacity {

namespace {

struct Reading {
  std::string_view bytes;
  std::size_t at = 0;
  std::string error;
};

void on_error(png_structp png, png_const_charp message) {
  static_cast<Reading*>(png_get_error_ptr(png))->error = message;
  png_longjmp(png, 1);
}

void on_warning(png_structp, png_const_charp) {}

void on_read(png_structp png, png_bytep out, png_size_t length) {
  Reading& r = *static_cast<Reading*>(png_get_io_ptr(png));
  if (length > r.bytes.size() - r.at) png_error(png, "the file ends before the image does");
  std::memcpy(out, r.bytes.data() + r.at, length);
  r.at += length;
}

}  // namespace

bool is_png(std::string_view bytes) {
  return bytes.size() >= 8 && png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8) == 0;
}

std::string png_problem(std::string_view bytes, double max_pixels) {
  Reading r{bytes, 0, {}};
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &r, on_error, on_warning);
  if (!png) return "libpng cannot start";
  png_infop info = png_create_info_struct(png);
  // Locals changed between a setjmp and its longjmp lose their values: the row buffer is
  // sized between the two reads, outside either.
  std::vector<png_byte> row;
  int passes = 0;
  png_uint_32 height = 0;
  if (setjmp(png_jmpbuf(png)) == 0) {
    png_set_read_fn(png, &r, on_read);
    png_read_info(png, info);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
  }
  // Too large an image is left to the caller's size check, undecoded.
  if (r.error.empty() && static_cast<double>(png_get_image_width(png, info)) * png_get_image_height(png, info) <= max_pixels) {
    passes = png_get_interlace_type(png, info) == PNG_INTERLACE_ADAM7 ? 7 : 1;
    height = png_get_image_height(png, info);
    row.resize(png_get_rowbytes(png, info));
    if (setjmp(png_jmpbuf(png)) == 0) {
      for (int pass = 0; pass < passes; ++pass)
        for (png_uint_32 y = 0; y < height; ++y) png_read_row(png, row.data(), nullptr);
      png_read_end(png, nullptr);
    }
  }
  png_destroy_read_struct(&png, &info, nullptr);
  return r.error;
}

}  // namespace exacity
