// Exacity's version, as --version, report.json and the exports' generator fields name it.
#pragma once

namespace exacity {

inline constexpr const char* kVersion = "0.1.0";

}  // namespace exacity
