// Textured models end to end (docs/design.md, Textured models): a library of boxes whose
// sides carry a 2 x 2 checker through map_Kd, generated into a small city; city.glb holds the
// image once with the corners' texture coordinates, CityJSON's appearance names it, a
// render shows the checker's colours
// where the boxes are seen, and a missing or unreadable texture stops the run with one line.
#include <set>
#include <sstream>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <tiny_gltf.h>

#include "tests/cli_util.h"
#include "tests/test_util.h"

using namespace cli_util;

namespace {

void write(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

// A 2 x 2 checker of red and blue: no green anywhere, so green in a render is light that
// did not come from the texture.
void write_checker(const fs::path& file) {
  const std::vector<std::uint8_t> rgb{255, 0, 0, 0, 0, 255, 0, 0, 255, 255, 0, 0};
  auto out = OIIO::ImageOutput::create(file.string());
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(file.string(), OIIO::ImageSpec(2, 2, 3, OIIO::TypeDesc::UINT8)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, rgb.data()));
  out->close();
}

// A box w x w x h (m), Z-up, on z = 0. Each side spans the image's width and half its
// height (vt 1-4), the top shows one point of it (vt 5), the bottom has no vt.
std::string textured_box(double w, double h) {
  std::string s = "mtllib box.mtl\n";
  for (int k = 0; k < 8; ++k)
    s += "v " + std::to_string((k & 1 ? 0.5 : -0.5) * w) + " " + std::to_string((k & 2 ? 0.5 : -0.5) * w) + " " +
         std::to_string(k & 4 ? h : 0) + "\n";
  return s + "vt 0 0\nvt 1 0\nvt 1 0.5\nvt 0 0.5\nvt 0.75 0.75\nusemtl checker\n" +
         "f 1 3 4 2\nf 5/5 6/5 8/5 7/5\nf 1/1 2/2 6/3 5/4\nf 2/1 4/2 8/3 6/4\nf 4/1 3/2 7/3 8/4\nf 3/1 1/2 5/3 7/4\n";
}

// Two box models sharing one .mtl and so one image, and a grid map city of a few blocks.
fs::path textured_library(const std::string& name) {
  const fs::path dir = testing_util::temp_dir(name);
  write_checker(dir / "checker.png");
  write(dir / "box.mtl", "newmtl checker\nKd 1 1 1\nmap_Kd checker.png\n");
  write(dir / "box_a.obj", textured_box(10, 8));
  write(dir / "box_b.obj", textured_box(12, 8));
  write(dir / "library.json", R"({"models": [
    {"file": "box_a.obj", "zones": ["residential"], "up": "z", "scale": [1, 1]},
    {"file": "box_b.obj", "zones": ["residential"], "up": "z", "scale": [1, 1]}]})");
  write(dir / "city.grid", "cell 10\nrrrrr=rrrrr\nrrrrr=rrrrr\nrrrrr=rrrrr\n===========\nrrrrr=rrrrr\nrrrrr=rrrrr\n");
  return dir;
}

// The value of one channel of an EXR, for every pixel.
template <typename T>
std::vector<T> exr_channel(const fs::path& file, const std::string& name, OIIO::TypeDesc type) {
  auto in = OIIO::ImageInput::open(file.string());
  EXPECT_TRUE(in) << file;
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<T> values(static_cast<std::size_t>(spec.width) * spec.height);
  for (int c = 0; c < spec.nchannels; ++c)
    if (spec.channelnames[c] == name) {
      EXPECT_TRUE(in->read_image(0, 0, c, c + 1, type, values.data()));
    }
  return values;
}

}  // namespace

