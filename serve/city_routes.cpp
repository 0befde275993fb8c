// The generate and render jobs, their status and events, and the outputs they leave.
#include <algorithm>
#include <chrono>
#include <fstream>
#include <set>
#include <sstream>

#include "generate/city_report.h"
#include "generate/errors.h"
#include "generate/export/clutter_layer.h"
#include "generate/export/gis_export.h"
#include "generate/export/output_folder.h"
#include "generate/pipeline.h"
#include "generate/sketch/like_place.h"
#include "geom/kernel.h"
#include "serve/city_tiles.h"
#include "serve/render_request.h"
#include "serve/server_state.h"

namespace exacity::serve {
namespace fs = std::filesystem;

namespace {

const std::string kNoCity = "no city yet: POST /api/generate first";

std::string read_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void refuse_busy(ServerState& s, httplib::Response& res) {
  const JobStatus now = s.jobs.status();
  refuse(res, 409, "a " + now.job + " job is running (" + now.stage + "); wait for it to finish (GET /api/status)");
}

// Sketch to every output into work/city, as exacity generate does (docs/design.md, The
// pipeline), but for the files only downloaded (the 3D files and the GeoPackage, written
// when first asked for: send_city_file), then the 3D view's tiles (docs/design.md,
// Serving: tiles). What the page shows is committed and answered before validation, which
// then checks the folder and writes its report again (Serving: jobs).
void generate_job(ServerState& s, const Sketch& drawn, JobRunner::Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  OutputFolder folder(s.city_folder());
  StageClock clock([&](int i, int n, const std::string& stage) { progress.stage(i, n, stage); },
                   kCityStages + kWriteStages);  // the write stages less the 3d export, and the tiles
  // The zone parameters of the place the sketch's "like" names, measured first.
  Sketch sketch = drawn;
  nlohmann::ordered_json like = sketch.like.empty() ? nlohmann::ordered_json() : like_place(sketch, sketch.like);
  if (!like.is_null()) like["file"] = s.in_work(like["file"].get<std::string>());  // as the page names it
  // Regions, blocks and lots the edits since the last generation left as they were are reused.
  auto city = std::make_shared<City>(build_city(sketch, clock, s.regions));
  GenerateResult result = write_city(sketch, *city, folder.staging(), clock, ExportOptions::before_answer());
  if (!like.is_null()) result.report["like"] = like;
  clock.run("tiles", [&] { write_city_tiles(*city, folder.staging() / "tiles"); });
  // The report's seconds are then the update's server time, tiles included, which the page
  // shows (validation's added when it ends); answer_s the server's time to the answer; and
  // what was reused, the tiles' meshes included (the first ask for them).
  result.report["timings_s"] = clock.seconds;
  result.report["answer_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.report["reused"] = reuse_report(*city->regions);
  write_report(result.report, folder.staging());
  std::shared_ptr<const City> before;  // freed after the locks, as the job's last work
  {
    // The folder and the city it holds change together: the downloads are written from it.
    std::unique_lock lock(s.outputs);
    folder.commit();
    fs::remove_all(s.render_folder());  // it showed the city before this one
    std::lock_guard city_lock(s.city_mutex);
    before = std::exchange(s.city, city);
  }
  progress.answered();
  before.reset();
  if (!geom::kernel_validates_its_output()) return;
  // Only this thread replaces the folder, so it stays as it is while validation reads it;
  // the downloads written meanwhile are files validation does not read.
  bool valid = false;
  try {
    valid = validate_written(*city, s.city_folder(), result.report, clock).valid;
  } catch (const Cancelled&) {
    // The report no longer says validation is under way.
    result.report["validation"] = {{"stopped", "cancelled before it ended; generate again to validate"}};
    write_report(result.report, s.city_folder());
    throw;
  }
  if (!valid) throw InternalError("the generated city failed validation (see report.json); please report this sketch");
}

// The city to render: the one generated in this run, else work/city's rebuilt (same sketch,
// same seed: the same city), as exacity render does.
std::shared_ptr<const City> city_to_render(ServerState& s, JobRunner::Progress& progress, int stages) {
  {
    std::lock_guard lock(s.city_mutex);
    if (s.city) return s.city;
  }
  std::string text;
  {
    std::shared_lock lock(s.outputs);
    text = read_file(s.city_folder() / "sketch.geojson");
  }
  const Sketch sketch = parse_sketch(text, s.sketch.file());
  StageClock clock([&](int i, int n, const std::string& stage) { progress.stage(i, n, stage); }, stages);
  auto city = std::make_shared<const City>(build_city(sketch, clock));
  std::lock_guard lock(s.city_mutex);
  if (!s.city) s.city = city;
  return city;
}

// The still (and overview and minimap) into work/render, written aside and swapped in.
void render_job(ServerState& s, const RenderAsk& ask, JobRunner::Progress& progress) {
  bool rebuilt = false;
  {
    std::lock_guard lock(s.city_mutex);
    rebuilt = !s.city;
  }
  const int stages = rebuilt ? kCityStages + 1 : 1;
  const std::shared_ptr<const City> city = city_to_render(s, progress, stages);
  render::RenderRequest r = render_request(*city, ask);
  const fs::path aside = s.work.root() / ".render.partial";
  fs::remove_all(aside);
  fs::create_directories(aside);
  r.still = aside / "still.png", r.overview_file = aside / "overview.png", r.minimap_file = aside / "minimap.png";
  // A render cancelled or failed leaves the previous still as it was, and nothing aside.
  try {
    progress.stage(stages, stages, "render");
    const nlohmann::ordered_json stats = render::render_city(
        *city, r, [&](const std::string& stage, double f) { progress.fraction("render " + stage, f); });
    std::ofstream(aside / "still.json", std::ios::binary) << stats.dump(2) << "\n";
  } catch (...) {
    fs::remove_all(aside);
    throw;
  }
  std::unique_lock lock(s.outputs);
  fs::remove_all(s.render_folder());
  fs::rename(aside, s.render_folder());
}

// `job` with its failure's message naming paths in the work folder as the refusals do.
JobRunner::Job in_work_folder(ServerState& s, JobRunner::Job job) {
  return [&s, job = std::move(job)](JobRunner::Progress& progress) {
    try {
      job(progress);
    } catch (const Cancelled&) {
      throw;
    } catch (const UserError& e) {
      throw UserError(s.in_work(e.what()));
    } catch (const std::exception& e) {
      throw std::runtime_error(s.in_work(e.what()));
    }
  };
}

// GET /api/events: each job event as a server-sent event; the status first, then what follows.
void stream_events(ServerState& s, httplib::Response& res) {
  if (++s.event_streams > ServerState::kMaxEventStreams) {
    --s.event_streams;
    return refuse(res, 503,
                  "too many event streams open (" + std::to_string(ServerState::kMaxEventStreams) +
                      "); close other pages of this server");
  }
  res.set_header("Cache-Control", "no-cache");
  struct Cursor {
    bool started = false;
    std::uint64_t after = 0;
    int quiet = 0;
  };
  auto cursor = std::make_shared<Cursor>();
  // The provider's last copy goes when the stream ends, however it ends.
  std::shared_ptr<void> open_stream(nullptr, [&s](void*) { --s.event_streams; });
  res.set_chunked_content_provider(
      "text/event-stream", [&s, cursor, open_stream](std::size_t, httplib::DataSink& sink) {
        auto send = [&](const std::string& text) { return sink.write(text.data(), text.size()); };
        if (!cursor->started) {
          cursor->started = true;
          cursor->after = s.jobs.last_event();
          return send("retry: 1000\nevent: state\ndata: " + s.jobs.status().to_json().dump() + "\n\n");
        }
        // Waits a second at most, so a stopping server is not held (httplib stops calling
        // once it shuts down).
        const std::vector<JobEvent> events = s.jobs.events_after(cursor->after, std::chrono::milliseconds(1000));
        for (const JobEvent& e : events) {
          cursor->after = e.id;
          if (!send("id: " + std::to_string(e.id) + "\nevent: " + e.name + "\ndata: " + e.data.dump() + "\n\n"))
            return false;
        }
        // A comment every few quiet seconds finds a closed page, whose thread is then freed.
        if (events.empty() && ++cursor->quiet % 5 == 0) return send(": waiting\n\n");
        return true;
      });
}

// The city's files offered to download as generate writes them, with their media types
// (GET /api/files/NAME; the status lists those there: city.osm only for a sketch with a CRS).
const std::vector<std::pair<std::string, std::string>>& city_files() {
  static const std::vector<std::pair<std::string, std::string>> files{
      {"city.glb", "model/gltf-binary"},     {"city.city.json", "application/city+json"},
      {"city.obj", "model/obj"},             {"city.ply", "application/octet-stream"},
      {"city.osm", "application/xml"},       {"city.gpkg", "application/geopackage+sqlite3"},
      {"map.svg", "image/svg+xml"}};
  return files;
}

// The files written only when first downloaded, and the call that writes them into a folder.
bool written_when_asked(const std::string& name) {
  static const std::set<std::string> names{"city.glb", "city.city.json", "city.obj", "city.ply", "city.gpkg"};
  return names.count(name) > 0;
}

// The city work/city holds: the one generated in this run, else rebuilt from its sketch (a
// server started on the work folder of another run).
std::shared_ptr<const City> folders_city(ServerState& s) {
  {
    std::lock_guard lock(s.city_mutex);
    if (s.city) return s.city;
  }
  StageClock clock(nullptr, kCityStages);
  auto city = std::make_shared<const City>(
      build_city(parse_sketch(read_file(s.city_folder() / "sketch.geojson"), s.sketch.file()), clock));
  std::lock_guard lock(s.city_mutex);
  if (!s.city) s.city = city;
  return s.city;
}

// Writes `name` into work/city if it is one written when asked and is not there yet; the
// caller holds s.outputs shared, so the folder and its city stay as they are. The 3D files
// are written together (one set of meshes), aside, then moved in.
void write_when_asked(ServerState& s, const std::string& name) {
  if (!written_when_asked(name) || fs::is_regular_file(s.city_folder() / name) ||
      !fs::is_regular_file(s.city_folder() / "report.json"))
    return;
  const std::shared_ptr<const City> city = folders_city(s);
  const fs::path aside = s.work.root() / ".downloads.partial";
  fs::remove_all(aside);
  fs::create_directories(aside);
  std::vector<std::string> files{name};
  if (name == "city.gpkg") {
    // From the layers the GeoJSON files were written from.
    const Layer clutter = clutter_layer(city->clutter.items, city->ground, city->model_library());
    write_vector_formats(vector_files(city->layers, clutter), aside, {"gpkg"}, city->settings.crs);
  } else {
    // The structures' meshes afresh: the cache is the job thread's.
    ThreeDFiles afresh;
    afresh.through_cache = false;
    write_3d_files(*city, aside, afresh);
    files = {"city.glb", "city.city.json", "city.obj", "city.ply"};
  }
  for (const std::string& file : files)
    if (!fs::exists(s.city_folder() / file)) fs::rename(aside / file, s.city_folder() / file);
  fs::remove_all(aside);
}

// A file of work/city, written first if it is written when asked.
void send_city_file(ServerState& s, const std::string& name, const std::string& type, httplib::Response& res,
                    const std::string& missing) {
  std::lock_guard writing(s.downloads);
  std::shared_lock lock(s.outputs);
  write_when_asked(s, name);
  if (!fs::is_regular_file(s.city_folder() / name)) return refuse(res, 404, missing);
  const std::string bytes = read_file(s.city_folder() / name);
  res.set_header("Cache-Control", "no-store");
  res.set_content(bytes, type.c_str());
}

const std::set<std::string>& layer_names() {
  static const std::set<std::string> names{"zones", "water", "roads", "road_areas", "blocks", "lots", "buildings"};
  return names;
}

}  // namespace

void add_city_routes(ServerState& s) {
  // A generation whose city is shown and which is still validating is stopped for this one,
  // which replaces its city (the page's update after each edit does not wait for it).
  s.http.Post("/api/generate", [&s](const httplib::Request&, httplib::Response& res) {
    if (const JobStatus now = s.jobs.status(); now.state == JobState::Running && !now.answered)
      return refuse_busy(s, res);
    Sketch sketch;
    try {
      sketch = s.sketch.load();
    } catch (const UserError& e) {
      return refuse(res, 400, s.in_work(e.what()));
    }
    auto shared = std::make_shared<Sketch>(std::move(sketch));
    if (!s.jobs.start("generate", in_work_folder(s, [&s, shared](JobRunner::Progress& p) { generate_job(s, *shared, p); }),
                      JobRunner::WhileRunning::ReplaceAnswered))
      return refuse_busy(s, res);
    res.status = 202;
    res.set_content(s.jobs.status().to_json().dump(), "application/json");
  });
  s.http.Post("/api/render", [&s](const httplib::Request& req, httplib::Response& res) {
    RenderAsk ask;
    try {
      ask = parse_render_ask(req.body, s.options.max_render);
    } catch (const UserError& e) {
      return refuse(res, 400, s.in_work(e.what()));
    }
    if (s.jobs.status().state == JobState::Running) return refuse_busy(s, res);
    bool have_city = false;
    {
      std::lock_guard lock(s.city_mutex);
      have_city = s.city != nullptr;
    }
    if (!have_city && !fs::is_regular_file(s.city_folder() / "sketch.geojson")) return refuse(res, 409, kNoCity);
    if (!s.jobs.start("render", in_work_folder(s, [&s, ask](JobRunner::Progress& p) { render_job(s, ask, p); })))
      return refuse_busy(s, res);
    res.status = 202;
    res.set_content(s.jobs.status().to_json().dump(), "application/json");
  });
  // Stops the running job within its stage (docs/design.md, Serving: cancelling); the status
  // turns "cancelled" once it has stopped.
  s.http.Post("/api/cancel", [&s](const httplib::Request&, httplib::Response& res) {
    if (!s.jobs.cancel()) return refuse(res, 409, "no job is running: nothing to cancel");
    res.status = 202;
    res.set_content(s.jobs.status().to_json().dump(), "application/json");
  });
  // The job's status, and whether a city and a render are there to fetch (the page asks
  // before fetching, so it never asks for what is not there).
  s.http.Get("/api/status", [&s](const httplib::Request&, httplib::Response& res) {
    nlohmann::json status = s.jobs.status().to_json();
    {
      std::shared_lock lock(s.outputs);
      status["city"] = fs::is_regular_file(s.city_folder() / "report.json");
      status["render"] = fs::is_regular_file(s.render_folder() / "still.png");
      status["files"] = nlohmann::json::array();
      for (const auto& [name, type] : city_files())
        if (fs::is_regular_file(s.city_folder() / name) || (status["city"] && written_when_asked(name)))
          status["files"].push_back(name);
    }
    res.set_header("Cache-Control", "no-store");
    res.set_content(status.dump(), "application/json");
  });
  s.http.Get("/api/events", [&s](const httplib::Request&, httplib::Response& res) { stream_events(s, res); });
  s.http.Get("/api/map.svg", [&s](const httplib::Request&, httplib::Response& res) {
    send_file(s, s.city_folder() / "map.svg", "image/svg+xml", res, kNoCity);
  });
  s.http.Get("/api/report", [&s](const httplib::Request&, httplib::Response& res) {
    send_file(s, s.city_folder() / "report.json", "application/json", res, kNoCity);
  });
  s.http.Get("/api/city.glb", [&s](const httplib::Request&, httplib::Response& res) {
    send_city_file(s, "city.glb", "model/gltf-binary", res, kNoCity);
  });
  s.http.Get(R"(/api/files/([a-z.]+))", [&s](const httplib::Request& req, httplib::Response& res) {
    const std::string name = req.matches[1];
    const auto file = std::find_if(city_files().begin(), city_files().end(), [&](const auto& f) { return f.first == name; });
    if (file == city_files().end()) {
      std::string names;
      for (const auto& [known, type] : city_files()) names += (names.empty() ? "" : ", ") + known;
      return refuse(res, 404, "no city file \"" + name + "\"; the files are " + names);
    }
    send_city_file(s, name, file->second, res,
                   name == "city.osm" ? kNoCity + " (city.osm needs a sketch with a CRS)" : kNoCity);
  });
  s.http.Get("/api/tiles.json", [&s](const httplib::Request&, httplib::Response& res) {
    send_file(s, s.city_folder() / "tiles" / "index.json", "application/json", res, kNoCity);
  });
  s.http.Get("/api/tiles/facades.json", [&s](const httplib::Request&, httplib::Response& res) {
    send_file(s, s.city_folder() / "tiles" / "facades.json", "application/json", res, kNoCity);
  });
  s.http.Get("/api/tiles/ground.glb", [&s](const httplib::Request&, httplib::Response& res) {
    send_file(s, s.city_folder() / "tiles" / "ground.glb", "model/gltf-binary", res, kNoCity);
  });
  // Digits only: a tile's name cannot leave the tiles folder.
  s.http.Get(R"(/api/tiles/([0-9]{1,4})_([0-9]{1,4})/([012])\.glb)", [&s](const httplib::Request& req,
                                                                          httplib::Response& res) {
    const std::string tile = std::string(req.matches[1]) + "_" + std::string(req.matches[2]);
    send_file(s, s.city_folder() / "tiles" / tile / (std::string(req.matches[3]) + ".glb"), "model/gltf-binary", res,
              "no tile " + tile + " at level " + std::string(req.matches[3]) + ": GET /api/tiles.json lists the tiles");
  });
  s.http.Get(R"(/api/layers/([^/]*)\.geojson)", [&s](const httplib::Request& req, httplib::Response& res) {
    const std::string name = req.matches[1];
    if (!layer_names().count(name))
      return refuse(
          res, 404,
          "no layer \"" + name + "\"; the layers are zones, water, roads, road_areas, blocks, lots, buildings");
    send_file(s, s.city_folder() / "vector" / (name + ".geojson"), "application/geo+json", res, kNoCity);
  });
  s.http.Get(R"(/api/render/(still|overview|minimap)\.png)", [&s](const httplib::Request& req, httplib::Response& res) {
    const std::string name = req.matches[1];
    send_file(
        s, s.render_folder() / (name + ".png"), "image/png", res,
        "no " + name + " rendered yet: POST /api/render" + (name == "still" ? "" : " with \"" + name + "\": true"));
  });
  s.http.Get("/api/render/still.json", [&s](const httplib::Request&, httplib::Response& res) {
    send_file(s, s.render_folder() / "still.json", "application/json", res, "nothing rendered yet: POST /api/render");
  });
}

}  // namespace exacity::serve
