// OSMesa, loaded only when something renders.
//
// Linking libOSMesa directly made every efc command pay for loading it: it
// pulls in libLLVM, and the dynamic loader spent most of `efc check`'s 20 ms
// there. The renderer is the only user, so it opens the library on first use
// (RTLD_GLOBAL: MuJoCo's GL loader looks the GL entry points up globally).
#pragma once

#include <GL/osmesa.h>

#include <string>

namespace efc {

// The OSMesa entry points the offscreen renderer uses.
struct OsMesaApi {
  OSMesaContext (*create_context_ext)(GLenum format, GLint depth_bits, GLint stencil_bits,
                                      GLint accum_bits, OSMesaContext sharelist);
  GLboolean (*make_current)(OSMesaContext ctx, void* buffer, GLenum type, GLsizei width,
                            GLsizei height);
  void (*destroy_context)(OSMesaContext ctx);
  OSMesaContext (*get_current_context)();
};

// The API, loading the library on the first call (thread-safe, once). Null
// when the library or one of its symbols is missing, with the reason in
// *error (e.g. "cannot load libOSMesa.so.8: ...; install libosmesa6").
const OsMesaApi* osmesa_api(std::string* error);

}  // namespace efc
