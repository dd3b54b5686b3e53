#include "pipeline/templates/frame_signals.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <thread>
#include <unordered_map>

#include <Eigen/Dense>

namespace efc::pipeline {
namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kMaskGrow = 2;          // px: a segmenter's ragged outline
constexpr double kRoiSide = 0.3;      // m around the effector, across
constexpr double kRoiAbove = 0.5;     // m above it (motes rise from vents)
constexpr double kSupportClear = 0.015;  // m above the object's lowest point
constexpr double kMinBlobGap = 0.015;  // m in front of the neighbourhood
constexpr double kMaskTrust = 0.015;   // m: a mask pixel this near its part's box is the part
constexpr int kMinEffectorPixels = 4;
// The runtime's red-hot (runtime/mujoco: a heated part's colour blends
// towards it; pipeline/ may not include runtime/).
constexpr double kHotRgb[3] = {1.0, 0.22, 0.04};
// hot_component(): the share of the frames, farthest from red-hot in
// chromaticity, whose mean is the part's own colour; and how far from
// red-hot's that colour must be for a blend towards it to show.
constexpr double kBaseShare = 0.2;
constexpr double kMinBaseToHot = 0.15;
constexpr int kBlobReach = 4;
constexpr double kMinBlobContrast = 24;  // grey levels: a blob unlike its surroundings
constexpr double kMaxBackgroundStep = 10;  // grey levels: ... which are alike
// A mote's streak is thin: of the pixels within kStreakReach, few share its
// colour (at most kMaxLikeShare). A lit patch of a white surface between a
// shadow's ragged teeth passes the blob test too, but it belongs to the lit
// surface around it, which fills much of that neighbourhood.
constexpr int kStreakReach = 8;
constexpr double kMaxLikeShare = 0.2;
constexpr double kFallSide = 0.15;     // m: droplets thrown forward as they fall
// The surround's luminance is compared point for point: object-frame cells
// of this size, each against its own mean over the frames that see it.
constexpr double kSurroundCell = 0.02;  // m


// A blob pixel's kind from its colour: 1 water blue (blue well above red,
// not below green: a droplet), 2 a bright near-grey streak (a mote: its
// channels within a fifth of each other and brighter than its surroundings
// on average), 0 neither (clutter, an edge, a shadow).
int blob_kind(const uint8_t* v, int reach, int W, size_t i, const uint8_t* px) {
  const int R = v[0], G = v[1], B = v[2];
  const int hi = std::max(R, std::max(G, B)), lo = std::min(R, std::min(G, B));
  if (B >= G && B - R >= std::max(12, hi / 4)) return 1;  // (0.35, 0.55, 0.95): B - R is 63 % of B
  if (hi - lo <= hi / 5) {
    double around = 0;
    const size_t offs[4] = {static_cast<size_t>(reach), static_cast<size_t>(reach) * W, 0, 0};
    for (int k = 0; k < 2; ++k) {
      const uint8_t* a = px + 3 * (i - offs[k]);
      const uint8_t* b = px + 3 * (i + offs[k]);
      around += (a[0] + a[1] + a[2] + b[0] + b[1] + b[2]) / 6.0;
    }
    if ((R + G + B) / 3.0 > around / 2 + 12) return 2;
  }
  return 0;
}

// The share of pixels within kStreakReach of pixel (x, y) whose colour is
// within kMinBlobContrast of its own, in every channel.
double like_share(const uint8_t* px, int W, int H, int x, int y) {
  const uint8_t* v = px + 3 * (static_cast<size_t>(y) * W + x);
  int like = 0, total = 0;
  for (int yy = std::max(0, y - kStreakReach); yy <= std::min(H - 1, y + kStreakReach); ++yy)
    for (int xx = std::max(0, x - kStreakReach); xx <= std::min(W - 1, x + kStreakReach); ++xx) {
      const uint8_t* q = px + 3 * (static_cast<size_t>(yy) * W + xx);
      ++total;
      like += std::abs(q[0] - v[0]) < kMinBlobContrast && std::abs(q[1] - v[1]) < kMinBlobContrast &&
              std::abs(q[2] - v[2]) < kMinBlobContrast;
    }
  return total ? static_cast<double>(like) / total : 1.0;
}

Eigen::AlignedBox3d moved(const Eigen::AlignedBox3d& b, const Eigen::Isometry3d& T) {
  Eigen::AlignedBox3d out;
  if (b.isEmpty()) return out;
  for (int c = 0; c < 8; ++c) out.extend(T * b.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)));
  return out;
}

