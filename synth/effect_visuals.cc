#include "synth/effect_visuals.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "backends/common/naming.h"
#include "synth/image/rng.h"
#include "synth/scene.h"

namespace efc::synth {
namespace {

using Eigen::Matrix3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;

constexpr double kAirMoteSpeedScale = 0.35;  // motes drift slower than the air, like dust

const Function* function_named(const Object& obj, const char* name) {
  for (const Function& f : obj.functions)
    if (f.name == name) return &f;
  return nullptr;
}

}  // namespace

void set_mocap(const mjModel* m, mjData* d, int body, const Vector3d& p, const Quaterniond& q) {
  const int id = body >= 0 ? m->body_mocapid[body] : -1;
  if (id < 0) return;
  for (int k = 0; k < 3; ++k) d->mocap_pos[3 * id + k] = p[k];
  d->mocap_quat[4 * id] = q.w();
  d->mocap_quat[4 * id + 1] = q.x();
  d->mocap_quat[4 * id + 2] = q.y();
  d->mocap_quat[4 * id + 3] = q.z();
}

EffectVisuals::EffectVisuals(const Object& obj, const mjModel* m, const efc_mj::Controller& controller,
                             const Vector3d& parked, uint64_t seed)
    : parked_(parked) {
  for (int i = 0; i < controller.count(); ++i) {
    const efc_mj::FunctionBinding& b = controller.binding(i);
    const Function* fn = function_named(obj, b.name);
    if (!fn) continue;
    if (fn->effect.type == EffectType::Illumination) {
      const int mat = mj_name2id(m, mjOBJ_MATERIAL, (std::string(kGlowMaterialPrefix) + b.name).c_str());
      if (mat >= 0) glows_.push_back({i, mat});
    }
    if (fn->effect.type != EffectType::Airflow) continue;
    Motes mo;
    mo.function = i;
    mo.site = mj_name2id(m, mjOBJ_SITE, naming::mjcf_point(b.name).c_str());
    mo.body = mj_name2id(m, mjOBJ_BODY, b.effector_body);
    mo.direction = Vector3d(b.direction[0], b.direction[1], b.direction[2]).normalized();
    mo.cone = b.cone_angle;
    mo.reach = b.reach > 0 ? b.reach : 1.0;
    Rng rng(stream_seed(seed, 0x616972, i));  // "air"
    for (int k = 0; k < kAirMotes; ++k) {
      mo.bodies.push_back(
          mj_name2id(m, mjOBJ_BODY, (std::string(kAirPrefix) + b.name + "_" + std::to_string(k)).c_str()));
      mo.along.push_back(rng.uniform(0, mo.reach));
      const double a = rng.uniform(0, 2 * M_PI), r = std::sqrt(rng.uniform());
      mo.across.push_back(Vector3d(r * std::cos(a), r * std::sin(a), 0));
    }
    if (mo.site >= 0 && mo.body >= 0) motes_.push_back(std::move(mo));
  }
}

void EffectVisuals::update(mjModel* m, mjData* d, const efc_mj::Controller& controller, double dt) {
  for (Motes& mo : motes_) {
    const double speed = controller.readout(mo.function).measured;  // air speed at the outlet
    const Vector3d origin(d->site_xpos[3 * mo.site], d->site_xpos[3 * mo.site + 1], d->site_xpos[3 * mo.site + 2]);
    Matrix3d R;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) R(r, c) = d->xmat[9 * mo.body + 3 * r + c];
    const Vector3d axis = (R * mo.direction).normalized();
    const Quaterniond q = Quaterniond::FromTwoVectors(Vector3d::UnitZ(), axis);
    for (size_t j = 0; j < mo.bodies.size(); ++j) {
      if (speed <= 1e-3) {  // still air: nothing to see
        set_mocap(m, d, mo.bodies[j], parked_, Quaterniond::Identity());
        continue;
      }
      mo.along[j] = std::fmod(mo.along[j] + kAirMoteSpeedScale * speed * dt, mo.reach);
      const Vector3d p =
          origin + axis * mo.along[j] + q * (mo.across[j] * (mo.along[j] * std::tan(mo.cone) + 0.01));
      set_mocap(m, d, mo.bodies[j], p, q);
    }
  }
  for (const auto& [row, mat] : glows_) {
    const efc_rt::EffectParams& e = controller.binding(row).params.effect;
    // The glow follows the light's output (lumens), not the mapping's
    // progress from e_lo to e_hi: a press that dims (range [36, 0]) takes
    // a lit LED dark.
    const double brightest = std::max(e.e_lo, e.e_hi);
    const double f = brightest > 0 ? controller.readout(row).s_E / brightest : 0;
    m->mat_emission[mat] = static_cast<float>(kGlowEmission * std::clamp(f, 0.0, 1.0));
  }
}

}  // namespace efc::synth
