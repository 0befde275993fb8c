// Surfaces (pbrt's split: evaluate, sample, pdf), in the local frame where the normal is
// +z. Diffuse is Lambertian; glossy is a dielectric coat over a diffuse base (glass,
// water): a GGX microfacet reflection weighted by Schlick's Fresnel term, the base
// getting what the coat lets through.
#pragma once

#include "render/vec.h"

namespace render {

struct Material {
  enum Kind { Diffuse, Glossy } kind = Diffuse;
  V3 albedo{0.5f, 0.5f, 0.5f};
  float roughness = 0.1f;  // GGX alpha, glossy only
  float ior = 1.5f;        // glossy only
  V3 emission{0, 0, 0};
  // Its emission seen by camera rays only: a lamp's head, whose light is its point light's
  // (render/night.h).
  bool camera_only = false;
};

// f(wo, wi) · cos(wi): what the surface sends towards wo of light arriving from wi.
V3 eval(const Material& m, V3 wo, V3 wi);
// The density sample() draws wi with, per solid angle.
float pdf(const Material& m, V3 wo, V3 wi);

struct BsdfSample {
  V3 wi;
  V3 weight;  // f · cos / pdf
  float pdf = 0;
};
// Draws wi for wo from three uniform numbers; false when nothing is drawn.
bool sample(const Material& m, V3 wo, float u1, float u2, float u3, BsdfSample& s);

}  // namespace render