// Grey mask dilated by r (separable square max filter).
std::vector<uint8_t> dilate(const std::vector<uint8_t>& m, int w, int h, int r) {
  std::vector<uint8_t> tmp(m.size()), out(m.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t v = 0;
      for (int d = -r; d <= r && !v; ++d) {
        const int xx = x + d;
        if (xx >= 0 && xx < w) v = m[y * w + xx];
      }
      tmp[y * w + x] = v;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t v = 0;
      for (int d = -r; d <= r && !v; ++d) {
        const int yy = y + d;
        if (yy >= 0 && yy < h) v = tmp[yy * w + x];
      }
      out[y * w + x] = v;
    }
  return out;
}

// A blob pixel seen from an effector's space: its kind (1 droplet, 2 mote),
// its area (m^2 at the effector), its point there, and how near its ray's
// passage through that space comes to the effector's box.
struct BlobClaim {
  size_t pixel;
  size_t effector;
  int kind;
  double area;
  Eigen::Vector3d at;
  double distance;
};

// Where the ray eye + t d (t: depth along the optical axis, t >= 0) is
// inside box b: [*t0, *t1]. False when it misses the box.
bool ray_passage(const Eigen::Vector3d& eye, const Eigen::Vector3d& d, const Eigen::AlignedBox3d& b, double* t0,
                 double* t1) {
  *t0 = 0, *t1 = 1e9;
  for (int k = 0; k < 3; ++k) {
    if (std::fabs(d[k]) < 1e-12) {
      if (eye[k] < b.min()[k] || eye[k] > b.max()[k]) return false;
      continue;
    }
    double a = (b.min()[k] - eye[k]) / d[k], c = (b.max()[k] - eye[k]) / d[k];
    if (a > c) std::swap(a, c);
    *t0 = std::max(*t0, a), *t1 = std::min(*t1, c);
  }
  return *t0 < *t1;
}

// The least distance to `box` of the ray eye + t d over its passage through
// `space` in front of the background at depth bg (0: none), sampled at
// kRaySamples points. (A blob is claimed only where its ray passes through
// part of `space`, so the passage is there.)
constexpr int kRaySamples = 16;
double ray_distance(const Eigen::Vector3d& eye, const Eigen::Vector3d& d, double bg,
                    const Eigen::AlignedBox3d& space, const Eigen::AlignedBox3d& box) {
  double t0, t1;
  if (!ray_passage(eye, d, space, &t0, &t1)) t1 = t0;
  if (bg > 0) t1 = std::min(t1, bg);
  if (!(t1 > t0)) t1 = t0;
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= kRaySamples; ++k) best = std::min(best, box.exteriorDistance(eye + d * (t0 + (t1 - t0) * k / kRaySamples)));
  return best;
}

// An object-frame point's cell, packed (20 bits a coordinate: +-10 km at 2 cm).
int64_t cell_of(const Eigen::Vector3d& p) {
  auto q = [](double v) { return (static_cast<int64_t>(std::floor(v / kSurroundCell)) + (1 << 19)) & 0xFFFFF; };
  return (q(p.x()) << 40) | (q(p.y()) << 20) | q(p.z());
}

}  // namespace

std::vector<double> surround_from_cells(const std::vector<std::vector<CellLum>>& frames) {
  std::vector<double> out(frames.size(), kNaN);
  // Each cell's mean over the frames that see it: (cell, its frame means'
  // sum, frames), sorted by cell.
  std::vector<std::pair<int64_t, double>> seen;
  for (const auto& f : frames)
    for (const CellLum& c : f) seen.push_back({c.cell, c.sum / c.count});
  std::sort(seen.begin(), seen.end());
  struct CellMean {
    int64_t cell;
    double sum;
    int frames;
  };
  std::vector<CellMean> mean;
  for (const auto& [cell, lum] : seen) {
    if (mean.empty() || mean.back().cell != cell) mean.push_back({cell, 0.0, 0});
    mean.back().sum += lum;
    ++mean.back().frames;
  }
  double grand = 0;
  long grand_n = 0;
  for (const CellMean& m : mean)
    if (m.frames >= 2) grand += m.sum / m.frames, ++grand_n;
  if (grand_n == 0) return out;
  grand /= grand_n;
  for (size_t f = 0; f < frames.size(); ++f) {
    double d = 0;
    long n = 0;
    for (const CellLum& c : frames[f]) {
      const auto it = std::lower_bound(mean.begin(), mean.end(), c.cell,
                                       [](const CellMean& m, int64_t key) { return m.cell < key; });
      if (it == mean.end() || it->cell != c.cell || it->frames < 2) continue;
      d += c.sum / c.count - it->sum / it->frames;
      ++n;
    }
    if (n > 0) out[f] = grand + d / n;
  }
  return out;
}

