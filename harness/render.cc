#include "harness/render.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "backends/common/naming.h"
#include "harness/osmesa_loader.h"
#include "sequence/sequence.h"

namespace efc {
namespace {

struct RenderMujocoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void throwing_error_handler(const char* msg) { throw RenderMujocoError(msg ? msg : "MuJoCo error"); }

// Installs a throwing mju_user_error for the duration of a renderer call, so a
// MuJoCo error inside rendering becomes a failure we report instead of an exit
// (the default handler waits for Enter). Restores the previous handler.
class ErrorGuard {
 public:
  ErrorGuard() : saved_(mju_user_error) { mju_user_error = throwing_error_handler; }
  ~ErrorGuard() { mju_user_error = saved_; }
  ErrorGuard(const ErrorGuard&) = delete;
  ErrorGuard& operator=(const ErrorGuard&) = delete;

 private:
  void (*saved_)(const char*);
};

}  // namespace

OffscreenRenderer::OffscreenRenderer(const mjModel* m, int width, int height) {
  if (!m) {
    error_ = "no model";
    return;
  }
  int maxw = m->vis.global.offwidth > 0 ? m->vis.global.offwidth : 640;
  int maxh = m->vis.global.offheight > 0 ? m->vis.global.offheight : 480;
  width_ = std::max(1, std::min(width > 0 ? width : maxw, maxw));
  height_ = std::max(1, std::min(height > 0 ? height : maxh, maxh));

  osmesa_api_ = osmesa_api(&error_);
  if (!osmesa_api_) return;
  const OsMesaApi& gl = *osmesa_api_;
  OSMesaContext ctx = gl.create_context_ext(OSMESA_RGBA, 24, 8, 0, nullptr);
  if (!ctx) {
    error_ = "OSMesaCreateContextExt failed";
    return;
  }
  osmesa_ = ctx;
  osbuf_.assign(static_cast<size_t>(width_) * height_ * 4, 0);
  if (!gl.make_current(ctx, osbuf_.data(), GL_UNSIGNED_BYTE, width_, height_)) {
    error_ = "OSMesaMakeCurrent failed";
    return;
  }

  mjv_defaultScene(&scn_);
  mjr_defaultContext(&con_);
  mjv_defaultCamera(&cam_);
  mjv_defaultOption(&opt_);
  try {
    ErrorGuard guard;
    mjv_makeScene(m, &scn_, 2000);
    scene_made_ = true;
    mjr_makeContext(m, &con_, mjFONTSCALE_150);
    context_made_ = true;
    mjr_setBuffer(mjFB_OFFSCREEN, &con_);
    if (con_.currentBuffer != mjFB_OFFSCREEN) {
      error_ = "offscreen framebuffer not available";
      return;
    }
  } catch (const std::exception& e) {
    error_ = std::string("MuJoCo rendering setup failed: ") + e.what();
    return;
  }
  // The actual offscreen buffer may be smaller than requested.
  width_ = std::min(width_, con_.offWidth);
  height_ = std::min(height_, con_.offHeight);

  camera_id_ = mj_name2id(m, mjOBJ_CAMERA, naming::kMjcfCamera);
  if (camera_id_ >= 0) {
    cam_.type = mjCAMERA_FIXED;
    cam_.fixedcamid = camera_id_;
  } else {
    mjv_defaultFreeCamera(m, &cam_);
  }
  ok_ = true;
}

OffscreenRenderer::~OffscreenRenderer() {
  if (osmesa_) {
    const OsMesaApi& gl = *osmesa_api_;
    OSMesaContext ctx = static_cast<OSMesaContext>(osmesa_);
    gl.make_current(ctx, osbuf_.data(), GL_UNSIGNED_BYTE, std::max(1, width_),
                      std::max(1, height_));
    try {
      ErrorGuard guard;
      if (context_made_) mjr_freeContext(&con_);
      if (scene_made_) mjv_freeScene(&scn_);
    } catch (...) {
    }
    gl.destroy_context(ctx);
    osmesa_ = nullptr;
  }
}

bool OffscreenRenderer::render_rgb(const mjModel* m, mjData* d, std::vector<unsigned char>* rgb,
                                   int* w, int* h) {
  if (!ok_) {
    if (error_.empty()) error_ = "renderer not initialised";
    return false;
  }
  if (!m || !d || !rgb) {
    error_ = "render_rgb: null argument";
    return false;
  }
  const OsMesaApi& gl = *osmesa_api_;
  OSMesaContext ctx = static_cast<OSMesaContext>(osmesa_);
  if (gl.get_current_context() != ctx &&
      !gl.make_current(ctx, osbuf_.data(), GL_UNSIGNED_BYTE, width_, height_)) {
    error_ = "OSMesaMakeCurrent failed";
    return false;
  }
  std::vector<unsigned char> raw(static_cast<size_t>(width_) * height_ * 3);
  try {
    ErrorGuard guard;
    mjrRect viewport = {0, 0, width_, height_};
    mjr_setBuffer(mjFB_OFFSCREEN, &con_);
    mjv_updateScene(m, d, &opt_, nullptr, &cam_, mjCAT_ALL, &scn_);
    mjr_render(viewport, &scn_, &con_);
    mjr_readPixels(raw.data(), nullptr, viewport, &con_);
  } catch (const std::exception& e) {
    error_ = std::string("MuJoCo rendering failed: ") + e.what();
    return false;
  }
  // OpenGL rows are bottom-first; flip to top-first.
  const size_t row = static_cast<size_t>(width_) * 3;
  rgb->resize(raw.size());
  for (int y = 0; y < height_; ++y) {
    std::memcpy(rgb->data() + static_cast<size_t>(y) * row,
                raw.data() + static_cast<size_t>(height_ - 1 - y) * row, row);
  }
  if (w) *w = width_;
  if (h) *h = height_;
  return true;
}

bool OffscreenRenderer::render_views(const mjModel* m, mjData* d, int camera_id, bool want_depth,
                                     bool want_segmentation, Views* out) {
  if (!ok_) {
    if (error_.empty()) error_ = "renderer not initialised";
    return false;
  }
  const OsMesaApi& gl = *osmesa_api_;
  OSMesaContext ctx = static_cast<OSMesaContext>(osmesa_);
  if (gl.get_current_context() != ctx &&
      !gl.make_current(ctx, osbuf_.data(), GL_UNSIGNED_BYTE, width_, height_)) {
    error_ = "OSMesaMakeCurrent failed";
    return false;
  }
  const size_t n = static_cast<size_t>(width_) * height_;
  std::vector<unsigned char> raw(n * 3), ids;
  std::vector<float> zbuf;
  mjvCamera cam;
  mjv_defaultCamera(&cam);
  cam.type = mjCAMERA_FIXED;
  cam.fixedcamid = camera_id;
  try {
    ErrorGuard guard;
    mjrRect viewport = {0, 0, width_, height_};
    mjr_setBuffer(mjFB_OFFSCREEN, &con_);
    mjv_updateScene(m, d, &opt_, nullptr, &cam, mjCAT_ALL, &scn_);
    if (want_depth) zbuf.resize(n);
    mjr_render(viewport, &scn_, &con_);
    mjr_readPixels(raw.data(), want_depth ? zbuf.data() : nullptr, viewport, &con_);
    if (want_segmentation) {
      ids.resize(n * 3);
      scn_.flags[mjRND_SEGMENT] = 1;
      scn_.flags[mjRND_IDCOLOR] = 1;
      mjr_render(viewport, &scn_, &con_);
      scn_.flags[mjRND_SEGMENT] = 0;
      scn_.flags[mjRND_IDCOLOR] = 0;
      mjr_readPixels(ids.data(), nullptr, viewport, &con_);
    }
  } catch (const std::exception& e) {
    scn_.flags[mjRND_SEGMENT] = 0;
    scn_.flags[mjRND_IDCOLOR] = 0;
    error_ = std::string("MuJoCo rendering failed: ") + e.what();
    return false;
  }
  out->width = width_;
  out->height = height_;
  out->rgb.resize(n * 3);
  const size_t row = static_cast<size_t>(width_) * 3;
  for (int y = 0; y < height_; ++y)  // OpenGL rows are bottom-first
    std::memcpy(out->rgb.data() + static_cast<size_t>(y) * row,
                raw.data() + static_cast<size_t>(height_ - 1 - y) * row, row);
  out->depth.clear();
  if (want_depth) {
    // The depth buffer holds z in [0, 1] of a standard perspective projection
    // between MuJoCo's near and far planes; invert it to metres.
    const double extent = m->stat.extent;
    const double znear = m->vis.map.znear * extent, zfar = m->vis.map.zfar * extent;
    out->depth.resize(n);
    for (int y = 0; y < height_; ++y) {
      const float* src = zbuf.data() + static_cast<size_t>(height_ - 1 - y) * width_;
      float* dst = out->depth.data() + static_cast<size_t>(y) * width_;
      for (int x = 0; x < width_; ++x) {
        const double z = src[x];
        dst[x] = z >= 1.0 ? 0.0f : static_cast<float>(znear / (1.0 - z * (1.0 - znear / zfar)));
      }
    }
  }
  out->geom.clear();
  if (want_segmentation) {
    // Each pixel's colour is the scene geom's segid + 1 (little-endian RGB);
    // the scene geom names the model geom it draws.
    std::vector<int> model_geom(static_cast<size_t>(scn_.ngeom) + 1, -1);  // segid + 1 -> geom
    for (int i = 0; i < scn_.ngeom; ++i) {
      const mjvGeom& g = scn_.geoms[i];
      if (g.segid >= 0 && g.segid < scn_.ngeom && g.objtype == mjOBJ_GEOM) model_geom[g.segid + 1] = g.objid;
    }
    out->geom.assign(n, -1);
    for (int y = 0; y < height_; ++y) {
      const unsigned char* src = ids.data() + static_cast<size_t>(height_ - 1 - y) * row;
      int* dst = out->geom.data() + static_cast<size_t>(y) * width_;
      for (int x = 0; x < width_; ++x) {
        const int id = src[3 * x] | (src[3 * x + 1] << 8) | (src[3 * x + 2] << 16);
        if (id > 0 && id <= scn_.ngeom) dst[x] = model_geom[id];
      }
    }
  }
  return true;
}

bool OffscreenRenderer::render_png(const mjModel* m, mjData* d, const std::string& path) {
  std::vector<unsigned char> rgb;
  int w = 0, h = 0;
  if (!render_rgb(m, d, &rgb, &w, &h)) return false;
  return write_png_rgb(path, rgb.data(), w, h, &error_);
}

bool write_png_rgb(const std::string& path, const unsigned char* rgb, int width, int height,
                   std::string* error) {
  if (!rgb || width <= 0 || height <= 0) {
    if (error) *error = "write_png_rgb: empty image";
    return false;
  }
  seq::Image8 img;
  img.width = width, img.height = height, img.channels = 3;
  img.pixels.assign(rgb, rgb + static_cast<size_t>(width) * height * 3);
  std::string why;
  if (!seq::write_png_rgb(path, img, &why)) {
    if (error) *error = why;
    return false;
  }
  return true;
}

}  // namespace efc
