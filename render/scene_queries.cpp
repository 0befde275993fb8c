// Embree's ray queries on the scene: the nearest hit and occlusion, one ray or a packet.
#include <cassert>
#include <cmath>

#include "render/scene_build.h"

namespace render {

namespace {

RTCRayHit ray_hit(V3 o, V3 d, float tmax) {
  RTCRayHit rh{};
  rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
  rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
  rh.ray.tnear = 0, rh.ray.tfar = tmax, rh.ray.mask = 0xffffffff;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID, rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

}  // namespace

bool RenderScene::raw_intersect(V3 o, V3 d) const {
  RTCRayHit rh = ray_hit(o, d, INFINITY);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(scene_, &context, &rh);
  return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

bool RenderScene::intersect(V3 o, V3 d, float tmax, Surface& s) const {
  RTCRayHit rh = ray_hit(o, d, tmax);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(scene_, &context, &rh);
  const Hit hit{rh.hit.geomID, rh.hit.primID, rh.hit.instID[0], rh.ray.tfar, rh.hit.u, rh.hit.v,
                {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z}};
  return surface(o, d, tmax, hit, s);
}

void RenderScene::intersect_packet(const V3* o, const V3* d, int count, Surface* hits, bool* found) const {
  assert(count >= 0 && count <= kPacket);
  if (!device_.packets()) {
    for (int i = 0; i < count; ++i) found[i] = intersect(o[i], d[i], INFINITY, hits[i]);
    return;
  }
  alignas(64) int valid[kPacket];
  alignas(64) RTCRayHit16 rh{};
  for (int i = 0; i < kPacket; ++i) {
    valid[i] = i < count ? -1 : 0;
    const V3 oi = o[i < count ? i : 0], di = d[i < count ? i : 0];
    rh.ray.org_x[i] = oi.x, rh.ray.org_y[i] = oi.y, rh.ray.org_z[i] = oi.z;
    rh.ray.dir_x[i] = di.x, rh.ray.dir_y[i] = di.y, rh.ray.dir_z[i] = di.z;
    rh.ray.tnear[i] = 0, rh.ray.tfar[i] = INFINITY, rh.ray.mask[i] = 0xffffffff;
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID, rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect16(valid, scene_, &context, &rh);
  for (int i = 0; i < count; ++i) {
    const Hit hit{rh.hit.geomID[i], rh.hit.primID[i], rh.hit.instID[0][i], rh.ray.tfar[i], rh.hit.u[i], rh.hit.v[i],
                  {rh.hit.Ng_x[i], rh.hit.Ng_y[i], rh.hit.Ng_z[i]}};
    found[i] = surface(o[i], d[i], INFINITY, hit, hits[i]);
  }
}

// The ground plane past the city blocks a ray that goes down to it within tmax.
bool RenderScene::meets_ground_plane(V3 o, V3 d, float tmax) const {
  return ground_plane_ && d.z < 0 && o.z > ground && (ground - o.z) / d.z < tmax;
}

void RenderScene::occluded_packet(const V3* o, const V3* d, int count, bool* blocked) const {
  assert(count >= 0 && count <= kPacket);
  if (count == 0) return;  // camera rays that met no surface the sun lights: no call to make
  if (!device_.packets()) {
    for (int i = 0; i < count; ++i) blocked[i] = occluded(o[i], d[i], INFINITY);
    return;
  }
  alignas(64) int valid[kPacket];
  alignas(64) RTCRay16 r{};
  for (int i = 0; i < kPacket; ++i) {
    const bool traced = i < count && !meets_ground_plane(o[i], d[i], INFINITY);
    valid[i] = traced ? -1 : 0;
    const V3 oi = o[i < count ? i : 0], di = d[i < count ? i : 0];
    r.org_x[i] = oi.x, r.org_y[i] = oi.y, r.org_z[i] = oi.z;
    r.dir_x[i] = di.x, r.dir_y[i] = di.y, r.dir_z[i] = di.z;
    r.tnear[i] = 0, r.tfar[i] = traced ? INFINITY : -INFINITY, r.mask[i] = 0xffffffff;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcOccluded16(valid, scene_, &context, &r);
  for (int i = 0; i < count; ++i) blocked[i] = r.tfar[i] < 0;  // Embree sets tfar to -inf on a hit
}

bool RenderScene::occluded(V3 o, V3 d, float tmax) const {
  if (meets_ground_plane(o, d, tmax)) return true;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r{};
  r.org_x = o.x, r.org_y = o.y, r.org_z = o.z;
  r.dir_x = d.x, r.dir_y = d.y, r.dir_z = d.z;
  r.tnear = 0, r.tfar = tmax, r.mask = 0xffffffff;
  rtcOccluded1(scene_, &context, &r);
  return r.tfar < 0;  // Embree sets tfar to -inf on a hit
}

}  // namespace render