namespace {

struct Worker {
  const TemplateInput* in;
  const std::vector<int>* effectors;
  std::vector<std::vector<std::vector<CellLum>>>* surround_cells;  // [effector][frame]: shared, disjoint frames
  std::vector<EffectorSignals>* out;     // per-frame vectors: shared, disjoint frames
  std::vector<EffectorSignals> sums;     // this worker's blob sums
  int failed = 0;

  void frame(int f) {
    const seq::Sequence& S = *in->sequence;
    const seq::Meta& M = S.meta();
    if (f >= static_cast<int>(in->camera_to_world.size())) return;
    Diagnostics quiet;
    seq::Image8 rgb;
    if (!S.read_rgb(f, quiet, &rgb)) {
      ++failed;
      return;
    }
    const int W = rgb.width, H = rgb.height;
    const auto& names = S.mask_names();
    auto read_mask = [&](const std::string& name, seq::Image8* m) {
      if (!std::binary_search(names.begin(), names.end(), name)) return false;
      return S.read_mask(name, f, quiet, m) && m->width == W && m->height == H;
    };
    seq::Image8 hand;
    const bool have_hand = read_mask("hand", &hand);

    // Depth, and which part's mask each pixel is in (the hand's grown by a
    // segmenter's ragged outline).
    seq::Image16 depth;
    const bool have_depth = S.has_depth() && S.read_depth(f, quiet, &depth) && depth.width == W;
    // Every part's pixels (as segmented), and the hand's grown by a
    // segmenter's ragged outline: blobs are what no mask claims.
    // The movable parts' pixels (grown likewise) are left out of the
    // surround: a door moving through it is not its lighting.
    std::vector<uint8_t> taken(static_cast<size_t>(W) * H, 0), hand_grown, moving(taken.size(), 0);
    for (const PartObservation& q : in->parts) {
      seq::Image8 m;
      if (!read_mask(q.name, &m)) continue;
      const bool movable = !q.joint_type.empty() && q.joint_type != "fixed";
      for (size_t i = 0; i < taken.size(); ++i) {
        taken[i] |= m.pixels[i] ? 1 : 0;
        if (movable) moving[i] |= m.pixels[i] ? 1 : 0;
      }
    }
    if (have_hand) hand_grown = dilate(hand.pixels, W, H, kMaskGrow);
    moving = dilate(moving, W, H, kMaskGrow);
    const Eigen::Isometry3d obj_to_cam = in->camera_to_world[f].inverse() * in->object_to_world;
    const Eigen::Isometry3d cam_to_obj = obj_to_cam.inverse();
    const seq::Intrinsics& K = M.intrinsics;
    Eigen::AlignedBox3d object_box;
    for (const PartObservation& p : in->parts) {
      const Eigen::Isometry3d T = f < static_cast<int>(p.motion.size()) ? p.motion[f] : Eigen::Isometry3d::Identity();
      if (!p.bounds.isEmpty()) object_box.extend(moved(p.bounds, T));
    }
    std::vector<Eigen::AlignedBox3d> part_box(in->parts.size());
    for (size_t p = 0; p < in->parts.size(); ++p) {
      const PartObservation& q = in->parts[p];
      const Eigen::Isometry3d T = f < static_cast<int>(q.motion.size()) ? q.motion[f] : Eigen::Isometry3d::Identity();
      if (!q.bounds.isEmpty()) {
        part_box[p] = moved(q.bounds, T);
        part_box[p].extend(part_box[p].min() - Eigen::Vector3d::Constant(kMaskTrust));
        part_box[p].extend(part_box[p].max() + Eigen::Vector3d::Constant(kMaskTrust));
      }
    }
    // A pixel's object-frame point from its depth (NaN when none).
    auto point = [&](int x, int y) -> Eigen::Vector3d {
      const uint16_t d = have_depth ? depth.pixels[static_cast<size_t>(y) * W + x] : 0;
      if (!d) return Eigen::Vector3d::Constant(std::nan(""));
      const double z = d * M.depth_scale;
      return cam_to_obj * Eigen::Vector3d((x - K.cx) / K.fx * z, (y - K.cy) / K.fy * z, z);
    };
    double far_z = -1e9;
    if (!object_box.isEmpty())
      for (int c = 0; c < 8; ++c)
        far_z = std::max(far_z, (obj_to_cam * object_box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c))).z());

