// exacity serve: the sketch editor and viewer in a browser (docs/serve.md).
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <filesystem>
#include <string>

namespace exacity {

struct ServeCommand {
  CLI::App* app = nullptr;
  std::filesystem::path sketch, work = "exacity-work";
  std::string host = "127.0.0.1";
  int port = 8080;
  std::uint64_t max_render = std::uint64_t(1) << 28;  // serve::ServeOptions::max_render
};

void add_serve(CLI::App& app, ServeCommand& c);
// Serves until SIGINT or SIGTERM; returns 128 + the signal. Throws UserError.
int run_serve(const ServeCommand& c);

}  // namespace exacity
