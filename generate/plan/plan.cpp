#include "generate/plan/plan.h"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "generate/errors.h"
#include "generate/pipeline.h"
#include "generate/plan/memo_text.h"
#include "generate/regenerate.h"
#include "generate/sketch/like_place.h"
#include "generate/version.h"

namespace exacity {
namespace fs = std::filesystem;

namespace {

constexpr const char* kPlanFile = "plan.json";
constexpr const char* kPlanFormat = "exacity plan 1";

std::string file_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string hex_id(std::uint64_t id) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(id));
  return text;
}

// The plan's id: the version, the task count, the names and bytes of the sketch's files,
// the footprints' and the place like measures, and what every item reads besides its own
// input (shared_input: the settings and the named files' sizes and times).
std::string plan_id(const Plan& plan, const Sketch& sketch) {
  std::string text = std::string(kVersion) + " tasks " + std::to_string(plan.tasks) + " ";
  for (const fs::path& file : plan.sketch) text += file.string() + " " + file_bytes(file) + " ";
  for (const fs::path& file : plan.buildings) text += "buildings " + file.string() + " " + file_bytes(file) + " ";
  if (!plan.like.empty()) text += "like " + plan.like.string() + " " + file_bytes(plan.like) + " ";
  text += shared_input(sketch);
  return hex_id(content_id(text));
}

fs::path items_file(const fs::path& plan, int task, PlanStep step) {
  return plan / "tasks" / std::to_string(task) / (std::string(step_name(step)) + ".items");
}

// The start of a task's items' first line: whose they are. The line ends with the items'
// content id: items changed on the way (storage, a copy) may still read as items, and
// would be merged into another city.
std::string items_owner(const Plan& plan, int task, PlanStep step) {
  return "exacity plan items; plan " + plan.id + "; task " + std::to_string(task) + " of " +
         std::to_string(plan.tasks) + "; step " + step_name(step) + "; content ";
}

// Every task's items of `step` into the cache.
void load_step(const fs::path& dir, const Plan& plan, PlanStep step, RegionCache& cache) {
  for (int task = 0; task < plan.tasks; ++task) {
    const fs::path file = items_file(dir, task, step);
    if (!fs::exists(file))
      throw UserError(file.string() + ": missing: task " + std::to_string(task) + " has not run step " +
                      step_name(step) + "; run exacity plan-task " + dir.string() + " --task " + std::to_string(task) +
                      " --step " + step_name(step));
    const std::string text = file_bytes(file);
    const std::string owner = items_owner(plan, task, step);
    if (text.compare(0, owner.size(), owner) != 0)
      throw UserError(file.string() + ": not this plan's task " + std::to_string(task) + " (another plan's, or the " +
                      "sketch changed since it ran); run that task's step " + step_name(step) + " again");
    const std::size_t end = text.find('\n', owner.size());
    const std::string_view items = std::string_view(text).substr(end == std::string::npos ? text.size() : end + 1);
    if (end == std::string::npos || text.substr(owner.size(), end - owner.size()) != hex_id(content_id(items)))
      throw UserError(file.string() + ": damaged (its items are not the ones its task wrote); run that task's step " +
                      step_name(step) + " again");
    try {
      switch (step) {
        case PlanStep::Roads: read_memo_text(items, cache.road_plans); break;
        case PlanStep::Lots: read_memo_text(items, cache.lot_plans); break;
        case PlanStep::Buildings: read_memo_text(items, cache.placements); break;
      }
    } catch (const std::invalid_argument& e) {
      throw UserError(file.string() + ": damaged (" + e.what() + "); run that task's step " + step_name(step) + " again");
    }
  }
}

// Thrown at the first stage past a task's step: the build has computed what the step asks.
struct StepDone {};

}  // namespace

const char* step_name(PlanStep step) {
  switch (step) {
    case PlanStep::Roads: return "roads";
    case PlanStep::Lots: return "lots";
    case PlanStep::Buildings: return "buildings";
  }
  return "";
}

Plan write_plan(const Plan& given, const fs::path& dir) {
  if (given.tasks < 1) throw UserError("--tasks " + std::to_string(given.tasks) + ": give 1 or more tasks");
  if (fs::exists(dir) && !(fs::is_directory(dir) && fs::is_empty(dir)))
    throw UserError(dir.string() + ": exists and is not an empty folder; give a new folder for the plan with -o");
  const auto absolute = [](const fs::path& file) { return file.empty() ? file : fs::absolute(file).lexically_normal(); };
  Plan plan;
  for (const fs::path& file : given.sketch) plan.sketch.push_back(absolute(file));
  for (const fs::path& file : given.buildings) plan.buildings.push_back(absolute(file));
  plan.models = absolute(given.models);
  Sketch sketch = load_sketch(plan.sketch, true, plan.models, plan.buildings);
  plan.like = absolute(given.like.empty() ? sketch.like : given.like);
  plan.tasks = given.tasks;
  plan.id = plan_id(plan, sketch);
  // Measured here once, so that a place too small to measure is refused now, not by every task.
  if (!plan.like.empty()) like_place(sketch, plan.like);
  nlohmann::ordered_json json{{"format", kPlanFormat}, {"version", kVersion}, {"id", plan.id}, {"tasks", plan.tasks}};
  for (const fs::path& file : plan.sketch) json["sketch"].push_back(file.string());
  json["buildings"] = nlohmann::ordered_json::array();
  for (const fs::path& file : plan.buildings) json["buildings"].push_back(file.string());
  json["models"] = plan.models.string();
  json["like"] = plan.like.string();
  json["steps"] = nlohmann::ordered_json::array();
  for (PlanStep step : kPlanSteps) json["steps"].push_back(step_name(step));
  fs::create_directories(dir / "tasks");
  std::ofstream(dir / kPlanFile, std::ios::binary) << json.dump(2) << "\n";
  return plan;
}