    std::vector<BlobClaim> claims;
    for (size_t e = 0; e < effectors->size(); ++e) {
      const PartObservation& part = in->parts[(*effectors)[e]];
      EffectorSignals& o = (*out)[e];
      EffectorSignals& s = sums[e];
      // ---- the effector's own pixels
      seq::Image8 m;
      const int pi = (*effectors)[e];
      if (read_mask(part.name, &m)) {
        // The mask's core (eroded as far as 2 px while enough is left: a
        // grown outline takes in the neighbours' colour), where the depth
        // agrees with the part's box.
        int mx0 = W, my0 = H, mx1 = -1, my1 = -1;
        for (int y = 0; y < H; ++y)
          for (int x = 0; x < W; ++x)
            if (m.pixels[static_cast<size_t>(y) * W + x]) mx0 = std::min(mx0, x), mx1 = std::max(mx1, x), my0 = std::min(my0, y), my1 = std::max(my1, y);
        std::vector<uint8_t> core = m.pixels;
        for (int r = 1; r <= kMaskGrow && mx1 >= 0; ++r) {
          std::vector<uint8_t> next(core.size(), 0);
          long left = 0;
          for (int y = my0; y <= my1; ++y)
            for (int x = mx0; x <= mx1; ++x) {
              const size_t i = static_cast<size_t>(y) * W + x;
              if (!core[i]) continue;
              bool inner = x > 0 && y > 0 && x < W - 1 && y < H - 1;
              for (int dy = -1; dy <= 1 && inner; ++dy)
                for (int dx = -1; dx <= 1 && inner; ++dx) inner = core[i + dy * W + dx] != 0;
              left += next[i] = inner;
            }
          if (left < kMinEffectorPixels) break;
          core.swap(next);
        }
        double lum = 0, red = 0, green = 0, blue = 0;
        long count = 0;
        for (int y = std::max(0, my0); y <= my1; ++y)
          for (int x = std::max(0, mx0); x <= mx1; ++x) {
            const size_t i = static_cast<size_t>(y) * W + x;
            if (!core[i] || (have_hand && hand.pixels[i])) continue;
            if (have_depth && !part_box[pi].isEmpty()) {
              const Eigen::Vector3d p = point(x, y);
              if (std::isfinite(p.x()) && !part_box[pi].contains(p)) continue;
            }
            const double R = rgb.pixels[3 * i], G = rgb.pixels[3 * i + 1], B = rgb.pixels[3 * i + 2];
            lum += 0.299 * R + 0.587 * G + 0.114 * B;
            red += R, green += G, blue += B;
            ++count;
          }
        if (count >= kMinEffectorPixels) {
          o.glow[f] = lum / count / 255.0;
          o.colour[f] = Eigen::Vector3d(red, green, blue) / (count * 255.0);  // heat: hot_component()
          ++s.frames_seen;
        }
      }
      // ---- blobs around it
      if (part.bounds.isEmpty() || object_box.isEmpty()) continue;
      const Eigen::Isometry3d T = f < static_cast<int>(part.motion.size()) ? part.motion[f] : Eigen::Isometry3d::Identity();
      const Eigen::AlignedBox3d eb = moved(part.bounds, T);
      // Below it (droplets fall) and around and above it (air blows out).
      const double floor_z = object_box.min().z() + kSupportClear;
      const Eigen::AlignedBox3d below(
          Eigen::Vector3d(eb.min().x() - kFallSide, eb.min().y() - kFallSide, floor_z),
          Eigen::Vector3d(eb.max().x() + kFallSide, eb.max().y() + kFallSide, std::max(floor_z + 0.01, eb.min().z())));
      const Eigen::AlignedBox3d around(
          Eigen::Vector3d(eb.min().x() - kRoiSide, eb.min().y() - kRoiSide, eb.min().z()),
          Eigen::Vector3d(eb.max().x() + kRoiSide, eb.max().y() + kRoiSide, eb.max().z() + kRoiAbove));
      Eigen::AlignedBox3d roi = below;
      roi.extend(around);
      double u0 = 1e9, v0 = 1e9, u1 = -1e9, v1 = -1e9;
      int front = 0;
      for (int c = 0; c < 8; ++c) {
        const Eigen::Vector3d pc = obj_to_cam * roi.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
        if (pc.z() < 0.05) continue;
        ++front;
        const double u = K.fx * pc.x() / pc.z() + K.cx, v = K.fy * pc.y() / pc.z() + K.cy;
        u0 = std::min(u0, u), u1 = std::max(u1, u), v0 = std::min(v0, v), v1 = std::max(v1, v);
      }
      if (front == 0) continue;  // all behind the camera
      if (front < 8) u0 = v0 = -1e9, u1 = v1 = 1e9;  // the camera is inside it or beside it: look everywhere
      const int x0 = std::max(kBlobReach, static_cast<int>(std::floor(std::max(u0, -1.0)))),
                x1 = std::min(W - 1 - kBlobReach, static_cast<int>(std::ceil(std::min(u1, double(W)))));
      const int y0 = std::max(kBlobReach, static_cast<int>(std::floor(std::max(v0, -1.0)))),
                y1 = std::min(H - 1 - kBlobReach, static_cast<int>(std::ceil(std::min(v1, double(H)))));
      if (x1 <= x0 || y1 <= y0) continue;  // out of view: not observed
      const Eigen::Vector3d eye = cam_to_obj.translation();
      const Eigen::Matrix3d Rco = cam_to_obj.linear();
      const double ez = std::max(0.1, (obj_to_cam * eb.center()).z());
      const double px_area = (ez / K.fx) * (ez / K.fy);  // m^2 per pixel at the effector
      // Where a ray (t = depth along the optical axis) is inside a box.
      auto through = [&](const Eigen::AlignedBox3d& b, const Eigen::Vector3d& d, double bg, Eigen::Vector3d* at) {
        double t0, t1;
        if (!ray_passage(eye, d, b, &t0, &t1) || (bg > 0 && t0 >= bg)) return false;  // misses it, or the background is in front
        *at = eye + d * (0.5 * (t0 + std::min(t1, bg > 0 ? bg : t1)));
        return true;
      };
      // Every other row and column at 640 x 480 and above: a droplet there is
      // two pixels or more across, and the scan is the stage's main cost.
      const int stride = W >= 600 ? 2 : 1;
      const double px_count = px_area * stride * stride;
      o.droplets[f] = o.motes[f] = 0;  // observed: the claims below add to them
      // The surround's pixels (static surface points in the space), summed
      // per cell; neighbouring pixels mostly share one.
      std::vector<CellLum> lit;
      std::unordered_map<int64_t, size_t> lit_at;
      size_t last = 0;
      for (int y = y0; y <= y1; y += stride)
        for (int x = x0; x <= x1; x += stride) {
          const size_t i = static_cast<size_t>(y) * W + x;
          if (!hand_grown.empty() && hand_grown[i]) continue;
          if (!moving[i]) {
            const Eigen::Vector3d p = point(x, y);
            if (std::isfinite(p.x()) && roi.contains(p)) {
              const uint8_t* c = &rgb.pixels[3 * i];
              const int64_t cell = cell_of(p);
              if (lit.empty() || lit[last].cell != cell) {
                const auto [it, fresh] = lit_at.emplace(cell, lit.size());
                if (fresh) lit.push_back({cell, 0.0, 0});
                last = it->second;
              }
              lit[last].sum += (0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2]) / 255.0;
              ++lit[last].count;
            }
          }
          if (taken[i]) continue;
          // A small blob in colour: unlike both neighbours across it, which
          // are alike (so not an edge between two surfaces).
          bool blob = false;
          const uint8_t* v = &rgb.pixels[3 * i];
          for (int r = 1; r <= kBlobReach && !blob; ++r) {
            for (int axis = 0; axis < 2 && !blob; ++axis) {
              const size_t step = axis ? static_cast<size_t>(r) * W : static_cast<size_t>(r);
              const uint8_t* a = v - 3 * step;
              const uint8_t* b = v + 3 * step;
              double contrast = 0;
              for (int k = 0; k < 3; ++k)
                contrast = std::max(contrast, static_cast<double>(std::min(std::abs(v[k] - a[k]), std::abs(v[k] - b[k]))));
              if (contrast < kMinBlobContrast) continue;  // most pixels stop here
              double apart = 0;
              for (int k = 0; k < 3; ++k) apart = std::max(apart, static_cast<double>(std::abs(a[k] - b[k])));
              blob = apart <= kMaxBackgroundStep;
            }
          }
          if (!blob) continue;
          // The blob's colour says what it is (the renderers' materials):
          // a droplet is water blue (0.35, 0.55, 0.95), a mote a near-white
          // streak (0.92, 0.95, 1) brighter than what is behind it. Shading
          // scales the channels alike, so the tests are on their order and
          // spread, not on levels.
          const int kind = blob_kind(v, kBlobReach, W, i, rgb.pixels.data());
          if (kind == 0) continue;
          if (kind == 2 && like_share(rgb.pixels.data(), W, H, x, y) > kMaxLikeShare) continue;
          const Eigen::Vector3d d = Rco * Eigen::Vector3d((x - K.cx) / K.fx, (y - K.cy) / K.fy, 1.0);
          const double bg = have_depth && depth.pixels[i] ? depth.pixels[i] * M.depth_scale : 0;
          Eigen::Vector3d at;
          const bool inside = kind == 1 ? through(below, d, bg, &at) || through(around, d, bg, &at)
                                        : through(around, d, bg, &at) || through(below, d, bg, &at);
          if (inside) claims.push_back({i, e, kind, px_count, at, ray_distance(eye, d, bg, roi, eb)});
        }
      std::sort(lit.begin(), lit.end(), [](const CellLum& a, const CellLum& b) { return a.cell < b.cell; });
      (*surround_cells)[e][f] = std::move(lit);
    }
    settle_claims(f, &claims);
  }

  // A blob seen from several effectors' spaces (a vent's motes rise past a
  // lamp beside it) is theirs only whose box its ray passes nearest: each
  // pixel counts once, for one effector.
  void settle_claims(int f, std::vector<BlobClaim>* claims) {
    std::stable_sort(claims->begin(), claims->end(), [](const BlobClaim& a, const BlobClaim& b) {
      return a.pixel != b.pixel ? a.pixel < b.pixel : a.distance < b.distance;
    });
    int owner = -1;  // the part the current pixel went to (an effector listed twice gets it twice)
    for (size_t k = 0; k < claims->size(); ++k) {
      const BlobClaim& c = (*claims)[k];
      const int part = (*effectors)[c.effector];
      if (k == 0 || c.pixel != (*claims)[k - 1].pixel) owner = part;
      else if (part != owner) continue;  // a nearer effector has it
      EffectorSignals& o = (*out)[c.effector];
      EffectorSignals& s = sums[c.effector];
      if (c.kind == 1) {
        o.droplets[f] += c.area;
        s.droplet_sum += c.at;
        ++s.droplet_points;
        s.droplet_top_z = std::max(s.droplet_top_z, c.at.z());
      } else {
        o.motes[f] += c.area;
        s.mote_sum += c.at;
        ++s.mote_points;
      }
    }
  }
};

}  // namespace

