// Depth sensor noise: what a structured-light / active-stereo camera does to
// a perfect depth image. Per pixel, in this order:
//   1. lateral edge noise: at a depth jump the pixel may take its neighbour's
//      reading (the matching window straddles the edge: ~0.8 px lateral sigma);
//   2. grazing dropouts: the pattern is stretched beyond recognition when the
//      surface is seen edge-on (incidence > ~70 deg, nothing at ~85 deg);
//   3. dark dropouts: a low-albedo surface returns too little IR light;
//   4. speckle dropouts: isolated pixels lost to interference and saturation;
//   5. axial noise sigma = s0 + k (z - z0)^2: triangulation turns a constant
//      disparity error into a depth error growing with z^2;
//   6. disparity quantisation: the sensor measures disparity d = f b / z in
//      1/8 pixel steps, so depth comes in steps of z^2 / (8 f b);
//   7. working range: readings outside [min, max] are dropped.
// Neighbours are read from the unmodified input, so the result does not
// depend on the scan order beyond the random stream.
#include <algorithm>
#include <cmath>

#include "synth/image/noise.h"

namespace efc::synth {
namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

bool depth_noise_off(const NoiseParams& p) {
  return p.depth_sigma0_m == 0 && p.depth_sigma_k == 0 && p.depth_min_m <= 0 &&
         p.depth_max_m <= 0 && p.depth_grazing_start_deg >= 90 && p.depth_dark_max_prob <= 0 &&
         p.depth_speckle_prob <= 0 && p.depth_edge_shift_prob <= 0 &&
         (p.depth_baseline_m <= 0 || p.depth_disparity_step_px <= 0);
}

// Of the two neighbours along one image axis (at i - stride and i + stride),
// the one on the same surface: the valid one whose depth differs least (at an
// occlusion edge the other side belongs to another surface). Returns -1 or +1
// for the side, 0 when neither has a reading.
int smoother_side(const float* depth, int i, int stride, bool has_before, bool has_after) {
  const float z = depth[i];
  const bool b = has_before && depth[i - stride] > 0;
  const bool a = has_after && depth[i + stride] > 0;
  if (a && b) return std::fabs(depth[i + stride] - z) <= std::fabs(depth[i - stride] - z) ? 1 : -1;
  return a ? 1 : (b ? -1 : 0);
}

// cos^2(incidence): the angle between the viewing ray and the surface normal,
// the normal from the back-projected neighbours (P = z (ax, by, 1)). 1 (head
// on) where the neighbours cannot tell. Squared: the common case (well below
// the threshold) needs no square root.
double incidence_cos2(const float* depth, int w, int h, int x, int y, const double* ax,
                      const double* by) {
  const int i = y * w + x;
  const int sx = smoother_side(depth, i, 1, x > 0, x + 1 < w);
  const int sy = smoother_side(depth, i, w, y > 0, y + 1 < h);
  if (sx == 0 || sy == 0) return 1.0;
  const double z = depth[i];
  const double px = z * ax[x], py = z * by[y];
  const double zx = depth[i + sx], zy = depth[i + sy * w];
  // Tangents towards the chosen neighbours (their signs do not matter).
  const double tx0 = zx * ax[x + sx] - px, tx1 = zx * by[y] - py, tx2 = zx - z;
  const double ty0 = zy * ax[x] - px, ty1 = zy * by[y + sy] - py, ty2 = zy - z;
  const double n0 = tx1 * ty2 - tx2 * ty1;
  const double n1 = tx2 * ty0 - tx0 * ty2;
  const double n2 = tx0 * ty1 - tx1 * ty0;
  const double r0 = ax[x], r1 = by[y];
  const double nn = n0 * n0 + n1 * n1 + n2 * n2;
  if (!(nn > 0)) return 1.0;
  const double dot = n0 * r0 + n1 * r1 + n2;
  return dot * dot / (nn * (r0 * r0 + r1 * r1 + 1.0));
}

}  // namespace

