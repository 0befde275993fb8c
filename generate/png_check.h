// libpng prints its errors to stderr by itself whenever OpenImageIO reads a PNG it cannot
// decode ("libpng error: IHDR: Read error"), beside Exacity's one line. Decoding a PNG once
// here first, with libpng's messages caught, lets the one line carry the reason instead.
#pragma once

#include <string>
#include <string_view>

namespace exacity {

// Whether `bytes` start as a PNG file does.
bool is_png(std::string_view bytes);

// Decodes the PNG in `bytes` row by row (one row in memory) and returns libpng's error
// message, or "" when it decodes. Nothing is printed. An image of more than `max_pixels`
// is not decoded (""): its caller refuses it by the size its header gives, before the
// work its rows would be (a small file of compressed zeros inflates a thousandfold).
std::string png_problem(std::string_view bytes, double max_pixels);

}  // namespace exacity
