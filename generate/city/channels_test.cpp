// Channels (docs/design.md, Placement): values read between pixel centres, clamped at the bounds, and the
// affinity that weighs a model by them.
#include <gtest/gtest.h>

#include <cmath>

#include "generate/city/channels.h"

using namespace exacity;

TEST(Channels, AOnePixelImageIsOneValueEverywhere) {
  const Channels c({{"wealth", "", {0, 0, 100, 50}}}, {GreyImage{1, 1, {0.75f}}}, 4);
  for (geom::Vec2 p : {geom::Vec2{0, 0}, geom::Vec2{50, 25}, geom::Vec2{100, 50}, geom::Vec2{-1e6, 1e6}})
    EXPECT_EQ(c.value(0, p), 0.75);
  EXPECT_EQ(c.index("wealth"), 0);
  EXPECT_EQ(c.index("downtown"), -1);
}

TEST(Channels, ValuesRunBetweenPixelCentresAndStopAtTheBounds) {
  // Two pixels, 0 west and 1 east, over 0..400: centres at 100 and 300.
  const Channels c({{"d", "", {0, 0, 400, 10}}}, {GreyImage{2, 1, {0.0f, 1.0f}}}, 4);
  EXPECT_EQ(c.value(0, {0, 5}), 0);
  EXPECT_EQ(c.value(0, {100, 5}), 0);
  EXPECT_EQ(c.value(0, {200, 5}), 0.5);
  EXPECT_EQ(c.value(0, {300, 5}), 1);
  EXPECT_EQ(c.value(0, {900, 5}), 1);
}

TEST(Channels, AffinityIsOneMinusTheMeanDifferenceToTheSharpness) {
  const Channels c({{"a", "", {0, 0, 1, 1}}, {"b", "", {0, 0, 1, 1}}},
                   {GreyImage{1, 1, {0.5f}}, GreyImage{1, 1, {1.0f}}}, 2);
  EXPECT_EQ(c.affinity({}, {0, 0}), 1);  // no values: unaffected
  EXPECT_EQ(c.affinity({{"a", 0.5}}, {0, 0}), 1);
  EXPECT_EQ(c.affinity({{"a", 0.0}}, {0, 0}), 0.25);                 // (1 - 0.5)^2
  EXPECT_EQ(c.affinity({{"a", 0.5}, {"b", 0.0}}, {0, 0}), 0.25);     // mean |difference| 0.5
  EXPECT_EQ(c.affinity({{"b", 0.0}}, {0, 0}), 0);                   // as far as can be: no weight
}
