// Channels (docs/design.md, Placement): greyscale images stretched over the city, each giving every point a
// value in [0, 1] whose meaning the user decides ("downtown-ness", wealth, greenery). Library
// models and clutter carry values of their own; where one stands, its weight is multiplied
// by how near its values are to the channels' there (docs/design.md, Placement).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "generate/city/grey_image.h"
#include "generate/city/features.h"

namespace exacity {

// A model's channel values, by channel name (ModelLibrary's "channels").
using ChannelValues = std::vector<std::pair<std::string, double>>;

class Channels {
 public:
  Channels() = default;
  // Reads every channel's image. Throws UserError naming the file and the channel.
  static Channels load(const std::vector<ChannelSpec>& specs, double sharpness);
  // For tests: images already read.
  Channels(std::vector<ChannelSpec> specs, std::vector<GreyImage> images, double sharpness);

  bool empty() const { return specs_.empty(); }
  // The channel's position, or -1 when the sketch has none of that name.
  int index(const std::string& name) const;
  // The channel's value at p, clamped to its bounds.
  double value(int channel, geom::Vec2 p) const { return images_[channel].sample(specs_[channel].bounds, p); }
  // How well values suit p: (1 - the mean absolute difference to the channels there) raised
  // to the sharpness; 1 for a model without values. Every name must be a channel's.
  double affinity(const ChannelValues& values, geom::Vec2 p) const;

 private:
  std::vector<ChannelSpec> specs_;
  std::vector<GreyImage> images_;
  double sharpness_ = 4;
};

}  // namespace exacity