Plan read_plan(const fs::path& dir, Sketch& sketch) {
  const fs::path file = dir / kPlanFile;
  Plan plan;
  try {
    const auto json = nlohmann::json::parse(file_bytes(file));
    if (json.at("format") != kPlanFormat) throw std::invalid_argument("format");
    for (const auto& path : json.at("sketch")) plan.sketch.push_back(path.get<std::string>());
    for (const auto& path : json.value("buildings", nlohmann::json::array())) plan.buildings.push_back(path.get<std::string>());
    plan.models = json.value("models", std::string());
    plan.like = json.value("like", std::string());
    plan.tasks = json.at("tasks").get<int>();
    plan.id = json.at("id").get<std::string>();
    if (plan.tasks < 1 || plan.sketch.empty()) throw std::invalid_argument("tasks");
  } catch (const std::exception&) {
    throw UserError(file.string() + ": not a plan of exacity plan (missing or unreadable); make one with exacity plan SKETCH -o " +
                    dir.string());
  }
  sketch = load_sketch(plan.sketch, true, plan.models, plan.buildings);
  if (plan_id(plan, sketch) != plan.id)
    throw UserError(file.string() + ": the sketch, a file it names or the program changed since this plan was made; "
                    "make the plan again with exacity plan");
  return plan;
}

int run_plan_task(const fs::path& dir, int task, PlanStep step) {
  Sketch sketch;
  const Plan plan = read_plan(dir, sketch);
  if (task < 0 || task >= plan.tasks)
    throw UserError("--task " + std::to_string(task) + ": the plan has tasks 0 to " + std::to_string(plan.tasks - 1));
  // The zone parameters generate takes from the place, so the items are generate's.
  if (!plan.like.empty()) like_place(sketch, plan.like);
  auto cache = std::make_shared<RegionCache>();
  cache->next_build(sketch);
  for (PlanStep before : kPlanSteps) {
    if (before == step) break;
    load_step(dir, plan, before, *cache);
  }
  // An item is the task's by its key, whatever region it lies in: every task builds the
  // whole map up to its step anyway, so nearness buys nothing, and keys spread evenly.
  const auto n = static_cast<std::uint64_t>(plan.tasks);
  const auto mine = [n, task](const std::string& key) { return content_id(key) % n == static_cast<std::uint64_t>(task); };
  // The other tasks' lots get no structures here, so the buildings stage would merge them
  // into their neighbours and place again (build_on_lots): a lot asked for twice means that
  // second pass has begun, and this task's lots were all placed in the first.
  std::mutex asked_mutex;
  std::set<std::string> asked;
  std::string stop;
  switch (step) {
    case PlanStep::Roads:
      // A growth region's plan says whether its one piece reaches a sketch road.
      cache->road_plans.others = [&](const std::string& key) {
        RoadPlan none;
        none.piece_reaches_sketch = {0};
        return mine(key) ? std::nullopt : std::optional(none);
      };
      stop = "blocks";
      break;
    case PlanStep::Lots:
      cache->lot_plans.others = [&](const std::string& key) {
        return mine(key) ? std::nullopt : std::optional(std::vector<PlannedLot>());
      };
      stop = "buildings";
      break;
    case PlanStep::Buildings:
      cache->placements.others = [&](const std::string& key) -> std::optional<Structures> {
        if (mine(key)) return std::nullopt;
        const std::lock_guard lock(asked_mutex);
        if (!asked.insert(key).second) throw StepDone{};
        return Structures();
      };
      stop = "ground";
      break;
  }
  StageClock clock([&](int, int, const std::string& stage) {
    if (stage == stop) throw StepDone{};
  }, kCityStages);
  try {
    build_city(sketch, clock, cache);
  } catch (const StepDone&) {
  }
  std::string items;
  int count = 0;
  auto write = [&](const auto& memo) {
    memo.for_each([&](const std::string&, const auto&) { ++count; });
    items = memo_text(memo);
  };
  switch (step) {
    case PlanStep::Roads: write(cache->road_plans); break;
    case PlanStep::Lots: write(cache->lot_plans); break;
    case PlanStep::Buildings: write(cache->placements); break;
  }
  // Written aside and renamed, so a merge never reads half a file.
  const fs::path file = items_file(dir, task, step);
  fs::create_directories(file.parent_path());
  const fs::path aside = file.string() + ".part";
  {
    std::ofstream out(aside, std::ios::binary);
    out << items_owner(plan, task, step) << hex_id(content_id(items)) << "\n" << items;
    if (!out) throw UserError(aside.string() + ": could not be written (disk full?); run the task again");
  }
  fs::rename(aside, file);
  return count;
}

std::shared_ptr<RegionCache> merged_cache(const fs::path& dir, const Plan& plan, const Sketch& sketch) {
  auto cache = std::make_shared<RegionCache>();
  cache->next_build(sketch);
  for (PlanStep step : kPlanSteps) load_step(dir, plan, step, *cache);
  return cache;
}

}  // namespace exacity
