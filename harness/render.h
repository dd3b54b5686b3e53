// Offscreen rendering of a MuJoCo model without GPU or display (OSMesa).
//
// One OffscreenRenderer owns one OSMesa context; only one should exist at a time.
// The constructor never aborts: failures (no OSMesa, MuJoCo GL errors) leave ok()
// false with a message in error(). During its own MuJoCo calls the renderer
// temporarily installs an mju_user_error handler that throws, so a MuJoCo
// rendering error becomes error() instead of exiting the process; the previous
// handler is restored afterwards.
#ifndef EFC_HARNESS_RENDER_H_
#define EFC_HARNESS_RENDER_H_

#include <mujoco/mujoco.h>

#include <string>
#include <vector>

namespace efc {

struct OsMesaApi;  // harness/osmesa_loader.h

class OffscreenRenderer {
 public:
  // width/height are clamped to the model's <visual><global offwidth offheight>.
  OffscreenRenderer(const mjModel* m, int width, int height);  // never aborts
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  bool ok() const { return ok_; }
  const std::string& error() const { return error_; }
  int width() const { return width_; }
  int height() const { return height_; }

  // Renders the current state and writes an RGB PNG. False with error() on failure.
  bool render_png(const mjModel* m, mjData* d, const std::string& path);
  // Renders into an RGB buffer (width*height*3, top row first) for tests.
  bool render_rgb(const mjModel* m, mjData* d, std::vector<unsigned char>* rgb, int* w,
                  int* h);

  // RGB, metric depth and segmentation from one camera of the model (`efc
  // synth`). The scene is updated once; segmentation is a second pass with
  // MuJoCo's id colours. Exact only without multisampling: build the renderer
  // after setting m->vis.quality.offsamples = 0, or edges blend ids.
  struct Views {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;  // width*height*3, top row first
    std::vector<float> depth;        // metres along the optical axis; 0 = nothing hit
    std::vector<int> geom;           // model geom id per pixel; -1 = background
  };
  bool render_views(const mjModel* m, mjData* d, int camera_id, bool depth, bool segmentation,
                    Views* out);

 private:
  bool ok_ = false;
  std::string error_;
  int width_ = 0;
  int height_ = 0;
  const OsMesaApi* osmesa_api_ = nullptr;  // loaded on first use
  void* osmesa_ = nullptr;               // OSMesaContext
  std::vector<unsigned char> osbuf_;     // OSMesa colour buffer (RGBA)
  bool scene_made_ = false;
  bool context_made_ = false;
  int camera_id_ = -1;                   // "efc_camera" or -1 (free camera)
  mjvScene scn_;
  mjrContext con_;
  mjvCamera cam_;
  mjvOption opt_;
};

// Writes an 8-bit RGB PNG (rgb: width*height*3, top row first).
bool write_png_rgb(const std::string& path, const unsigned char* rgb, int width,
                   int height, std::string* error);

}  // namespace efc

#endif  // EFC_HARNESS_RENDER_H_
