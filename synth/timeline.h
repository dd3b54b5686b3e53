// When the hand does what: the camera approaches, then the hand reaches each
// profile-driven receptor in turn, grasps it, moves it through the user's
// profile, lets go and moves on; at the end it withdraws. The receptors'
// targets over the whole run become one csv profile (a knot per physics
// step), which the playback follows and truth/profile.csv records, so
// `efc play --profile csv:truth/profile.csv` replays the same run.
#pragma once

#include <string>
#include <vector>

#include "compiler/ir.h"
#include "runtime/efc_profile.h"

namespace efc::synth {

struct Visit {
  int part = -1;  // the receptor (index into Object::parts)
  double reach = 0, grasp = 0, release = 0, leave = 0;  // s: hand leaves rest, holds, lets go, gone
};

struct Timeline {
  double duration = 0;        // s (frames / fps)
  double approach = 0;        // s: the wearer walks up until then
  std::vector<Visit> visits;  // in time order
  Profile profile;            // Kind::Csv, one column per profile-driven receptor
};

// 0 below 0, 1 above 1, a smooth S between: eases every move in and out.
inline double smoothstep(double x) {
  x = x < 0 ? 0 : (x > 1 ? 1 : x);
  return x * x * (3 - 2 * x);
}

// At most this many receptors are operated; the others hold where they start.
constexpr int kMaxVisits = 6;

Timeline plan_timeline(const Object& obj, const Profile& user, double duration, double dt);

// truth/profile.csv: t and one column per receptor, every knot, numbers that
// read back to the same doubles (%.17g).
std::string profile_csv(const Timeline& timeline);

}  // namespace efc::synth
