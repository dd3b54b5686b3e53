// check_resolved(): the rules that need the values resolve() fills in
// (default thresholds, default effect ranges). It also works on an object
// that was not resolved: absent optional values are simply skipped.
#include <algorithm>
#include <cmath>

#include "compiler/frontend/check.h"

namespace efc {
namespace {

std::string num(double v) { return nlohmann::json(v).dump(); }

bool valid_index(const Object& obj, int i) {
  return i >= 0 && static_cast<size_t>(i) < obj.parts.size();
}

// A receptor's joint range for threshold checks; false when any finite value
// is fine (continuous joints, which playback sweeps over [0, 2 pi]) or the
// range is unknown.
bool bounded_range(const Part& p, double* lo, double* hi) {
  if (!p.joint || p.joint->type == JointType::Continuous || !p.joint->has_range) return false;
  *lo = p.joint->lo;
  *hi = p.joint->hi;
  return true;
}

void check_threshold(const Object& obj, size_t i, Diagnostics& d) {
  const Function& f = obj.functions[i];
  const Mapping& m = f.mapping;
  if (m.type == MappingType::Linear || !m.threshold || !valid_index(obj, f.receptor_index)) return;
  const std::string ptr = "/functions/" + std::to_string(i) + "/mapping/threshold";
  double lo, hi;
  if (!bounded_range(obj.parts[f.receptor_index], &lo, &hi)) {
    if (!std::isfinite(*m.threshold))
      report(d, obj, "E0318", ptr, "threshold of '" + f.name + "' is not finite");
    return;
  }
  if (*m.threshold < lo || *m.threshold > hi)
    report(d, obj, "E0318", ptr,
           "threshold " + num(*m.threshold) + " of '" + f.name + "' is outside receptor '" +
               f.receptor + "' range [" + num(lo) + ", " + num(hi) + "]",
           "the receptor never gets there; pick a value inside the range (or leave it out)");
}

// A geometry effect's [off, on] lies inside its effector joint's range.
void check_geometry_range(const Object& obj, size_t i, Diagnostics& d) {
  const Function& f = obj.functions[i];
  const Effect& e = f.effect;
  if (e.type != EffectType::Geometry || !e.has_range || !valid_index(obj, f.effector_index)) return;
  double lo, hi;
  if (!bounded_range(obj.parts[f.effector_index], &lo, &hi)) return;
  const std::string ptr = "/functions/" + std::to_string(i) + "/effect/range";
  for (int k = 0; k < 2; ++k) {
    double v = k ? e.hi : e.lo;
    if (v < lo || v > hi)
      report(d, obj, "E0320", ptr + "/" + std::to_string(k),
             "geometry effect of '" + f.name + "' targets " + num(v) + ", outside joint '" +
                 f.effector + "' range [" + num(lo) + ", " + num(hi) + "]",
             "keep both ends inside the joint's range (or leave the range out to use it)");
  }
}

// A cumulative mapping's initial state lies between the effect's two ends.
void check_cumulative_initial(const Object& obj, size_t i, Diagnostics& d) {
  const Function& f = obj.functions[i];
  const Mapping& m = f.mapping;
  if (m.type != MappingType::Cumulative || !m.initial || !f.effect.has_range) return;
  double lo = std::min(f.effect.lo, f.effect.hi), hi = std::max(f.effect.lo, f.effect.hi);
  if (*m.initial < lo || *m.initial > hi)
    report(d, obj, "E0321", "/functions/" + std::to_string(i) + "/mapping/initial",
           "cumulative initial " + num(*m.initial) + " of '" + f.name +
               "' is outside the effect range [" + num(f.effect.lo) + ", " + num(f.effect.hi) + "]",
           "the state is clamped between the effect's ends; start inside them");
}

}  // namespace

void check_resolved(const Object& obj, Diagnostics& out) {
  Diagnostics diags;
  for (size_t i = 0; i < obj.functions.size(); ++i) {
    check_threshold(obj, i, diags);
    check_geometry_range(obj, i, diags);
    check_cumulative_initial(obj, i, diags);
  }
  append_in_file_order(diags, out);
}

}  // namespace efc
