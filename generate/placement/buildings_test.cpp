// Buildings and placed models share one numbering: for_each_by_id visits them in it.
#include "generate/placement/buildings.h"

#include <gtest/gtest.h>

#include <string>

namespace exacity {
namespace {

TEST(Structures, ForEachByIdVisitsBuildingsAndModelsInIdOrder) {
  std::vector<Building> buildings(3);
  std::vector<ModelInstance> models(4);
  for (auto [i, id] : {std::pair{0, 0}, {1, 1}, {2, 5}}) buildings[i].id = id;
  for (auto [i, id] : {std::pair{0, 2}, {1, 3}, {2, 4}, {3, 6}}) models[i].id = id;
  std::string order;
  for_each_by_id(
      buildings, models, [&](const Building& b) { order += "b" + std::to_string(b.id); },
      [&](const ModelInstance& m) { order += "m" + std::to_string(m.id); });
  EXPECT_EQ(order, "b0b1m2m3m4b5m6");
  order.clear();
  for_each_by_id({}, models, [&](const Building&) { order += "b"; }, [&](const ModelInstance&) { order += "m"; });
  EXPECT_EQ(order, "mmmm");
}

}  // namespace
}  // namespace exacity
