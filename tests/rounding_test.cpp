// Sketches the city fuzz target and the robustness benchmark found whose exports rounding
// left invalid: far from the origin, turned, with vertices shared or a few ulps apart, or
// lines nearer each other than a double's step. Each must now give a city the exact
// validator accepts.
#include <gtest/gtest.h>

#include <fstream>

#include "generate/pipeline.h"
#include "generate/export/validate.h"
#include "tests/test_util.h"

using namespace exacity;

namespace {

struct FuzzFinding {
  const char* name;
  const char* what;
  const char* sketch;
};

const FuzzFinding kFindings[] = {
    {"finding8", "a park ring folded along one line at x = 1e9: its zone rounded into a ring that crossed itself",
     R"({"exacity":{"seed":1410,"zones":{"park":{"block_area":1000000000.0,"jitter":180.0,"lots":"allocation","min_block_width":10000.0,"setback":1000.0}}},"features":[{"geometry":{"coordinates":[[[1000000019.7976935,123.47038109850632],[1000000083.4881887,131.13130572437348],[1000000083.4881887,131.1313057243735],[1000000051.6697032,127.3040624487584],[1000000068.7145735,129.3542814944225],[1000000026.2573136,124.24736772006467],[1000000035.6517493,125.37736463075046],[1000000019.7976935,123.47038109850632]]],"type":"Polygon"},"properties":{"zone":"park"},"type":"Feature"}],"type":"FeatureCollection"})"},
    {"finding9", "two zones sharing vertices at (1e9, -7e9): grown roads ended off the zone edge once rounded",
     R"({"exacity":{"seed":0},"features":[{"geometry":{"coordinates":[[[1000000295.8383934,-6999999765.182116],[1000000114.1155972,-7000000036.434003],[1000000295.8383934,-6999999765.182116],[1000000295.8383934,-6999999765.182116],[1000000295.8383934,-6999999765.182116],[1000000295.8383934,-6999999765.182116],[1000000114.117647,-6999999885.882353],[1000000295.8383934,-6999999765.182116]]],"type":"Polygon"},"properties":{"zone":"commercial"},"type":"Feature"},{"geometry":{"coordinates":[[[1000000114.117647,-6999999885.882353],[1000000114.117647,-6999999885.882353],[1000000114.117647,-6999999885.882353],[1000000239.6738584,-6999999883.879541],[999999700.0,-7000000300.0],[1000000114.117647,-6999999885.882353]]],"type":"Polygon"},"properties":{"zone":"residential"},"type":"Feature"}],"type":"FeatureCollection"})"},
    {"finding14", "two highways through one vertex beside water at (1e9, 3.5e6): rounded centre lines met between vertices",
     R"({"exacity":{"seed":0},"features":[{"geometry":{"coordinates":[[[1000000082.6460255,3499708.016892994],[999999909.3948283,3499694.6008996125],[1000000051.1377335,3500294.158563186],[999999909.3948283,3499694.6008996125],[999999909.3948283,3499694.6008996125],[1000000082.6460255,3499708.016892994]]],"type":"Polygon"},"properties":{"zone":"residential"},"type":"Feature"},{"geometry":{"coordinates":[[[1000000082.6460255,3499708.016892994],[999999909.3948283,3499694.6008996125],[1000000319.6344491,3500002.874328788],[1000000051.1377335,3500294.158563186],[1000000082.6460255,3499708.016892994]]],"type":"Polygon"},"properties":{"zone":"water"},"type":"Feature"},{"geometry":{"coordinates":[[999999909.3948283,3499694.6008996125],[1000000319.6344491,3500002.874328788]],"type":"LineString"},"properties":{"road":"highway","width":3.0},"type":"Feature"},{"geometry":{"coordinates":[[1000000155.5464001,3499879.570817876],[999999755.4050481,3500179.6691168225],[999999909.3948283,3499694.6008996125],[1000000000.0,3499575.7359312885]],"type":"LineString"},"properties":{"road":"highway","width":0.5},"type":"Feature"}],"type":"FeatureCollection"})"},
    {"finding22", "three zones at (-7e9, 1e9) meeting at a vertex: a block pinched in two by rounding (two block ids; its lots name theirs)",
     R"({"exacity":{"seed":0},"features":[{"geometry":{"coordinates":[[[-6999999799.055381,1000000051.7074765],[-7000000199.267749,999999979.9469131],[-7000000109.807621,999999590.1923789],[-7000000109.807621,999999590.1923789],[-7000000109.807621,999999590.1923789],[-6999999799.055381,1000000051.7074765]]],"type":"Polygon"},"properties":{"zone":"residential"},"type":"Feature"},{"geometry":{"coordinates":[[[-6999999798.726285,999999806.579876],[-7000000018.628743,1000000176.8458557],[-7000000128.847116,999999673.1425145],[-6999999798.726285,999999806.579876]]],"type":"Polygon"},"properties":{"zone":"commercial"},"type":"Feature"},{"geometry":{"coordinates":[[[-7000000005.7714,999999904.1392429],[-6999999904.042572,999999983.908671],[-7000000109.807621,999999590.1923789],[-7000000109.807621,999999590.1923789],[-7000000109.807621,999999590.1923789],[-7000000005.7714,999999904.1392429]]],"type":"Polygon"},"properties":{"zone":"residential"},"type":"Feature"}],"type":"FeatureCollection"})"},
    {"finding4", "two residential rings sharing an edge at (1e5, 1e9) with setback 0: rounded zones overlapped",
     R"({"exacity":{"seed":5126,"zones":{"commercial":{"block_area":1000000000.0,"jitter":180.0,"setback":0.0}}},"features":[{"geometry":{"coordinates":[[[99952.43960478825,1000000163.0757262],[100045.60819298503,999999800.808701],[100002.15594140546,999999969.763906],[99953.86041162227,1000000157.551209],[99952.43960478825,1000000163.0757262]]],"type":"Polygon"},"properties":{"zone":"residential"},"type":"Feature"},{"geometry":{"coordinates":[[[100045.60819298503,999999800.808701],[100026.34054291643,999999875.7270229],[100002.15594140546,999999969.763906],[100037.8969761743,999999830.7921926],[99921.28121958107,1000000185.8999572],[99969.7254803103,1000000095.86313],[100045.60819298503,999999800.808701]]],"type":"Polygon"},"properties":{"zone":"residential"},"type":"Feature"}],"type":"FeatureCollection"})"},
    {"thin_angle", "a highway and a main road leaving one point 1e-11 rad apart: rounded, the main road's first "
                   "73 um ran along the highway's",
     R"({"exacity":{"version":1,"seed":4562442215541141},"features":[{"type":"Feature","properties":{"zone":"residential"},"geometry":{"type":"Polygon","coordinates":[[[0.0,0.0],[500.0,0.0],[500.0,400.0],[0.0,400.0],[0.0,0.0]]]}},{"type":"Feature","properties":{"road":"highway","width":18.0},"geometry":{"type":"LineString","coordinates":[[-348.6934320756883,225.6823192514458],[851.3065679243117,225.6823192514458]]}},{"type":"Feature","properties":{"road":"main","width":10.0},"geometry":{"type":"LineString","coordinates":[[-348.6934320756883,225.6823192454458],[851.3065679243117,225.68231925744578]]}}],"type":"FeatureCollection"})"},
};

void PrintTo(const FuzzFinding& f, std::ostream* os) { *os << f.name; }

class RoundedExports : public testing::TestWithParam<FuzzFinding> {};

}  // namespace

TEST_P(RoundedExports, PassTheValidator) {
  const FuzzFinding& f = GetParam();
  auto dir = testing_util::temp_dir(std::string("rounding-") + f.name);
  std::ofstream(dir / "in.geojson") << f.sketch;
  std::filesystem::create_directories(dir / "out");
  auto result = generate_city(load_sketch(dir / "in.geojson"), dir / "out", nullptr);
  Validation v = validate_output(dir / "out");
  EXPECT_TRUE(result.valid) << f.what;
  EXPECT_TRUE(v.ok()) << f.what << ": " << (v.problems.empty() ? "" : v.problems[0]);
}

INSTANTIATE_TEST_SUITE_P(FuzzFindings, RoundedExports, testing::ValuesIn(kFindings),
                         [](const testing::TestParamInfo<FuzzFinding>& info) { return std::string(info.param.name); });
