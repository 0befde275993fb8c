// One Embree device: its errors, its memory and what it was built with. Embree reports an
// error through a callback and carries on (a buffer it could not make comes back null), so
// the device keeps the first error's text and `check` throws it as an InternalError after
// each step that builds the scene.
#pragma once

#include <embree3/rtcore.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>

namespace render {

class EmbreeDevice {
 public:
  // Throws InternalError with Embree's message when no device can be made.
  explicit EmbreeDevice(const char* config = nullptr);
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  RTCDevice get() const { return device_; }
  // Throws InternalError ("Embree: <what>: <Embree's message>") if Embree reported an error
  // since the device was made.
  void check(const char* what) const;
  // A new buffer of a geometry, checked: Embree gives null where it could not make one.
  void* new_buffer(RTCGeometry g, RTCBufferType type, RTCFormat format, std::size_t item_bytes, std::size_t count) const;
  // Embree 3 builds ray packets and streams together (EMBREE_RAY_PACKETS); whether it was.
  bool packets() const { return packets_; }
  // The most memory Embree held at once, from the device's memory monitor.
  std::size_t peak_bytes() const { return peak_; }

 private:
  static void record_error(void* device, RTCError code, const char* message);
  RTCDevice device_ = nullptr;
  bool packets_ = false;
  std::atomic<std::int64_t> now_{0};
  std::atomic<std::size_t> peak_{0};
  mutable std::mutex error_mutex_;
  std::string error_;  // the first error Embree reported, empty if none
};

}  // namespace render
