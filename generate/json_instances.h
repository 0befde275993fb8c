// nlohmann::json's two document types, instantiated once in json_instances.cpp. The files of
// the libraries see these declarations through their precompiled header (CMakeLists.txt,
// exacity_precompiled_headers), so each compiles only what it inlines of the members it uses
// rather than every one of them again: about a tenth of a cold build.
#pragma once

#include <nlohmann/json.hpp>

extern template class nlohmann::basic_json<>;
extern template class nlohmann::basic_json<nlohmann::ordered_map>;
