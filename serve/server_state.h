// What the server's routes share (serve/server.cpp sets them up).
#pragma once

#include <httplib.h>

#include <atomic>
#include <memory>
#include <mutex>
#include <shared_mutex>
#include <string>

#include "generate/city.h"
#include "generate/regenerate.h"
#include "serve/confined_folder.h"
#include "serve/job_runner.h"
#include "serve/server.h"
#include "serve/work_sketch.h"

namespace exacity::serve {

struct ServerState {
  explicit ServerState(ServeOptions o)
      : options(std::move(o)), work(options.work, true), web(options.web), sketch(work), http(options.connections) {}

  ServeOptions options;
  ConfinedFolder work, web;
  WorkSketch sketch;
  JobRunner jobs;
  HttpServer http;
  int port = 0;  // bound
  std::string token;
  // Readers of the outputs share it; a job takes it alone only to swap a finished folder in.
  std::shared_mutex outputs;
  // Held while a download written when first asked for is written (serve/city_routes.cpp),
  // so that two asking at once write it once.
  std::mutex downloads;
  // Event streams open now: each holds a request thread, so they are capped below the pool
  // (serve/server.cpp) and the API keeps answering however many pages are open.
  std::atomic<int> event_streams{0};
  static constexpr int kMaxEventStreams = 16;
  // The last city generated, kept for renders.
  std::mutex city_mutex;
  std::shared_ptr<const City> city;
  // What the last generation kept for the next (generate/regenerate.h); only the job
  // thread touches it.
  std::shared_ptr<RegionCache> regions = std::make_shared<RegionCache>();

  // `message` naming files by their paths in the work folder, as the user knows them,
  // rather than by the server's absolute path to it.
  std::string in_work(std::string message) const;

  std::filesystem::path city_folder() const { return work.root() / "city"; }
  std::filesystem::path render_folder() const { return work.root() / "render"; }
};

// A refusal: the status and a one-line message as the body.
void refuse(httplib::Response& res, int status, const std::string& message);
// Sends a file of the work folder, or 404 with `missing` when it is not there.
void send_file(ServerState& s, const std::filesystem::path& file, const std::string& type, httplib::Response& res,
               const std::string& missing);

// Refuses a request this server must not take: a Host that is not one of its addresses
// (DNS rebinding), no token, a write from another origin, a body of the wrong type
// (docs/design.md, Serving: who may drive it).
httplib::Server::HandlerResponse check_request(ServerState& s, const httplib::Request& req, httplib::Response& res);

void add_sketch_routes(ServerState& s);
void add_city_routes(ServerState& s);
void add_settings_routes(ServerState& s);

}  // namespace exacity::serve
