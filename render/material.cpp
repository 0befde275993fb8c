#include "render/material.h"

#include <cmath>

#include "render/sampling.h"

namespace render {
namespace {

float fresnel(float cos_theta, float ior) {
  float f0 = (ior - 1) / (ior + 1);
  f0 *= f0;
  float m = 1 - std::clamp(cos_theta, 0.0f, 1.0f);
  return f0 + (1 - f0) * m * m * m * m * m;
}

float ggx_d(float cos_h, float alpha) {
  float a2 = alpha * alpha, c2 = cos_h * cos_h;
  float d = c2 * (a2 - 1) + 1;
  return a2 / (kPi * d * d);
}

float smith_g1(float cos_v, float alpha) {
  float c2 = cos_v * cos_v, t2 = (1 - c2) / std::max(c2, 1e-8f);
  return 2 / (1 + std::sqrt(1 + alpha * alpha * t2));
}

// The chance of drawing from the coat's lobe rather than the base's.
float coat_chance(const Material& m, V3 wo) { return std::clamp(fresnel(wo.z, m.ior) * 4, 0.15f, 0.85f); }

V3 coat(const Material& m, V3 wo, V3 wi) {
  V3 h = normalize(wo + wi);
  float f = fresnel(dot(wo, h), m.ior);
  float spec = f * ggx_d(h.z, m.roughness) * smith_g1(wo.z, m.roughness) * smith_g1(wi.z, m.roughness) / (4 * wo.z);
  return V3{spec, spec, spec};
}

}  // namespace

V3 eval(const Material& m, V3 wo, V3 wi) {
  if (wo.z <= 0 || wi.z <= 0) return {0, 0, 0};
  V3 diffuse = m.albedo * (wi.z / kPi);
  if (m.kind == Material::Diffuse) return diffuse;
  // The base sees light that crossed the coat twice.
  return coat(m, wo, wi) + diffuse * ((1 - fresnel(wo.z, m.ior)) * (1 - fresnel(wi.z, m.ior)));
}

float pdf(const Material& m, V3 wo, V3 wi) {
  if (wo.z <= 0 || wi.z <= 0) return 0;
  float diffuse = wi.z / kPi;
  if (m.kind == Material::Diffuse) return diffuse;
  V3 h = normalize(wo + wi);
  float spec = ggx_d(h.z, m.roughness) * h.z / (4 * dot(wo, h));
  float p = coat_chance(m, wo);
  return p * spec + (1 - p) * diffuse;
}

bool sample(const Material& m, V3 wo, float u1, float u2, float u3, BsdfSample& s) {
  if (wo.z <= 0) return false;
  if (m.kind == Material::Glossy && u3 < coat_chance(m, wo)) {
    // A microfacet normal from D(h)·cos(h), reflected.
    float a2 = m.roughness * m.roughness;
    float cos_h = std::sqrt((1 - u1) / (1 + (a2 - 1) * u1)), sin_h = std::sqrt(std::max(0.0f, 1 - cos_h * cos_h));
    const CirclePoint p = circle_point(u2);
    V3 h{sin_h * p.c, sin_h * p.s, cos_h};
    s.wi = h * (2 * dot(wo, h)) - wo;
  } else {
    s.wi = cosine_hemisphere(u1, u2);
  }
  if (s.wi.z <= 0) return false;
  s.pdf = pdf(m, wo, s.wi);
  if (s.pdf <= 0) return false;
  s.weight = eval(m, wo, s.wi) / s.pdf;
  return true;
}

}  // namespace render