TEST(Textures, GoIntoTheGlbOnceWithTheirCoordinatesAndIntoTheRender) {
  const fs::path dir = textured_library("textures-city"), out = dir / "out";
  Result r = run("generate " + (dir / "city.grid").string() + " -o " + out.string() + " -q --models " +
                 (dir / "library.json").string());
  ASSERT_EQ(r.code, 0) << r.out;
  // The same bytes whatever the thread count, images included.
  r = run("generate " + (dir / "city.grid").string() + " -o " + (dir / "again").string() + " -q --threads 1 --models " +
          (dir / "library.json").string());
  ASSERT_EQ(r.code, 0) << r.out;
  for (const char* file : {"city.glb", "city.city.json", "textures/checker.png"})
    EXPECT_TRUE(read(out / file) == read(dir / "again" / file)) << file;

  tinygltf::Model glb;
  tinygltf::TinyGLTF loader;
  std::string error, warning;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&glb, &error, &warning, (out / "city.glb").string())) << error;
  // Both models name the file: one image, its bytes the PNG's as written.
  ASSERT_EQ(glb.images.size(), 1u);
  const tinygltf::BufferView& view = glb.bufferViews.at(glb.images[0].bufferView);
  const auto& buffer = glb.buffers.at(view.buffer).data;
  EXPECT_EQ(glb.images[0].mimeType, "image/png");
  EXPECT_EQ(std::string(buffer.begin() + view.byteOffset, buffer.begin() + view.byteOffset + view.byteLength),
            read(dir / "checker.png"));
  ASSERT_EQ(glb.textures.size(), 1u);
  EXPECT_EQ(glb.samplers.at(glb.textures[0].sampler).wrapS, TINYGLTF_TEXTURE_WRAP_REPEAT);

  // Each model's textured primitive: glTF's v is 1 - OBJ's, corner by corner. A side's
  // bottom corners (y 0 in glTF's y-up frame) have v 0 in the file, its top corners 0.5;
  // the top face is vt 5 (0.75, 0.75) everywhere. The bottom, without vt, is untextured.
  auto floats = [&](int accessor) {
    const tinygltf::Accessor& a = glb.accessors.at(accessor);
    const tinygltf::BufferView& v = glb.bufferViews.at(a.bufferView);
    const auto* p = reinterpret_cast<const float*>(glb.buffers.at(v.buffer).data.data() + v.byteOffset + a.byteOffset);
    return std::vector<float>(p, p + a.count * (a.type == TINYGLTF_TYPE_VEC3 ? 3 : 2));
  };
  int textured = 0, untextured = 0;
  for (const tinygltf::Mesh& mesh : glb.meshes)
    for (const tinygltf::Primitive& p : mesh.primitives) {
      const tinygltf::Material& material = glb.materials.at(p.material);
      if (material.name.rfind("box_", 0) != 0) continue;
      if (!p.attributes.count("TEXCOORD_0")) {
        EXPECT_EQ(material.pbrMetallicRoughness.baseColorTexture.index, -1) << material.name;
        ++untextured;
        continue;
      }
      ++textured;
      EXPECT_EQ(material.pbrMetallicRoughness.baseColorTexture.index, 0) << material.name;
      const std::vector<float> position = floats(p.attributes.at("POSITION")),
                               uv = floats(p.attributes.at("TEXCOORD_0"));
      ASSERT_EQ(position.size() / 3, uv.size() / 2);
      // Positions are per corner, in order: three a triangle.
      for (std::size_t t = 0; t < position.size() / 9; ++t) {
        const bool top = position[9 * t + 1] == 8 && position[9 * t + 4] == 8 && position[9 * t + 7] == 8;
        for (std::size_t k = 3 * t; k < 3 * t + 3; ++k) {
          const float y = position[3 * k + 1], u = uv[2 * k], v = uv[2 * k + 1];
          if (top) {
            EXPECT_EQ(u, 0.75f);
            EXPECT_EQ(v, 0.25f);
          } else {
            EXPECT_TRUE(u == 0 || u == 1) << u;
            EXPECT_EQ(v, y == 0 ? 1.0f : 0.5f) << "y " << y;
          }
        }
      }
    }
  EXPECT_GT(textured, 0);
  EXPECT_EQ(untextured, textured);
  EXPECT_EQ(shell(node_tool("check_glb.mjs") + " " + (out / "city.glb").string()).code, 0);
  // city.glb is written as it is made (generate/export/gltf_export.cpp), yet to the byte as
  // tinygltf writes the model it reads from it: images, samplers and textures included.
  std::ostringstream rewritten;
  ASSERT_TRUE(loader.WriteGltfSceneToStream(&glb, rewritten, false, true));
  EXPECT_TRUE(rewritten.str() == read(out / "city.glb"));

  // CityJSON: the image written once beside it, box_a's template (the first) with each
  // corner's texture vertex as the OBJ gives it (v up); its bottom untextured.
  const auto city = nlohmann::json::parse(read(out / "city.city.json"));
  const auto& appearance = city["appearance"];
  ASSERT_EQ(appearance["textures"].size(), 1u) << appearance;
  EXPECT_EQ(appearance["textures"][0]["image"], "textures/checker.png");
  EXPECT_EQ(read(out / "textures" / "checker.png"), read(dir / "checker.png"));
  const auto& box_a = city["geometry-templates"]["templates"][0];
  const auto& corners = city["geometry-templates"]["vertices-templates"];
  const auto& faces = box_a["boundaries"];
  const auto& values = box_a["texture"]["exacity"]["values"];
  ASSERT_EQ(values.size(), faces.size());
  int untextured_faces = 0;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& value = values[f][0];
    if (value[0].is_null()) {
      ++untextured_faces;
      continue;
    }
    EXPECT_EQ(value[0], 0);
    bool top = true;
    for (int k = 0; k < 3; ++k) top = top && corners[faces[f][0][k].get<int>()][2] == 8.0;
    for (int k = 0; k < 3; ++k) {
      const double z = corners[faces[f][0][k].get<int>()][2];
      const auto& uv = appearance["vertices-texture"][value[k + 1].get<int>()];
      if (top) {
        EXPECT_EQ(uv, nlohmann::json::array({0.75, 0.75}));
      } else {
        EXPECT_EQ(uv[1].get<double>(), z == 0 ? 0.0 : 0.5) << uv;
      }
    }
  }
  EXPECT_EQ(untextured_faces, 2) << "the bottom's two triangles";
  const fs::path schemas = cityjson_schemas();
  const Result cityjson = shell(node_tool("check_cityjson.mjs") + " " + (out / "city.city.json").string() +
                                (fs::exists(schemas / "cityjson.schema.json") ? " " + schemas.string() : ""));
  EXPECT_EQ(cityjson.code, 0) << cityjson.out;

  // A render looking at a box: where a box is seen, its colour is the checker's (red or
  // blue, no green), in the beauty and in the albedo the denoiser divides out.
  const auto buildings = nlohmann::json::parse(read(out / "vector" / "buildings.geojson"));
  double x = 0, y = 0;
  // The boxes as the id layer names them: by their place in the layer (Exacity's own garden
  // trees are models too).
  std::set<std::uint32_t> boxes;
  for (std::uint32_t i = 0; i < buildings["features"].size(); ++i)
    if (const auto& p = buildings["features"][i]["properties"]; p["model"] == "box_a" || p["model"] == "box_b")
      boxes.insert(i);
  for (const auto& f : buildings["features"])
    if (f["properties"]["model"] == "box_a") {
      const auto& ring = f["geometry"]["coordinates"][0];
      for (std::size_t i = 0; i + 1 < ring.size(); ++i) x += ring[i][0].get<double>(), y += ring[i][1].get<double>();
      x /= static_cast<double>(ring.size() - 1), y /= static_cast<double>(ring.size() - 1);
      break;
    }
  ASSERT_NE(x, 0) << "a box_a stands in the city";
  const fs::path still = dir / "still.png", exr = dir / "still.exr";
  r = run("render " + out.string() + " --size 64x48 --spp 4 -q -o " + still.string() + " --camera orbit:target=" +
          std::to_string(x) + "," + std::to_string(y) + ",4,azimuth=235,elevation=25,distance=30");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto id = exr_channel<std::uint32_t>(exr, "id", OIIO::TypeDesc::UINT);
  std::array<std::vector<float>, 3> beauty, albedo;
  for (int c = 0; c < 3; ++c) {
    beauty[c] = exr_channel<float>(exr, std::string(1, "RGB"[c]), OIIO::TypeDesc::FLOAT);
    albedo[c] = exr_channel<float>(exr, std::string("albedo.") + "RGB"[c], OIIO::TypeDesc::FLOAT);
  }
  const int w = 64, h = 48;
  auto model_at = [&](int px, int py) {
    const std::uint32_t v = id[static_cast<std::size_t>(py) * w + px];
    return v >> 24 == 2 && boxes.count(v & 0xffffff);
  };
  int seen = 0;
  for (int py = 2; py + 2 < h; ++py)
    for (int px = 2; px + 2 < w; ++px) {
      // Pixels two pixels inside a box's image: nothing else mixes in. (One pixel inside is
      // not enough: a diagonal edge can pass between a neighbour's centre and its corner,
      // and the pixel's samples, the denoiser's taps alike with them, see the grass past it.)
      bool inside = true;
      for (int j = -2; j <= 2; ++j)
        for (int i = -2; i <= 2; ++i) inside = inside && model_at(px + i, py + j);
      if (!inside) continue;
      ++seen;
      const std::size_t p = static_cast<std::size_t>(py) * w + px;
      EXPECT_LT(albedo[1][p], 0.01f) << px << "," << py;
      // Red and blue, or a blend of them (tints scale by 0.82 at the least).
      EXPECT_GT(albedo[0][p] + albedo[2][p], 0.6f) << px << "," << py;
      // A white box would be as green as it is red; samples at a pixel's edge may see past it.
      EXPECT_LE(beauty[1][p], 0.1f * (beauty[0][p] + beauty[2][p])) << px << "," << py;
    }
  EXPECT_GT(seen, 50) << "the box fills part of the view";
}

