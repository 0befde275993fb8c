// Who may drive the server, checked before a request is routed (docs/design.md, Serving:
// who may drive it).
#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include "serve/server_state.h"

namespace exacity::serve {
namespace {

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

std::string bracketed(const std::string& address) {
  return address.find(':') != std::string::npos ? "[" + address + "]" : address;
}

// Whether the Host header names this server: one of the addresses it is reached at, with
// its port. A page served from another name (DNS rebinding: attacker.example resolving to
// 127.0.0.1) is not.
bool names_this_server(const ServerState& s, const httplib::Request& req) {
  const std::string host = lower(req.get_header_value("Host"));
  const auto colon = host.rfind(':');
  const bool has_port = colon != std::string::npos && host.find(']', colon) == std::string::npos;
  const std::string name = has_port ? host.substr(0, colon) : host;
  const std::string port = has_port ? host.substr(colon + 1) : "80";
  if (port != std::to_string(s.port)) return false;
  // An IPv4 connection to a server listening on "::" arrives at an IPv4-mapped address.
  std::string arrived_at = lower(req.local_addr);
  if (arrived_at.rfind("::ffff:", 0) == 0 && arrived_at.find('.') != std::string::npos) arrived_at.erase(0, 7);
  return name == "localhost" || name == "127.0.0.1" || name == "[::1]" || name == lower(bracketed(s.options.host)) ||
         (!arrived_at.empty() && name == bracketed(arrived_at));
}

std::string cookie_name(const ServerState& s) { return "exacity_token_" + std::to_string(s.port); }

// The value of cookie `name` in the Cookie header; empty when it has none.
std::string cookie(const httplib::Request& req, const std::string& name) {
  const std::string header = req.get_header_value("Cookie");
  std::size_t start = 0;
  while (start < header.size()) {
    std::size_t end = header.find(';', start);
    if (end == std::string::npos) end = header.size();
    std::string pair = header.substr(start, end - start);
    pair.erase(0, pair.find_first_not_of(' '));
    if (pair.rfind(name + "=", 0) == 0) return pair.substr(name.size() + 1);
    start = end + 1;
  }
  return "";
}

// Compared in full whatever differs, so the time taken tells nothing of the token.
bool same_token(const std::string& given, const std::string& token) {
  if (given.size() != token.size() || token.empty()) return false;
  unsigned char differ = 0;
  for (std::size_t i = 0; i < token.size(); ++i) differ |= static_cast<unsigned char>(given[i] ^ token[i]);
  return differ == 0;
}

// The request's media type, lowercase, without its parameters; empty without one.
std::string media_type(const httplib::Request& req) {
  std::string type = lower(req.get_header_value("Content-Type"));
  // std::find rather than find(';'): g++ 12 at -O2 misreads the latter (-Wstringop-overread).
  type.erase(std::find(type.begin(), type.end(), ';'), type.end());
  while (!type.empty() && type.back() == ' ') type.pop_back();
  return type;
}

bool has_body(const httplib::Request& req) {
  const std::string length = req.get_header_value("Content-Length");
  return (!length.empty() && length != "0") || req.has_header("Transfer-Encoding");
}

// What a route takes as its body: the media types it accepts, "" meaning no Content-Type
// at all (for an empty body, or the page's heightmap upload, sent as raw bytes).
struct BodyRule {
  const char* method;
  const char* path;
  std::vector<std::string> types;
  const char* what;  // said on refusal
};

const std::vector<BodyRule>& body_rules() {
  static const std::vector<BodyRule> rules{
      {"PUT", "/api/sketch", {"application/geo+json", "application/json"},
       "send the sketch as JSON: Content-Type: application/geo+json (or application/json)"},
      {"POST", "/api/render", {"application/json"}, "send the render request as JSON: Content-Type: application/json"},
      {"POST", "/api/generate", {"", "application/json"}, "POST /api/generate takes no body"},
      {"POST", "/api/cancel", {"", "application/json"}, "POST /api/cancel takes no body"},
      {"PUT", "/api/heightmap", {"", "application/octet-stream", "image/png", "image/tiff", "image/x-exr"},
       "send the heightmap's bytes as image/png, image/tiff, image/x-exr or application/octet-stream"},
      {"POST", "/api/models", {"multipart/form-data"},
       "send the model library as multipart/form-data: the .json manifest and its OBJ and .mtl files, each part's "
       "file name its path below the library's folder"},
      {"POST", "/api/like", {"multipart/form-data"},
       "send the place as multipart/form-data: an OSM extract or a file of building footprints (a shapefile with its "
       ".shx, .dbf and .prj)"}};
  return rules;
}

}  // namespace

httplib::Server::HandlerResponse check_request(ServerState& s, const httplib::Request& req, httplib::Response& res) {
  using Answer = httplib::Server::HandlerResponse;
  const std::string address = "http://" + bracketed(s.options.host) + ":" + std::to_string(s.port) + "/";
  if (!names_this_server(s, req)) {
    refuse(res, 403,
           "refused: the Host \"" + req.get_header_value("Host") + "\" is not this server's; open " + address +
               " (or localhost, 127.0.0.1 or [::1] with port " + std::to_string(s.port) + ")");
    return Answer::Handled;
  }
  // The page's address carries the token once; the page then holds it as a cookie only
  // pages of this server send (SameSite=Strict).
  const std::string query_token = req.get_param_value("token");
  std::string bearer = req.get_header_value("Authorization");
  bearer = bearer.rfind("Bearer ", 0) == 0 ? bearer.substr(7) : "";
  const std::string& token = s.token;
  if (same_token(query_token, token)) {
    res.set_header("Set-Cookie", cookie_name(s) + "=" + token + "; Path=/; SameSite=Strict; HttpOnly");
  } else if (!same_token(cookie(req, cookie_name(s)), token) && !same_token(bearer, token)) {
    refuse(res, 403,
           "refused: no token, or a wrong one; open the address exacity serve printed (" + address +
               "?token=...), or send \"Authorization: Bearer TOKEN\"");
    return Answer::Handled;
  }
  // Writes come from this server's own page only. Browsers say where a request comes from
  // (Origin, Sec-Fetch-Site); a client that says nothing is not a browser page.
  if (req.method != "GET" && req.method != "HEAD") {
    const std::string origin = lower(req.get_header_value("Origin"));
    const std::string site = lower(req.get_header_value("Sec-Fetch-Site"));
    if ((req.has_header("Origin") && origin != "http://" + lower(req.get_header_value("Host"))) ||
        (!site.empty() && site != "same-origin" && site != "none")) {
      refuse(res, 403,
             "refused: a " + req.method + " from another site (Origin \"" + req.get_header_value("Origin") +
                 "\"); only this server's own page may change its sketch or start jobs");
      return Answer::Handled;
    }
  }
  for (const BodyRule& rule : body_rules()) {
    if (req.method != rule.method || req.path != rule.path) continue;
    const std::string type = media_type(req);
    const bool empty_allowed = rule.types.front().empty() || std::string(rule.path) == "/api/render";
    if (type.empty() && !has_body(req) && empty_allowed) break;
    if (std::find(rule.types.begin(), rule.types.end(), type) == rule.types.end()) {
      refuse(res, 415,
             std::string("refused: ") + rule.method + " " + rule.path + " with Content-Type \"" +
                 req.get_header_value("Content-Type") + "\"; " + rule.what);
      return Answer::Handled;
    }
  }
  return Answer::Unhandled;
}

}  // namespace exacity::serve
