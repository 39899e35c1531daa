#include "drivers/hid/hidapi_library.h"

#include <dlfcn.h>

#include <mutex>

namespace cb::hid {

const char* hidapiBackendName(HidapiBackend b) {
  return b == HidapiBackend::kHidraw ? "hidraw" : "libusb";
}

HidapiLibrary::~HidapiLibrary() {
  if (exit) exit();
  if (handle) dlclose(handle);
}

std::string narrow(const wchar_t* s) {
  std::string out;
  for (; s && *s; ++s) out += (*s >= 32 && *s < 127) ? static_cast<char>(*s) : '?';
  return out;
}

namespace {

template <typename F>
bool bind(void* h, const char* name, F& fn, std::string* error) {
  fn = reinterpret_cast<F>(dlsym(h, name));
  if (!fn && error) *error = std::string("hidapi library lacks ") + name;
  return fn != nullptr;
}

std::shared_ptr<HidapiLibrary> load(HidapiBackend backend, std::string* error) {
  const char* file =
      backend == HidapiBackend::kHidraw ? "libhidapi-hidraw.so.0" : "libhidapi-libusb.so.0";
  void* h = dlopen(file, RTLD_NOW | RTLD_LOCAL);
  if (!h) {
    if (error) *error = std::string("cannot load ") + file + ": " + dlerror();
    return nullptr;
  }
  auto lib = std::make_shared<HidapiLibrary>();
  lib->backend = backend;
  lib->handle = h;
  if (!bind(h, "hid_init", lib->init, error) || !bind(h, "hid_exit", lib->exit, error) ||
      !bind(h, "hid_enumerate", lib->enumerate, error) ||
      !bind(h, "hid_free_enumeration", lib->free_enumeration, error) ||
      !bind(h, "hid_open_path", lib->open_path, error) ||
      !bind(h, "hid_close", lib->close, error) ||
      !bind(h, "hid_read_timeout", lib->read_timeout, error) ||
      !bind(h, "hid_get_feature_report", lib->get_feature_report, error) ||
      !bind(h, "hid_send_feature_report", lib->send_feature_report, error) ||
      !bind(h, "hid_error", lib->error, error))
    return nullptr;
  if (lib->init() != 0) {
    if (error) *error = std::string(file) + ": hid_init failed";
    lib->exit = nullptr;
    return nullptr;
  }
  return lib;
}

}  // namespace

std::shared_ptr<HidapiLibrary> loadHidapi(HidapiBackend backend, std::string* error) {
  static std::mutex mutex;
  static std::weak_ptr<HidapiLibrary> loaded[2];
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = loaded[backend == HidapiBackend::kHidraw ? 0 : 1];
  if (auto lib = slot.lock()) return lib;
  auto lib = load(backend, error);
  slot = lib;
  return lib;
}

}  // namespace cb::hid
