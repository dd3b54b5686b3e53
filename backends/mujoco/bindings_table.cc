// build_bindings: the function table (efc_mj::FunctionBinding rows) in
// evaluation order. Both `efc play` and the generated callbacks use exactly
// these rows, so the in-memory and the compiled controller agree bit for bit.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "backends/mujoco/mjcf_internal.h"
#include "backends/mujoco/mujoco_backend.h"

namespace efc {

namespace {

constexpr double kPi = 3.14159265358979323846;
// The most droplets one fluid effect keeps alive: 300 colliding droplets step
// at about 1,400 steps/s on the reference machine, so 200 per emitter keeps
// playback faster than real time; a faster flow recycles droplets sooner.
constexpr int kMaxDroplets = 200;
constexpr int kMinDroplets = 8;
constexpr int kMaxKeyframeQpos = 1000;

void copy_name(char* dst, size_t cap, const std::string& s) {
  std::memset(dst, 0, cap);
  std::strncpy(dst, s.c_str(), cap - 1);
}

int part_index(const Object& obj, int index, const std::string& name) {
  return index >= 0 ? index : obj.find_part(name);
}

// Functions in topological order over chains (a function whose receptor is
// another function's effector runs after it); ties keep spec order.
std::vector<int> evaluation_order(const Object& obj) {
  const size_t n = obj.functions.size();
  std::vector<int> order, indegree(n, 0);
  std::vector<std::vector<int>> after(n);
  for (size_t a = 0; a < n; ++a)
    for (size_t b = 0; b < n; ++b)
      if (a != b && obj.functions[b].receptor == obj.functions[a].effector) {
        after[a].push_back(static_cast<int>(b));
        indegree[b]++;
      }
  std::vector<bool> done(n, false);
  while (order.size() < n) {
    int next = -1;
    for (size_t i = 0; i < n && next < 0; ++i)
      if (!done[i] && indegree[i] == 0) next = static_cast<int>(i);
    if (next < 0)  // a cycle (check() rejects these): keep spec order for the rest
      for (size_t i = 0; i < n && next < 0; ++i)
        if (!done[i]) next = static_cast<int>(i);
    done[next] = true;
    order.push_back(next);
    for (int b : after[next]) indegree[b]--;
  }
  return order;
}

Vec3 unit(const Vec3& v, const Vec3& fallback) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(n > 0)) return fallback;
  return {v[0] / n, v[1] / n, v[2] / n};
}

}  // namespace

namespace mjcf {

double droplet_volume_litres(double radius) { return 4.0 / 3.0 * kPi * radius * radius * radius * 1000.0; }

int droplet_pool_size(const Effect& e) {
  const double radius = e.droplet_radius.value_or(0.004);
  efc_rt::EffectParams p{efc_rt::kFluid, e.lo, e.hi, 0, droplet_volume_litres(radius)};
  const double peak = std::max(std::fabs(e.lo), std::fabs(e.hi));
  const double alive = std::ceil(efc_rt::droplet_rate(p, peak) * efc_mj::kDropletLifetime);
  return static_cast<int>(std::clamp(alive, double(kMinDroplets), double(kMaxDroplets)));
}

std::vector<int> droplet_pool_sizes(const Object& obj) {
  std::vector<int> sizes(obj.functions.size(), 0);
  int object_nq = 0, wanted = 0;
  for (const Part& p : obj.parts) object_nq += p.joint && p.joint->movable() ? 1 : 0;
  for (size_t i = 0; i < obj.functions.size(); ++i)
    if (obj.functions[i].effect.type == EffectType::Fluid)
      wanted += sizes[i] = droplet_pool_size(obj.functions[i].effect);
  // MuJoCo 2.2 reads at most 1000 numbers in a keyframe's qpos, and the
  // "initial" key must list every qpos (7 per droplet): share what is left
  // after the object's joints among the pools, in proportion.
  const int budget = (kMaxKeyframeQpos - object_nq) / 7;
  if (wanted > budget)
    for (int& n : sizes)
      if (n > 0) n = std::max(1, n * budget / wanted);
  return sizes;
}

}  // namespace mjcf