std::vector<EffectorSignals> measure_effectors(const TemplateInput& input, const std::vector<int>& effectors,
                                               int threads, int* frames_failed) {
  std::vector<EffectorSignals> out(effectors.size());
  *frames_failed = 0;
  if (!input.sequence) return out;
  const int N = input.sequence->meta().frames;
  for (EffectorSignals& s : out) {
    s.glow = s.heat = s.droplets = s.motes = s.surround = std::vector<double>(N, kNaN);
    s.colour.assign(N, Eigen::Vector3d::Constant(kNaN));
  }
  const int T = std::clamp(threads, 1, 16);
  std::vector<Worker> workers(T);
  std::vector<std::vector<std::vector<CellLum>>> surround_cells(effectors.size(), std::vector<std::vector<CellLum>>(N));
  for (Worker& w : workers) {
    w.in = &input;
    w.effectors = &effectors;
    w.surround_cells = &surround_cells;
    w.out = &out;
    w.sums.resize(effectors.size());
  }
  auto run = [&](int k) {
    for (int f = k; f < N; f += T) workers[k].frame(f);
  };
  std::vector<std::thread> pool;
  for (int k = 1; k < T; ++k) pool.emplace_back(run, k);
  run(0);
  for (std::thread& t : pool) t.join();
  for (const Worker& w : workers) {
    *frames_failed += w.failed;
    for (size_t e = 0; e < effectors.size(); ++e) {
      const EffectorSignals& s = w.sums[e];
      out[e].frames_seen += s.frames_seen;
      out[e].droplet_sum += s.droplet_sum;
      out[e].mote_sum += s.mote_sum;
      out[e].droplet_points += s.droplet_points;
      out[e].mote_points += s.mote_points;
      out[e].droplet_top_z = std::max(out[e].droplet_top_z, s.droplet_top_z);
    }
  }
  for (size_t e = 0; e < effectors.size(); ++e) {
    out[e].surround = surround_from_cells(surround_cells[e]);
    out[e].heat = hot_component(out[e].colour);
  }
  for (EffectorSignals& s : out) s.frames_read = N - *frames_failed;
  return out;
}

