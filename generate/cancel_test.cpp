// A cancelled build stops inside the stage under way (generate/cancel.h): the flag is set as a
// stage begins, and the build throws Cancelled before that stage returns.
#include "generate/cancel.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <chrono>
#include <fstream>
#include <string>
#include <thread>

#include "generate/cancellable_invoke.h"
#include "generate/errors.h"
#include "generate/export/cancellable_file.h"
#include "generate/pipeline.h"
#include "tests/test_util.h"

namespace exacity {
namespace {

// Two zones across a highway (tests/serve_test.cpp's small sketch).
const char* kSketch = R"({"type": "FeatureCollection", "exacity": {"seed": 3}, "features": [
  {"type": "Feature", "properties": {"zone": "residential"},
   "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [400, 0], [400, 300], [0, 300], [0, 0]]]}},
  {"type": "Feature", "properties": {"zone": "commercial"},
   "geometry": {"type": "Polygon", "coordinates": [[[400, 0], [600, 0], [600, 300], [400, 300], [400, 0]]]}},
  {"type": "Feature", "properties": {"road": "highway", "width": 16},
   "geometry": {"type": "LineString", "coordinates": [[-50, 150], [650, 150]]}}]})";

// Builds and writes the city into `dir`/out, setting the flag as `stage` begins; the last
// stage begun when the build ended, and whether it ended by Cancelled.
std::pair<std::string, bool> cancel_at(const std::string& stage, const std::filesystem::path& dir) {
  std::ofstream(dir / "sketch.geojson") << kSketch;
  const Sketch sketch = load_sketch(dir / "sketch.geojson");
  std::atomic<bool> flag{false};
  const CancelScope scope(flag);
  std::string last;
  StageClock clock(
      [&](int, int, const std::string& name) {
        last = name;
        if (name == stage) flag = true;
      },
      kCityStages + kWriteStages);
  try {
    const City city = build_city(sketch, clock);
    std::filesystem::create_directory(dir / "out");
    write_city(sketch, city, dir / "out", clock);
  } catch (const Cancelled&) {
    return {last, true};
  }
  return {last, false};
}

std::pair<std::string, bool> cancel_at(const std::string& stage) {
  return cancel_at(stage, testing_util::temp_dir("cancel_" + std::to_string(std::hash<std::string>()(stage))));
}

TEST(Cancel, TheLongStagesStopWithinThemselves) {
  for (const char* stage : {"road network", "lots", "buildings", "vector layers", "3d export"}) {
    const auto [last, cancelled] = cancel_at(stage);
    EXPECT_TRUE(cancelled) << stage;
    EXPECT_EQ(last, stage);
  }
}

// The exports and the validation stop within their first feature: a cancelled export
// writes none of its features, and a cancelled validation leaves no report.
TEST(Cancel, TheExportsAndTheValidationStopWithinThemselves) {
  for (const char* stage : {"export", "validation"}) {
    const std::filesystem::path dir = testing_util::temp_dir(std::string("cancel_writing_") + stage);
    const auto [last, cancelled] = cancel_at(stage, dir);
    EXPECT_TRUE(cancelled) << stage;
    EXPECT_EQ(last, stage);
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "report.json")) << stage;
    if (std::string(stage) != "export") continue;
    // The first layer written holds no feature, and the map is not begun.
    std::ifstream zones(dir / "out" / "vector" / "zones.geojson");
    const std::string text((std::istreambuf_iterator<char>(zones)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text.find("\"Feature\""), std::string::npos) << text.substr(0, 200);
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "map.svg"));
  }
}

TEST(Cancel, NothingStopsWithoutAScopeOrWithTheFlagDown) {
  EXPECT_NO_THROW(CancelCheck().check());
  std::atomic<bool> flag{false};
  {
    const CancelScope scope(flag);
    EXPECT_NO_THROW(CancelCheck().check());
    flag = true;
    EXPECT_THROW(CancelCheck().check(), Cancelled);
  }
  EXPECT_NO_THROW(CancelCheck().check());  // the scope ended: this thread checks no flag
}

TEST(Cancel, ACheckTakesItsThreadsFlagToOtherThreads) {
  std::atomic<bool> flag{true};
  const CancelScope scope(flag);
  const CancelCheck check;
  bool thrown = false;
  std::thread([&] {
    try {
      check.check();
    } catch (const Cancelled&) {
      thrown = true;
    }
  }).join();
  EXPECT_TRUE(thrown);
}

// Work run at once on TBB's threads checks the flag of the thread that started it: once
// cancelled, no piece begins, on whichever thread it would have run.
TEST(Cancel, PiecesRunAtOnceTakeTheStartingThreadsFlag) {
  const tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
  std::atomic<bool> flag{true};
  const CancelScope scope(flag);
  std::atomic<int> begun{0};
  auto piece = [&] {
    ++begun;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  };
  EXPECT_THROW(for_each_cancellable(64, [&](std::size_t) { piece(); }), Cancelled);
  EXPECT_THROW(invoke_cancellable(piece, piece, piece, piece), Cancelled);
  EXPECT_EQ(begun.load(), 0);
  flag = false;
  for_each_cancellable(64, [&](std::size_t) { piece(); });
  EXPECT_EQ(begun.load(), 64);
}

// Pieces made at once are written in their order, whatever the thread count and however
// long each takes to make; none is made once the starting thread's flag is up.
TEST(Cancel, PiecesMadeAtOnceAreWrittenInOrderAndTakeTheStartingThreadsFlag) {
  for (int threads : {1, 2}) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    std::string written;
    make_in_order<std::string>(
        40,
        [](std::size_t i, std::string& piece) {
          // The early pieces take longest, so later ones are made first with two threads.
          std::this_thread::sleep_for(std::chrono::microseconds(i < 8 ? 3000 : 100));
          piece = std::to_string(i) + ",";
        },
        [&](const std::string& piece) { written += piece; });
    std::string expected;
    for (int i = 0; i < 40; ++i) expected += std::to_string(i) + ",";
    EXPECT_EQ(written, expected) << threads << " thread(s)";
  }
  const tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
  std::atomic<bool> flag{true};
  const CancelScope scope(flag);
  std::atomic<int> made{0};
  EXPECT_THROW(make_in_order<int>(16, [&](std::size_t, int&) { ++made; }, [](int) {}), Cancelled);
  EXPECT_EQ(made.load(), 0);
}

// A document written in one call stops within its first 64 KiB once cancelled, and a file
// that cannot be written is a UserError, not a stream quietly gone bad.
TEST(Cancel, AFileWrittenInOneCallStopsWithinIt) {
  nlohmann::json doc = nlohmann::json::array();
  for (int i = 0; i < 100000; ++i) doc.push_back({{"id", i}, {"name", "feature " + std::to_string(i)}});
  const std::filesystem::path dir = testing_util::temp_dir("cancel_file");
  std::atomic<bool> flag{false};
  const CancelScope scope(flag);
  {
    CancellableFile whole(dir / "whole.json");
    whole << doc;
    whole.close();
  }
  EXPECT_EQ(std::filesystem::file_size(dir / "whole.json"), doc.dump().size());
  flag = true;
  {
    CancellableFile cut(dir / "cut.json");
    EXPECT_THROW(cut << doc, Cancelled);
  }
  EXPECT_LT(std::filesystem::file_size(dir / "cut.json"), 1u << 16);
  flag = false;
  CancellableFile full("/dev/full");
  EXPECT_THROW(
      {
        full << doc;
        full.close();
      },
      UserError);
}

}  // namespace
}  // namespace exacity
