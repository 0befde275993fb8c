// exacity serve: the page, its static files and the JSON API over HTTP (docs/serve.md;
// docs/design.md, Serving).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "serve/connections.h"

namespace exacity::serve {

struct ServeOptions {
  std::filesystem::path work;  // created when missing; the server reads and writes only here
  std::filesystem::path web;   // the page's static files (web/ with its node_modules)
  std::string host = "127.0.0.1";
  int port = 8080;                               // 0: any free port
  std::size_t max_body = std::size_t(64) << 20;  // bytes; a larger request body is refused (413)
  // The most samples one render may trace (pixels x samples per pixel, render_samples); a
  // larger render is refused. 1920x1080 at 128 samples a pixel fits.
  std::uint64_t max_render = std::uint64_t(1) << 28;
  // What every request must carry (?token=, the cookie the page gets with it, or
  // "Authorization: Bearer"); empty: a random one made at start.
  std::string token;
  ConnectionLimits connections;
};

struct ServerState;

class CityServer {
 public:
  // Throws UserError when the work or web folder cannot be used.
  explicit CityServer(ServeOptions options);
  ~CityServer();
  CityServer(const CityServer&) = delete;
  CityServer& operator=(const CityServer&) = delete;

  // Imports a sketch from elsewhere as the work folder's sketch (exacity serve SKETCH).
  void import_sketch(const std::filesystem::path& sketch);
  // Binds the port; returns it. Throws UserError when it cannot.
  int bind();
  // The token requests must carry (ServeOptions::token).
  const std::string& token() const;
  // Answers requests until stop().
  void run();
  // Callable from any thread: stops listening and cancels a running job.
  void stop();
  // Waits for the running job to end (after stop(), it ends within its stage).
  void finish_jobs();
  const std::filesystem::path& work_folder() const;

 private:
  std::unique_ptr<ServerState> state_;
};

}  // namespace exacity::serve