std::vector<double> hot_component(const std::vector<Eigen::Vector3d>& colour) {
  std::vector<double> out(colour.size(), kNaN);
  // Each frame's chromaticity, and how far it is from red-hot's.
  const Eigen::Vector3d hot = Eigen::Vector3d(kHotRgb[0], kHotRgb[1], kHotRgb[2]) / (kHotRgb[0] + kHotRgb[1] + kHotRgb[2]);
  std::vector<std::pair<double, int>> far;
  std::vector<Eigen::Vector3d> chroma(colour.size(), Eigen::Vector3d::Constant(kNaN));
  for (size_t f = 0; f < colour.size(); ++f) {
    const Eigen::Vector3d& c = colour[f];
    if (!c.allFinite() || c.sum() <= 0) continue;
    chroma[f] = c / c.sum();
    far.push_back({(chroma[f] - hot).norm(), static_cast<int>(f)});
  }
  if (far.empty()) return out;
  // The part's own colour: the mean chromaticity of the frames farthest
  // from red-hot's (kBaseShare of them): the frames it was coolest in.
  const size_t take = std::max<size_t>(1, static_cast<size_t>(kBaseShare * far.size()));
  std::partial_sort(far.begin(), far.begin() + static_cast<std::ptrdiff_t>(take), far.end(), std::greater<>());
  Eigen::Vector3d base = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < take; ++k) base += chroma[far[k].second];
  base /= static_cast<double>(take);
  if ((base - hot).norm() < kMinBaseToHot) {
    // A part coloured like red-hot itself: heat barely shifts its colour;
    // its red chromaticity is what there is.
    for (size_t f = 0; f < colour.size(); ++f)
      if (chroma[f].allFinite()) out[f] = chroma[f].x();
    return out;
  }
  Eigen::Matrix<double, 3, 2> A;
  A.col(0) = base;
  A.col(1) = hot;
  const Eigen::LDLT<Eigen::Matrix2d> normal(A.transpose() * A);
  // Never below 0: a colour farther from red-hot than the part's own is
  // noise, or a light of another colour, not a part colder than cold.
  for (size_t f = 0; f < colour.size(); ++f)
    if (chroma[f].allFinite()) out[f] = std::max(0.0, normal.solve(A.transpose() * colour[f])(1));
  return out;
}

std::vector<double> pose_shading_removed(const std::vector<double>& y, const std::vector<double>& q) {
  std::vector<int> rows;
  for (size_t i = 0; i < y.size() && i < q.size(); ++i)
    if (std::isfinite(y[i]) && std::isfinite(q[i])) rows.push_back(static_cast<int>(i));
  if (rows.size() < 6) return y;
  Eigen::MatrixXd A(rows.size(), 3);
  Eigen::VectorXd b(rows.size());
  for (size_t r = 0; r < rows.size(); ++r) {
    const double x = q[rows[r]];
    A.row(r) << 1.0, x, x * x;
    b(r) = y[rows[r]];
  }
  const Eigen::VectorXd c = A.colPivHouseholderQr().solve(b);
  std::vector<double> out = y;
  for (size_t r = 0; r < rows.size(); ++r) out[rows[r]] = b(r) - A.row(r).dot(c) + c(0);
  return out;
}

}  // namespace efc::pipeline
