// GET and PUT /api/sketch, PUT /api/heightmap, GET /api/heightmap.png, GET and POST /api/models
// and /api/like, GET /api/lonlat, GET /api/basemap and /api/basemap.png.
#include <tuple>

#include "generate/errors.h"
#include "generate/gis/projection.h"
#include "generate/placement/model_library.h"
#include "serve/basemap.h"
#include "serve/server_state.h"

namespace exacity::serve {
using nlohmann::json;

namespace {

// The model library the sketch names, read as the model library stage reads it: each model's
// name, kind, the zone types it stands in, weight and size; and the built-in models wanted.
json library_in_use(ServerState& s) {
  json out{{"file", nullptr}, {"models", json::array()}, {"builtin", json::array()}};
  if (!s.sketch.stored()) return out;
  const Sketch sketch = s.sketch.load();
  if (sketch.builtin_trees) out["builtin"].push_back("tree");
  if (sketch.builtin_lamps) out["builtin"].push_back("lamp");
  if (sketch.models.empty()) return out;
  out["file"] = s.in_work(sketch.models.lexically_normal().string());
  for (const Model& m : load_model_library(sketch.models).models) {
    json zones = json::array();
    for (ZoneType z : m.zones) zones.push_back(name(z));
    json model{{"name", m.name}, {"kind", name(m.kind)}, {"zones", zones}, {"weight", m.weight},
               {"size", {m.width, m.depth, m.height}}};
    if (m.has_lot()) model["lot"] = {m.lot_width, m.lot_depth};
    out["models"].push_back(std::move(model));
  }
  return out;
}

// Where the sketch lies on Earth, for a basemap under it: its CRS's EPSG code, and the
// lon/lat PROJ gives a grid of points over its features' box grown by its size each way,
// which the page interpolates (over a city's few kilometres a map projection is as good as
// linear; the page needs no projection library). No EPSG code: no place on Earth.
json lonlat_grid(ServerState& s) {
  json out{{"epsg", nullptr}};
  if (!s.sketch.stored()) return out;
  const Sketch sketch = s.sketch.load();
  const std::optional<int> epsg = sketch.crs.is_null() ? std::nullopt : epsg_of(sketch.crs);
  if (!epsg) return out;
  const geom::Box box = sketch_surroundings(sketch);
  constexpr int kSide = 9;
  const ToLonLat to_lonlat(*epsg);
  json points = json::array();
  for (int row = 0; row < kSide; ++row)
    for (int col = 0; col < kSide; ++col) {
      const geom::Vec2 p = to_lonlat({box.min_x + box.width() * col / (kSide - 1), box.min_y + box.height() * row / (kSide - 1)});
      points.push_back({p.x, p.y});
    }
  out["epsg"] = *epsg;
  out["box"] = {box.min_x, box.min_y, box.max_x, box.max_y};
  out["side"] = kSide;
  out["lonlat"] = std::move(points);  // row by row from the south-west corner, x first
  return out;
}

// The place the sketch's "like" names, measured as generate measures it: {"file", "measured"}
// (report.json's "like", in its order), both null when it names none.
nlohmann::ordered_json place_measured(ServerState& s) {
  const nlohmann::ordered_json measured = s.sketch.stored() ? s.sketch.like_measured() : nullptr;
  return {{"file", measured.is_null() ? nlohmann::ordered_json() : measured["file"]}, {"measured", measured}};
}

}  // namespace

void add_sketch_routes(ServerState& s) {
  s.http.Get("/api/sketch", [&s](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    res.set_content(s.sketch.text(), "application/geo+json");
  });
  // Checked exactly as the CLI checks a sketch: a bad one is a 400 with the CLI's message,
  // and the stored sketch stays as it was.
  s.http.Put("/api/sketch", [&s](const httplib::Request& req, httplib::Response& res) {
    try {
      s.sketch.put(req.body);
    } catch (const UserError& e) {
      return refuse(res, 400, s.in_work(e.what()));
    }
    res.set_content(s.sketch.text(), "application/geo+json");
  });
  s.http.Put("/api/heightmap", [&s](const httplib::Request& req, httplib::Response& res) {
    try {
      s.sketch.put_heightmap(req.body, req.get_param_value("bounds"), req.get_param_value("height"));
    } catch (const UserError& e) {
      return refuse(res, 400, s.in_work(e.what()));
    }
    res.set_content(s.sketch.text(), "application/geo+json");
  });
  // A model library's files, or a real place's, in one multipart form (check_request
  // refuses any other body), each part's file name its path below their folder: stored as
  // work/models or work/like and named by the sketch. Refused while a job runs, but for a
  // generation that has answered (its validation reads only work/city): a generation reads
  // the library and the place it started with.
  using Upload = Sketch (WorkSketch::*)(const std::vector<std::pair<std::string, std::string>>&);
  for (const auto& [route, what, put] : {std::tuple{"/api/models", "library", Upload{&WorkSketch::put_library}},
                                         std::tuple{"/api/like", "place", Upload{&WorkSketch::put_like}}})
    s.http.Post(route, [&s, what = std::string(what), put = put](const httplib::Request& req, httplib::Response& res) {
      if (const JobStatus now = s.jobs.status(); now.state == JobState::Running && !now.answered)
        return refuse(res, 409, "a " + now.job + " job is running; upload the " + what + " when it ends");
      std::vector<std::pair<std::string, std::string>> files;
      for (const auto& [field, part] : req.files) files.emplace_back(part.filename, part.content);
      try {
        (s.sketch.*put)(files);
      } catch (const UserError& e) {
        return refuse(res, 400, s.in_work(e.what()));
      }
      res.set_content(s.sketch.text(), "application/geo+json");
    });
  // What the stored sketch names or says, read as generate reads it: a sketch that no longer
  // reads (a library changed under it) is a 400 with the CLI's message.
  s.http.Get("/api/like", [&s](const httplib::Request&, httplib::Response& res) {
    nlohmann::ordered_json answer;
    try {
      answer = place_measured(s);
    } catch (const UserError& e) {
      return refuse(res, 400, s.in_work(e.what()));
    }
    res.set_header("Cache-Control", "no-store");
    res.set_content(answer.dump(), "application/json");
  });
  for (const auto& [route, read] : {std::pair{"/api/models", &library_in_use}, std::pair{"/api/lonlat", &lonlat_grid}})
    s.http.Get(route, [&s, read = read](const httplib::Request&, httplib::Response& res) {
      json answer;
      try {
        answer = read(s);
      } catch (const UserError& e) {
        return refuse(res, 400, s.in_work(e.what()));
      }
      res.set_header("Cache-Control", "no-store");
      res.set_content(answer.dump(), "application/json");
    });
  // A GeoTIFF below the work folder drawn under the sketch: where it lies, then its picture.
  // Read-only, so a GET (behind the token and Host checks as every route).
  const auto basemap = [&s](const httplib::Request& req) {
    if (!s.sketch.stored()) throw UserError("basemap: there is no sketch yet to place it under; draw or open one");
    return place_basemap(s.work, req.get_param_value("file"), s.sketch.load());
  };
  s.http.Get("/api/basemap", [&s, basemap](const httplib::Request& req, httplib::Response& res) {
    BasemapImage image;
    try {
      image = basemap(req);
    } catch (const UserError& e) {
      return refuse(res, 400, s.in_work(e.what()));
    }
    const json answer{{"file", image.name},
                      {"extent", image.extent},
                      {"size", {image.width, image.height}},
                      {"crs", image.target_srs.empty() ? json(nullptr) : json(image.target_srs)}};
    res.set_header("Cache-Control", "no-store");
    res.set_content(answer.dump(), "application/json");
  });
  s.http.Get("/api/basemap.png", [&s, basemap](const httplib::Request& req, httplib::Response& res) {
    std::string png;
    try {
      png = basemap_png(basemap(req));
    } catch (const UserError& e) {
      return refuse(res, 400, s.in_work(e.what()));
    }
    res.set_header("Cache-Control", "no-store");
    res.set_content(png, "image/png");
  });
  s.http.Get("/api/heightmap.png", [&s](const httplib::Request&, httplib::Response& res) {
    std::optional<std::string> png;
    try {
      png = s.sketch.heightmap_preview();
    } catch (const UserError& e) {
      return refuse(res, 404, s.in_work(e.what()));
    }
    if (!png) return refuse(res, 404, "the sketch has no heightmap; load one (PUT /api/heightmap)");
    res.set_header("Cache-Control", "no-store");
    res.set_content(*png, "image/png");
  });
}

}  // namespace exacity::serve
