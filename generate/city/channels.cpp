#include "generate/city/channels.h"

#include <cmath>

namespace exacity {

Channels::Channels(std::vector<ChannelSpec> specs, std::vector<GreyImage> images, double sharpness)
    : specs_(std::move(specs)), images_(std::move(images)), sharpness_(sharpness) {}

Channels Channels::load(const std::vector<ChannelSpec>& specs, double sharpness) {
  std::vector<GreyImage> images;
  for (const ChannelSpec& c : specs)
    images.push_back(read_grey_image(c.image, "channel \"" + c.name + "\" image",
                                     "\"exacity\".channels." + c.name + ".image"));
  return Channels(specs, std::move(images), sharpness);
}

int Channels::index(const std::string& name) const {
  for (std::size_t i = 0; i < specs_.size(); ++i)
    if (specs_[i].name == name) return static_cast<int>(i);
  return -1;
}

double Channels::affinity(const ChannelValues& values, geom::Vec2 p) const {
  if (values.empty()) return 1;
  double difference = 0;
  for (const auto& [name, v] : values) difference += std::abs(v - value(index(name), p));
  return std::pow(std::max(0.0, 1 - difference / static_cast<double>(values.size())), sharpness_);
}

}  // namespace exacity