std::vector<efc_mj::FunctionBinding> build_bindings(const Object& obj) {
  std::vector<efc_mj::FunctionBinding> rows;
  const std::vector<int> pools = mjcf::droplet_pool_sizes(obj);
  for (int fi : evaluation_order(obj)) {
    const Function& f = obj.functions[fi];
    const Mapping& mp = f.mapping;
    const Effect& e = f.effect;
    efc_mj::FunctionBinding b{};
    copy_name(b.name, sizeof b.name, f.name);
    const int rec = part_index(obj, f.receptor_index, f.receptor);
    const int eff = part_index(obj, f.effector_index, f.effector);
    copy_name(b.receptor_joint, sizeof b.receptor_joint, obj.parts[rec].name);
    copy_name(b.effector_body, sizeof b.effector_body, obj.parts[eff].name);

    // Mapping: resolve() fills every optional; the fallbacks repeat the
    // spec's defaults so a hand-built IR still yields a sane table.
    efc_rt::MappingParams& m = b.params.mapping;
    double r_lo, r_hi;
    mjcf::receptor_range(obj, f, &r_lo, &r_hi);
    m.kind = static_cast<int>(mp.type);
    m.r_lo = r_lo;
    m.r_hi = r_hi;
    m.e_lo = e.lo;
    m.e_hi = e.hi;
    const double mid = (r_lo + r_hi) / 2;
    m.threshold = mp.threshold.value_or(mp.type == MappingType::Step ? r_lo + 0.7 * (r_hi - r_lo) : mid);
    m.hysteresis = mp.hysteresis.value_or(0.02 * (r_hi - r_lo));
    m.latching = mp.latching.value_or(false) ? 1 : 0;
    m.gain = mp.gain.value_or((e.hi - e.lo) / (r_hi - r_lo));
    m.offset = mp.offset.value_or(e.lo);
    m.delta = mp.delta.value_or(0);
    m.initial = mp.initial.value_or(e.lo);

    efc_rt::EffectParams& ep = b.params.effect;
    ep.kind = static_cast<int>(e.type);
    ep.e_lo = e.lo;
    ep.e_hi = e.hi;
    ep.time_constant = e.type == EffectType::Temperature ? e.time_constant.value_or(30.0) : 0;
    ep.droplet_volume_l =
        e.type == EffectType::Fluid ? mjcf::droplet_volume_litres(e.droplet_radius.value_or(0.004)) : 0;

    if (e.type == EffectType::Geometry)
      copy_name(b.effector_joint, sizeof b.effector_joint, obj.parts[eff].name);
    const Vec3 fallback = e.type == EffectType::Airflow ? Vec3{1, 0, 0} : Vec3{0, 0, -1};
    const Vec3 dir = unit(e.direction.value_or(fallback), fallback);
    const Vec3 color = e.color.value_or(Vec3{1, 1, 1});
    for (int k = 0; k < 3; ++k) {
      b.direction[k] = (e.type == EffectType::Fluid || e.type == EffectType::Airflow) ? dir[k] : 0;
      b.color[k] = e.type == EffectType::Illumination ? color[k] : 0;
    }
    if (e.type == EffectType::Fluid) {
      b.speed = e.speed.value_or(1.0);
      b.droplet_radius = e.droplet_radius.value_or(0.004);
      b.droplet_count = pools[fi];
    }
    if (e.type == EffectType::Airflow) {
      b.cone_angle = e.cone_angle.value_or(0.35);
      b.reach = e.reach.value_or(0.6);
    }
    // A part glows red-hot only at kGlowFullC: an oven at 250 C glows
    // partly, a kettle at 100 C barely.
    if (e.type == EffectType::Temperature) b.glow_max = std::max(e.hi, efc_mj::kGlowFullC);
    rows.push_back(b);
  }
  return rows;
}

}  // namespace efc
