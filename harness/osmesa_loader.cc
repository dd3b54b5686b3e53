#include "harness/osmesa_loader.h"

#include <dlfcn.h>

namespace efc {
namespace {

struct Loaded {
  OsMesaApi api{};
  bool ok = false;
  std::string error;
};

// Binds one symbol; false (and the reason) when it is missing.
template <class F>
bool bind(void* lib, const char* name, F* out, std::string* error) {
  *out = reinterpret_cast<F>(dlsym(lib, name));
  if (!*out) *error = std::string("libOSMesa has no symbol ") + name;
  return *out != nullptr;
}

Loaded load() {
  Loaded l;
  // Debian's soname first; the unversioned name where only the dev link exists.
  void* lib = nullptr;
  for (const char* name : {"libOSMesa.so.8", "libOSMesa.so"}) {
    lib = dlopen(name, RTLD_NOW | RTLD_GLOBAL);
    if (lib) break;
    const char* why = dlerror();
    if (l.error.empty()) l.error = std::string("cannot load ") + name + ": " + (why ? why : "?");
  }
  if (!lib) {
    l.error += " (offscreen rendering needs OSMesa: apt-get install libosmesa6)";
    return l;
  }
  l.error.clear();
  l.ok = bind(lib, "OSMesaCreateContextExt", &l.api.create_context_ext, &l.error) &&
         bind(lib, "OSMesaMakeCurrent", &l.api.make_current, &l.error) &&
         bind(lib, "OSMesaDestroyContext", &l.api.destroy_context, &l.error) &&
         bind(lib, "OSMesaGetCurrentContext", &l.api.get_current_context, &l.error);
  return l;  // the library stays loaded for the process (MuJoCo keeps GL pointers into it)
}

}  // namespace

const OsMesaApi* osmesa_api(std::string* error) {
  static const Loaded loaded = load();
  if (!loaded.ok) {
    if (error) *error = loaded.error;
    return nullptr;
  }
  return &loaded.api;
}

}  // namespace efc
