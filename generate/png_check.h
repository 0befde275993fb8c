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
// message, or "" when it decodes. Nothing is printed.
std::string png_problem(std::string_view bytes);

}  // namespace exacity
