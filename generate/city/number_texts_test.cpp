#include "generate/city/number_texts.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "generate/city/format_number.h"

namespace exacity {
namespace {

// The remembered texts are append_number's, character for character, whether a double is
// met for the first time, again, or after another with the same slot took its place: over
// the doubles the writers meet (coordinates, whole numbers, -0) and any bit pattern at all
// (subnormals, infinities, NaNs, the largest and smallest).
TEST(NumberTexts, WritesWhatAppendNumberWrites) {
  std::vector<double> values = {0.0,
                                -0.0,
                                1.0,
                                -1.0,
                                0.1,
                                1e-300,
                                -1e-300,
                                5e-324,
                                1e300,
                                1e21,
                                1e22,
                                123456789012345680.0,
                                4503599627370496.5,
                                std::numeric_limits<double>::max(),
                                std::numeric_limits<double>::lowest(),
                                std::numeric_limits<double>::min(),
                                std::numeric_limits<double>::denorm_min(),
                                std::numeric_limits<double>::infinity(),
                                -std::numeric_limits<double>::infinity(),
                                std::numeric_limits<double>::quiet_NaN()};
  std::mt19937_64 random(37);
  std::uniform_real_distribution<double> metres(-5000, 5000);
  std::uniform_int_distribution<int> whole(-100000, 100000), exponent(-320, 310);
  for (int i = 0; i < 20000; ++i) {
    values.push_back(metres(random));
    values.push_back(std::round(metres(random) * 1000) / 1000);  // millimetres, as sketches give them
    values.push_back(whole(random));
    values.push_back(std::ldexp(metres(random), exponent(random)));
    values.push_back(std::bit_cast<double>(random()));
  }
  // Each again, in a different order, so texts are found as well as made, and slots reused.
  std::vector<double> again = values;
  std::shuffle(again.begin(), again.end(), random);
  values.insert(values.end(), again.begin(), again.end());
  NumberTexts texts;
  std::string remembered, made;
  for (double v : values) {
    remembered.clear(), made.clear();
    texts.append(remembered, v);
    append_number(made, v);
    ASSERT_EQ(remembered, made) << "bits " << std::bit_cast<std::uint64_t>(v);
  }
  remembered.clear();
  texts.append(remembered, -0.0);
  EXPECT_EQ(remembered, "0");
}

}  // namespace
}  // namespace exacity
