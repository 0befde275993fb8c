#include "serve/server.h"

#include <sys/socket.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "generate/errors.h"
#include "serve/server_state.h"

namespace exacity::serve {
namespace fs = std::filesystem;

namespace {

// 128 random bits in hex.
std::string random_token() {
  std::random_device random;
  std::string token;
  for (int i = 0; i < 4; ++i) {
    char part[9];
    std::snprintf(part, sizeof part, "%08x", static_cast<unsigned>(random()));
    token += part;
  }
  return token;
}

const std::map<std::string, std::string>& content_types() {
  static const std::map<std::string, std::string> types{{".html", "text/html; charset=utf-8"},
                                                        {".js", "text/javascript; charset=utf-8"},
                                                        {".mjs", "text/javascript; charset=utf-8"},
                                                        {".css", "text/css; charset=utf-8"},
                                                        {".json", "application/json"},
                                                        {".map", "application/json"},
                                                        {".png", "image/png"},
                                                        {".svg", "image/svg+xml"},
                                                        {".ico", "image/x-icon"},
                                                        {".glb", "model/gltf-binary"},
                                                        {".geojson", "application/geo+json"},
                                                        {".txt", "text/plain; charset=utf-8"}};
  return types;
}

// GET of the page's own files: anything under web/ by the confined folder's rules.
void send_static(ServerState& s, const httplib::Request& req, httplib::Response& res) {
  std::string name = req.path.substr(1);
  if (name.empty()) name = "index.html";
  fs::path file;
  try {
    file = s.web.resolve(name);
  } catch (const PathRefused& e) {
    return refuse(res, 400, std::string("path refused: ") + e.what());
  }
  const auto type = content_types().find(file.extension().string());
  if (!fs::is_regular_file(file) || type == content_types().end()) return refuse(res, 404, "not found: " + req.path);
  std::ifstream in(file, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  res.set_content(bytes.str(), type->second.c_str());
}

}  // namespace

std::string ServerState::in_work(std::string message) const {
  const std::string prefix = work.root().string() + "/";
  for (std::size_t at; (at = message.find(prefix)) != std::string::npos;) message.erase(at, prefix.size());
  return message;
}

void refuse(httplib::Response& res, int status, const std::string& message) {
  res.status = status;
  res.set_content(message, "text/plain; charset=utf-8");
}

void send_file(ServerState& s, const fs::path& file, const std::string& type, httplib::Response& res,
               const std::string& missing) {
  std::shared_lock lock(s.outputs);
  std::ifstream in(file, std::ios::binary);
  if (!in || !fs::is_regular_file(file)) return refuse(res, 404, missing);
  std::stringstream bytes;
  bytes << in.rdbuf();
  res.set_header("Cache-Control", "no-store");
  res.set_content(bytes.str(), type.c_str());
}

CityServer::CityServer(ServeOptions options) {
  try {
    state_ = std::make_unique<ServerState>(std::move(options));
  } catch (const PathRefused& e) {
    throw UserError(std::string("exacity serve: ") + e.what() + "; check --work, or the web folder");
  }
  ServerState& s = *state_;
  s.token = s.options.token.empty() ? random_token() : s.options.token;
  // SO_REUSEADDR only: httplib's default adds SO_REUSEPORT, which would let a second server
  // (or another program of this user) bind the same port and take some of its connections.
  s.http.set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  s.http.set_payload_max_length(s.options.max_body);
  // A page load is some thirty requests: httplib's default of closing a connection after five
  // makes the browser open new ones mid-load (and report a large response cut short as
  // aborted when the close comes with it).
  s.http.set_keep_alive_max_count(1000);
  s.http.set_keep_alive_timeout(2);
  s.http.set_exception_handler([&s](const httplib::Request&, httplib::Response& res, std::exception_ptr e) {
    try {
      std::rethrow_exception(e);
    } catch (const UserError& u) {
      refuse(res, 400, s.in_work(u.what()));
    } catch (const std::exception& x) {
      refuse(res, 500, std::string("internal error: ") + s.in_work(x.what()));
    } catch (...) {
      refuse(res, 500, "internal error");
    }
  });
  // httplib's own refusals (no route, body too large, bad request line) get a message too.
  s.http.set_error_handler(httplib::Server::HandlerWithResponse(
      [max = s.options.max_body](const httplib::Request& req, httplib::Response& res) {
        if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
        if (res.status == 404)
          refuse(res, 404,
                 "no such route: " + req.method + " " + req.path + "; the API is listed in docs/serve.md");
        else if (res.status == 413)
          refuse(res, 413, "request body too large: at most " + std::to_string(max) + " bytes");
        else
          refuse(res, res.status,
                 "bad request (HTTP " + std::to_string(res.status) +
                     "): a malformed request line or header, or a POST or PUT without a Content-Length");
        return httplib::Server::HandlerResponse::Handled;
      }));
  s.http.set_pre_routing_handler(
      [&s](const httplib::Request& req, httplib::Response& res) { return check_request(s, req, res); });
  add_sketch_routes(s);
  add_city_routes(s);
  add_settings_routes(s);
  s.http.Get(R"(/(.*))", [&s](const httplib::Request& req, httplib::Response& res) {
    if (req.path.rfind("/api/", 0) == 0)
      return refuse(res, 404, "no such route: GET " + req.path + "; the API is listed in docs/serve.md");
    send_static(s, req, res);
  });
}

CityServer::~CityServer() {
  stop();
  finish_jobs();
}

void CityServer::import_sketch(const fs::path& sketch) { state_->sketch.import(sketch); }

int CityServer::bind() {
  ServerState& s = *state_;
  const bool any = s.options.port == 0;
  const int port = any ? s.http.bind_to_any_port(s.options.host)
                       : (s.http.bind_to_port(s.options.host, s.options.port) ? s.options.port : -1);
  if (port <= 0)
    throw UserError("exacity serve: cannot listen on " + s.options.host + ":" + std::to_string(s.options.port) +
                    " (in use, or not an address of this machine); choose another --port or --host");
  s.port = port;
  return port;
}

void CityServer::run() { state_->http.listen_after_bind(); }

void CityServer::stop() {
  state_->jobs.cancel();
  state_->http.stop();
  state_->http.drop_connections();
}

const std::string& CityServer::token() const { return state_->token; }

void CityServer::finish_jobs() { state_->jobs.stop(); }

const fs::path& CityServer::work_folder() const { return state_->work.root(); }

}  // namespace exacity::serve
