// A city generated as a plan's tasks, as a Slurm job array (docs/design.md, Plans: a city
// across a cluster). `exacity plan` checks the sketch and writes PLAN/plan.json; each task
// computes its share of the items a build keeps by their input (generate/regenerate.h's
// RegionCache: the regions' road plans, the blocks' lot plans, the lots' structures) in three
// steps, each step's tasks reading every task's items of the steps before; `exacity merge`
// loads them all into the cache of one ordinary build, which then reuses rather than
// computes them. The merged city is therefore the bytes `exacity generate` writes.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "generate/sketch/sketch.h"

namespace exacity {

struct RegionCache;  // generate/regenerate.h

// The steps, in order: what one task computes in each, reading the items of the steps before.
enum class PlanStep { Roads, Lots, Buildings };
inline constexpr PlanStep kPlanSteps[] = {PlanStep::Roads, PlanStep::Lots, PlanStep::Buildings};
const char* step_name(PlanStep step);  // "roads", "lots", "buildings"

struct Plan {
  std::vector<std::filesystem::path> sketch;  // the sketch's files, absolute
  // What generate takes besides the sketch, absolute (empty: none): --buildings' files,
  // --models' library, and the place --like measures (--like's, else the sketch's own).
  std::vector<std::filesystem::path> buildings;
  std::filesystem::path models, like;
  int tasks = 1;
  // What the plan is of: the program's version, the sketch's files and every file they
  // name (Sketch::settings_text, shared_input). A task's items carry it; another means
  // another plan, or the sketch changed since.
  std::string id;
};

// Reads the sketch as generate would with `given`'s buildings, models and like (refusing
// what it refuses), and writes PLAN/plan.json for `given.tasks` tasks. PLAN must not exist
// or be an empty folder.
Plan write_plan(const Plan& given, const std::filesystem::path& plan);

// Reads PLAN/plan.json and the sketch it names, with the plan's buildings and models; refuses
// (UserError) a plan that is not one, or whose sketch or files changed since. The caller
// measures plan.like into the sketch (like_place), as generate does, before building.
Plan read_plan(const std::filesystem::path& plan, Sketch& sketch);

// Task `task`'s share of `step`: builds the city as far as the step needs, from every
// task's items of the steps before, computing only this task's items of this step, and
// writes them to PLAN/tasks/TASK/STEP.items. Returns how many it wrote.
int run_plan_task(const std::filesystem::path& plan, int task, PlanStep step);

// A cache holding every task's items of every step, for the build that merges them.
// Refuses with one line a plan with a task's items missing, of another plan, or stale.
std::shared_ptr<RegionCache> merged_cache(const std::filesystem::path& plan, const Plan& read, const Sketch& sketch);

}  // namespace exacity