TEST(Textures, AMissingOrUnreadableTextureStopsTheRunWithOneLine) {
  const fs::path dir = textured_library("textures-bad"), out = dir / "out";
  const std::string generate = "generate " + (dir / "city.grid").string() + " -o " + out.string() + " -q --models " +
                               (dir / "library.json").string();
  fs::remove(dir / "checker.png");
  Result r = run(generate);
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_EQ(r.out, "exacity: error: " + (dir / "box.mtl").string() + " line 3: map_Kd " +
                       (dir / "checker.png").string() +
                       " does not exist; put the image there or fix the map_Kd line\n");
  EXPECT_FALSE(fs::exists(out));
  write(dir / "checker.png", "\x89PNG\r\n\x1a\ncut short");
  r = run(generate);
  EXPECT_EQ(r.code, 2) << r.out;
  // Exacity's one line, libpng's reason in it ("libpng error: ..." printed on its own before).
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_EQ(r.out.rfind("exacity: error: " + (dir / "box.mtl").string() + " line 3: map_Kd " +
                            (dir / "checker.png").string() + " cannot be decoded (",
                        0),
            0u)
      << r.out;
  EXPECT_FALSE(fs::exists(out));
  // Cut short inside its pixels, and a byte of its pixels changed (its checksum then wrong): the same.
  write_checker(dir / "whole.png");
  const std::string whole = read(dir / "whole.png");
  const std::size_t pixels = whole.find("IDAT") + 6;
  std::string changed = whole;
  changed[pixels] = static_cast<char>(changed[pixels] ^ 0x55);
  for (const std::string& broken : {whole.substr(0, pixels), changed}) {
    write(dir / "checker.png", broken);
    r = run(generate);
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
    EXPECT_EQ(r.out.rfind("exacity: error: ", 0), 0u) << r.out;
    EXPECT_FALSE(fs::exists(out));
  }
}
