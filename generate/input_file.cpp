#include "generate/input_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include <cpl_string.h>

#include "generate/errors.h"

namespace exacity {
namespace fs = std::filesystem;

std::string megabytes(std::uintmax_t bytes) {
  const std::uintmax_t mb = bytes >> 20;
  return (mb > 0 ? std::to_string(mb) : "under 1") + " MB";
}

namespace {

std::string too_large(std::uintmax_t size, std::uintmax_t limit) {
  return "it is " + megabytes(size) + ", more than the " + megabytes(limit) + " such a file may be";
}

}  // namespace

bool readable_input(const fs::path& file, std::uintmax_t limit, std::string& why) {
  if (!CPLIsUTF8(file.c_str(), -1)) {  // outputs name their inputs in JSON, which holds only UTF-8
    why = "its name is not UTF-8 text, which the outputs naming it cannot hold; rename it";
    return false;
  }
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (!fs::exists(status)) {
    why = ec && ec != std::errc::no_such_file_or_directory ? ec.message() : "no such file";
    return false;
  }
  if (fs::is_directory(status)) {
    why = "it is a folder";
    return false;
  }
  if (!fs::is_regular_file(status)) {
    why = "it is not a regular file but a device, pipe or socket";
    return false;
  }
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec) {
    why = ec.message();
    return false;
  }
  if (size > limit) {
    why = too_large(size, limit);
    return false;
  }
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(std::fopen(file.c_str(), "rb"), std::fclose);
  if (!in) {
    why = std::strerror(errno);
    return false;
  }
  return true;
}

bool read_input(const fs::path& file, std::uintmax_t limit, std::string& bytes, std::string& why) {
  if (!readable_input(file, limit, why)) return false;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(std::fopen(file.c_str(), "rb"), std::fclose);
  if (!in) {
    why = std::strerror(errno);
    return false;
  }
  // The file may have grown since its size was read: at most `limit` bytes are taken.
  bytes.clear();
  char buffer[1 << 16];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, in.get())) {
    if (bytes.size() + n > limit) {
      why = too_large(bytes.size() + n, limit);
      return false;
    }
    bytes.append(buffer, n);
  }
  if (std::ferror(in.get())) {
    why = std::strerror(errno);
    return false;
  }
  return true;
}

std::string read_input(const fs::path& file, std::uintmax_t limit, const std::string& what, const std::string& fix) {
  std::string bytes, why;
  if (!read_input(file, limit, bytes, why))
    throw UserError(file.string() + ": cannot read " + what + " (" + why + "); " + fix);
  return bytes;
}

void expect_input(const fs::path& file, std::uintmax_t limit, const std::string& what, const std::string& fix) {
  std::string why;
  if (!readable_input(file, limit, why)) throw UserError(file.string() + ": cannot read " + what + " (" + why + "); " + fix);
}

bool lies_within(const fs::path& file, const fs::path& folder) {
  std::error_code ec;
  const fs::path f = fs::weakly_canonical(fs::absolute(file), ec);
  if (ec) return false;
  const fs::path d = fs::weakly_canonical(fs::absolute(folder), ec);
  if (ec) return false;
  const fs::path relative = f.lexically_relative(d);
  return !relative.empty() && *relative.begin() != ".." && relative != ".";
}

}  // namespace exacity
