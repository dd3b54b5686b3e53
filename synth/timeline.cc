#include "synth/timeline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "backends/common/lowering.h"

namespace efc::synth {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The range a profile sweeps, as `efc play` takes it: the joint's limits, or
// one turn for a continuous receptor.
void profile_range(const Joint& j, double* lo, double* hi) {
  if (j.has_range) {
    *lo = j.lo;
    *hi = j.hi;
  } else {
    *lo = 0;
    *hi = 2 * kPi;
  }
}

}  // namespace

Timeline plan_timeline(const Object& obj, const Profile& user, double duration, double dt) {
  Timeline T;
  T.duration = duration;
  T.approach = std::clamp(0.18 * duration, 0.3, 2.0);
  const double retreat = std::clamp(0.08 * duration, 0.2, 1.0);
  std::vector<int> receptors = lowering::profile_driven_receptors(obj);
  const int n = std::min<int>(static_cast<int>(receptors.size()), kMaxVisits);
  const double slot = n > 0 ? std::max(0.0, duration - T.approach - retreat) / n : 0;
  for (int i = 0; i < n; ++i) {
    Visit v;
    v.part = receptors[i];
    v.reach = T.approach - 0.5 * std::min(0.6, 0.15 * slot) + i * slot;
    v.grasp = v.reach + std::min(0.6, 0.15 * slot);
    v.leave = T.approach + (i + 1) * slot;
    v.release = v.leave - std::min(0.4, 0.1 * slot);
    T.visits.push_back(v);
  }

  Profile& P = T.profile;
  P.kind = Profile::Kind::Csv;
  P.text = "csv:truth/profile.csv";
  P.csv_path = "truth/profile.csv";
  const long steps = std::lround(duration / dt);
  for (long k = 0; k <= steps; ++k) P.csv_t.push_back(k * dt);
  for (int pi : receptors) {
    const Part& part = obj.parts[pi];
    const Joint& j = *part.joint;
    double lo, hi;
    profile_range(j, &lo, &hi);
    const double q0 = j.initial.value_or(0.0);
    const Visit* visit = nullptr;
    for (const Visit& v : T.visits)
      if (v.part == pi) visit = &v;
    // Held at the profile's start until grasped, through the profile while
    // held, at its end afterwards; never visited: held at its start.
    const double span = visit ? visit->release - visit->grasp : duration;
    std::vector<double>& q = P.csv_parts[part.name];
    q.reserve(P.csv_t.size());
    for (double t : P.csv_t) {
      const double local = visit ? std::clamp(t - visit->grasp, 0.0, span) : 0.0;
      double target = profile_target(user, part.name, lo, hi, q0, local, span);
      if (j.has_range) target = std::clamp(target, j.lo, j.hi);
      q.push_back(target);
    }
  }
  return T;
}

std::string profile_csv(const Timeline& timeline) {
  const Profile& P = timeline.profile;
  std::string out = "t";
  for (const auto& [name, values] : P.csv_parts) out += "," + name;
  out += "\n";
  char buf[40];
  for (size_t k = 0; k < P.csv_t.size(); ++k) {
    std::snprintf(buf, sizeof buf, "%.17g", P.csv_t[k]);
    out += buf;
    for (const auto& [name, values] : P.csv_parts) {
      std::snprintf(buf, sizeof buf, ",%.17g", values[k]);
      out += buf;
    }
    out += "\n";
  }
  return out;
}

}  // namespace efc::synth
