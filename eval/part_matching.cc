#include "eval/part_matching.h"

#include <limits>

#include "compiler/geometry/vec.h"

namespace efc::eval {

namespace {

Vec3 world_bbox_centre(const Part& p, const WorldFrame& world) {
  return world.point(geom::mul(geom::add(p.bbox_min, p.bbox_max), 0.5));
}

}  // namespace

std::vector<int> match_parts(const Object& gt, const WorldFrame& gt_world, const Object& pred,
                             const WorldFrame& pred_world) {
  std::vector<int> match(gt.parts.size(), -1);
  std::vector<bool> taken(pred.parts.size(), false);
  for (size_t g = 0; g < gt.parts.size(); ++g) {
    const int p = pred.find_part(gt.parts[g].name);
    if (p >= 0) match[g] = p, taken[p] = true;
  }
  for (size_t g = 0; g < gt.parts.size(); ++g) {
    if (match[g] >= 0) continue;
    const Vec3 centre = world_bbox_centre(gt.parts[g], gt_world);
    double best = std::numeric_limits<double>::infinity();
    for (size_t p = 0; p < pred.parts.size(); ++p) {
      if (taken[p] || pred.parts[p].role != gt.parts[g].role) continue;
      const double d = geom::norm(geom::sub(world_bbox_centre(pred.parts[p], pred_world), centre));
      if (d < best) best = d, match[g] = static_cast<int>(p);
    }
    if (match[g] >= 0) taken[match[g]] = true;
  }
  return match;
}

}  // namespace efc::eval
