#include "render/embree_device.h"

#include "generate/errors.h"

namespace render {

namespace {

const char* error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
    case RTC_ERROR_UNKNOWN: break;
  }
  return "unknown error";
}

}  // namespace

EmbreeDevice::EmbreeDevice(const char* config) {
  device_ = rtcNewDevice(config);
  if (!device_)
    throw exacity::InternalError(std::string("Embree: no device: ") + error_name(rtcGetDeviceError(nullptr)));
  rtcSetDeviceErrorFunction(device_, record_error, this);
  packets_ = rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_RAY_STREAM_SUPPORTED) != 0;
  rtcSetDeviceMemoryMonitorFunction(
      device_,
      [](void* user, ssize_t bytes, bool) {
        auto* d = static_cast<EmbreeDevice*>(user);
        const std::int64_t now = d->now_ += bytes;
        std::size_t peak = d->peak_;
        while (now > 0 && static_cast<std::size_t>(now) > peak &&
               !d->peak_.compare_exchange_weak(peak, static_cast<std::size_t>(now))) {
        }
        return true;
      },
      this);
}

EmbreeDevice::~EmbreeDevice() { rtcReleaseDevice(device_); }

// A build stopped by its progress monitor reports "cancelled": the job was cancelled
// (generate/cancel.h), and whoever stopped it throws that, not an error.
void EmbreeDevice::record_error(void* device, RTCError code, const char* message) {
  if (code == RTC_ERROR_CANCELLED) return;
  auto* d = static_cast<EmbreeDevice*>(device);
  const std::lock_guard<std::mutex> lock(d->error_mutex_);
  if (d->error_.empty()) d->error_ = std::string(error_name(code)) + (message && *message ? std::string(", ") + message : "");
}

void EmbreeDevice::check(const char* what) const {
  const std::lock_guard<std::mutex> lock(error_mutex_);
  if (!error_.empty()) throw exacity::InternalError(std::string("Embree: ") + what + ": " + error_);
}

void* EmbreeDevice::new_buffer(RTCGeometry g, RTCBufferType type, RTCFormat format, std::size_t item_bytes,
                               std::size_t count) const {
  void* buffer = rtcSetNewGeometryBuffer(g, type, 0, format, item_bytes, count);
  check("a geometry's buffer");
  if (!buffer) throw exacity::InternalError("Embree: a geometry's buffer of " + std::to_string(count) + " items was not made");
  return buffer;
}

}  // namespace render
