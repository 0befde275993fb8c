// The scene's materials: the palette of the ground and of buildings, and the model
// library's materials with their textures.
#include "render/scene_build.h"

namespace render {

using exacity::ZoneType;

void RenderScene::make_palette(Palette& p) {
  grass_material_ = add_material({Material::Diffuse, colour(exacity::kGrassAlbedo)}, Pattern::Grass);
  p.sidewalk = add_material({Material::Diffuse, colour(exacity::kSidewalkAlbedo)}, Pattern::Paving);
  p.asphalt = add_material({Material::Diffuse, colour(exacity::kAsphaltAlbedo)});
  p.paint = add_material({Material::Diffuse, colour(exacity::kPaintAlbedo)});
  p.yellow = add_material({Material::Diffuse, colour(exacity::kYellowPaintAlbedo)});
  p.water = add_material({Material::Glossy, colour(exacity::kWaterAlbedo), 0.02f, 1.33f});
  p.mapped = add_material({Material::Diffuse, {0.62f, 0.62f, 0.60f}});
  p.generated = add_material({Material::Diffuse, {0.80f, 0.30f, 0.06f}});
  p.lot_ground = {{ZoneType::Residential, grass_material_},
                  {ZoneType::Commercial,
                   add_material({Material::Diffuse, colour(exacity::kCommercialLotAlbedo)}, Pattern::Paving)},
                  {ZoneType::Industrial, add_material({Material::Diffuse, colour(exacity::kIndustrialLotAlbedo)})}};
  // Every zone: a mapped building stands in a park or by the water as well.
  for (ZoneType z : {ZoneType::Residential, ZoneType::Commercial, ZoneType::Industrial, ZoneType::Park, ZoneType::Water}) {
    for (int i = 0; i < static_cast<int>(exacity::facade_albedos(z).size()); ++i)
      p.facade[{z, i}] = add_material({Material::Diffuse, colour(exacity::facade_albedos(z)[i])}, Pattern::Windows);
    for (int i = 0; i < static_cast<int>(exacity::roof_albedos(z).size()); ++i)
      p.roof[{z, i}] = add_material({Material::Diffuse, colour(exacity::roof_albedos(z)[i])}, Pattern::Roof);
  }
}

RenderScene::ModelMaterials RenderScene::add_model_materials(const exacity::ModelLibrary* library,
                                                             float lamp_head_radiance) {
  ModelMaterials out;
  if (!library) return out;
  model_scenes_.assign(library->models.size(), nullptr);
  for (const auto& m : library->models) {
    out.base.push_back(static_cast<int>(materials_.size()));
    for (int tint = 0; tint < exacity::kTints; ++tint)
      for (const auto& mat : m.mesh.materials) {
        const bool glass = mat.name.find("glass") != std::string::npos || mat.name.find("window") != std::string::npos;
        Material made{glass ? Material::Glossy : Material::Diffuse, colour(exacity::tinted(mat.colour, tint)), 0.05f, 1.5f};
        // At night a lamp's head glows, warm (its light is its point light's, render/night.h).
        if (lamp_head_radiance > 0 && m.kind == exacity::ModelKind::Lamp && exacity::is_lamp_light_material(mat.name))
          made.emission = V3{1.0f, 0.78f, 0.5f} * lamp_head_radiance, made.camera_only = true;
        const int index = add_material(made);
        if (!mat.texture) continue;
        // The texture times the material's colour, as the MTL's map_Kd and Kd combine.
        std::unique_ptr<Texture>& texture = textures_[mat.texture.get()];
        if (!texture) texture = std::make_unique<Texture>(*mat.texture);
        material_textures_.resize(materials_.size());
        material_textures_[index] = {texture.get(), mat.clamp};
      }
    out.local.push_back(m.mesh.material);
  }
  return out;
}

}  // namespace render
