// The one way Exacity reads a file a user names (sketches, grid maps, grammars, model
// libraries, OBJ and MTL files, images, camera paths): only a regular file, and only up to
// a size limit, so a device such as /dev/zero, a pipe or a folder is one line, not a hang
// or runaway memory (docs/limits.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace exacity {

// Sketches (GeoJSON, grid maps, OSM extracts, other vector files), OBJ models and images.
inline constexpr std::uintmax_t kMaxDataFileBytes = std::uintmax_t{256} << 20;
// Grammars, model library manifests, MTL files, settings files and camera paths.
inline constexpr std::uintmax_t kMaxSettingsFileBytes = std::uintmax_t{16} << 20;

// Whether `file` may be read: false, with `why` ("no such file", "it is a folder", ...),
// when it is missing, not a regular file, larger than `limit` or cannot be opened.
bool readable_input(const std::filesystem::path& file, std::uintmax_t limit, std::string& why);

// The file's bytes, or false with `why` as readable_input gives it.
bool read_input(const std::filesystem::path& file, std::uintmax_t limit, std::string& bytes, std::string& why);

// The file's bytes; throws UserError "FILE: cannot read WHAT (WHY); FIX".
std::string read_input(const std::filesystem::path& file, std::uintmax_t limit, const std::string& what,
                       const std::string& fix);

// Throws UserError "FILE: cannot read WHAT (WHY); FIX" unless readable_input: for files a
// library opens itself (OpenImageIO, GDAL, libosmium).
void expect_input(const std::filesystem::path& file, std::uintmax_t limit, const std::string& what,
                  const std::string& fix);

// Whether `file` lies in `folder` or below it, symbolic links followed: the MTL and texture
// files a library's OBJ names stay below the library's folder (or the OBJ's own).
bool lies_within(const std::filesystem::path& file, const std::filesystem::path& folder);

// "16 MB": a limit as messages say it.
std::string megabytes(std::uintmax_t bytes);

}  // namespace exacity
