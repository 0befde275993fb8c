#include "generate/export/clutter_layer.h"

namespace exacity {

Layer clutter_layer(const std::vector<Clutter>& clutter, const Ground& ground, const ModelLibrary* library) {
  Layer layer{"clutter", false, {}};
  for (const Clutter& c : clutter) {
    nlohmann::ordered_json props{{"id", c.instance.stable_id},
                                 {"kind", name(c.instance.kind)},
                                 {"model", library->models[c.instance.placed.model].name},
                                 // A park's tree dresses no street.
                                 {"road", c.road >= 0 ? nlohmann::ordered_json(ground.roads[c.road].stable_id) : nlohmann::ordered_json()},
                                 {"heading", c.heading}};
    layer.features.push_back({std::move(props), {}, {c.spot}});
  }
  return layer;
}

}  // namespace exacity