void add_depth_noise(const NoiseParams& p, const seq::Intrinsics& K, int width, int height,
                     const uint8_t* rgb, std::vector<float>* depth_m, Rng& rng) {
  if (!depth_m || width <= 0 || height <= 0) return;
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
  if (depth_m->size() != n || depth_noise_off(p)) return;

  const std::vector<float> truth = *depth_m;  // neighbours must stay noise-free
  const float* in = truth.data();
  float* out = depth_m->data();

  // Viewing rays per column and row (OpenCV pinhole); without intrinsics
  // there is no geometry, so no grazing dropouts and no disparity.
  const bool has_geometry = K.fx > 0 && K.fy > 0;
  std::vector<double> ax(width, 0.0), by(height, 0.0);
  if (has_geometry) {
    for (int x = 0; x < width; ++x) ax[x] = (x - K.cx) / K.fx;
    for (int y = 0; y < height; ++y) by[y] = (y - K.cy) / K.fy;
  }
  const bool grazing = has_geometry && p.depth_grazing_start_deg < 90;
  const double graze_start = p.depth_grazing_start_deg;
  const double graze_span = std::max(1e-6, p.depth_grazing_full_deg - p.depth_grazing_start_deg);
  const double cos_start = std::cos(graze_start * kDegToRad);
  const double cos2_start = cos_start * cos_start;
  const bool dark = rgb && p.depth_dark_max_prob > 0 && p.depth_dark_luma > 0;
  const double fb = has_geometry ? K.fx * p.depth_baseline_m : 0.0;  // disparity x depth, px m
  const bool quantise = fb > 0 && p.depth_disparity_step_px > 0;
  const double step = p.depth_disparity_step_px;
  const double max_m = p.depth_max_m > 0 ? p.depth_max_m : HUGE_VAL;

  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const int i = y * width + x;
      double z = in[i];
      if (!(z > 0) || !std::isfinite(z)) {
        out[i] = 0;
        continue;
      }
      // 1. Lateral edge noise: only matters where depth jumps.
      if (p.depth_edge_shift_prob > 0 && rng.chance(p.depth_edge_shift_prob)) {
        int dir = rng.integer(0, 3);
        int j = i;
        if (dir == 0 && x > 0) j = i - 1;
        if (dir == 1 && x + 1 < width) j = i + 1;
        if (dir == 2 && y > 0) j = i - width;
        if (dir == 3 && y + 1 < height) j = i + width;
        if (std::fabs(in[j] - z) > p.depth_edge_jump_rel * z) z = in[j];
        if (!(z > 0)) {  // the neighbour had no reading: the edge pixel is lost
          out[i] = 0;
          continue;
        }
      }
      // 2. Grazing incidence: probability ramps linearly in angle.
      if (grazing) {
        double c2 = incidence_cos2(in, width, height, x, y, ax.data(), by.data());
        if (c2 < cos2_start) {
          double angle = std::acos(std::sqrt(c2)) / kDegToRad;
          double prob = (angle - graze_start) / graze_span;
          if (rng.chance(prob)) {
            out[i] = 0;
            continue;
          }
        }
      }
      // 3. Dark surfaces: visible luminance stands in for IR albedo.
      if (dark) {
        const uint8_t* c = rgb + 3 * static_cast<size_t>(i);
        double luma = (0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2]) * (1.0 / 255.0);
        if (luma < p.depth_dark_luma) {
          double prob = p.depth_dark_max_prob * (1.0 - luma / p.depth_dark_luma);
          if (rng.chance(prob)) {
            out[i] = 0;
            continue;
          }
        }
      }
      // 4. Speckle.
      if (p.depth_speckle_prob > 0 && rng.chance(p.depth_speckle_prob)) {
        out[i] = 0;
        continue;
      }
      // 5. Axial noise.
      double dz = z - p.depth_sigma_z0_m;
      double sigma = p.depth_sigma0_m + p.depth_sigma_k * dz * dz;
      if (sigma > 0) z += sigma * rng.normal();
      // 6. Disparity quantisation.
      if (quantise && z > 0) {
        double d = std::nearbyint(fb / z / step) * step;
        z = d > 0 ? fb / d : 0.0;
      }
      // 7. Working range.
      if (!(z >= p.depth_min_m) || z > max_m) z = 0;
      out[i] = static_cast<float>(z);
    }
  }
}

seq::Image16 quantize_depth(const std::vector<float>& depth_m, int width, int height,
                            double depth_scale) {
  seq::Image16 img;
  img.width = std::max(0, width);
  img.height = std::max(0, height);
  const size_t n = static_cast<size_t>(img.width) * static_cast<size_t>(img.height);
  img.pixels.assign(n, 0);
  if (!(depth_scale > 0) || !std::isfinite(depth_scale)) return img;
  const double inv = 1.0 / depth_scale;
  const size_t m = std::min(n, depth_m.size());
  for (size_t i = 0; i < m; ++i) {
    double z = depth_m[i];
    if (!(z > 0) || !std::isfinite(z)) continue;
    double units = std::floor(z * inv + 0.5);  // round half up
    if (units <= 65535.0) img.pixels[i] = static_cast<uint16_t>(units);  // beyond: no reading
  }
  return img;
}

}  // namespace efc::synth
