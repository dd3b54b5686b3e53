// The function-template stage (pipeline/templates): the mapping fitter on
// synthetic series, the whole stage on the committed synthetic suite (inputs
// from ground truth), robustness, and the vision-language adapter against a
// local fake server (tests/pipeline_templates_fake_vlm.py).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <sstream>

#include <unistd.h>

#include "pipeline/templates/effect_names.h"
#include "pipeline/templates/frame_signals.h"
#include "pipeline/templates/mapping_fit.h"
#include "pipeline/templates/mapping_names.h"
#include "pipeline/templates/template_input.h"
#include "pipeline/templates/vlm_client.h"
#include "pipeline_templates_truth.h"
#include "tests/efc_cli.h"
#include "tests/process_temp_dir.h"

namespace fs = std::filesystem;
using efc::pipeline::fit_mappings;
using efc::pipeline::MappingModel;
using efc::pipeline::MappingSeries;

namespace {

const char* const kTypes[5] = {"binary", "binary", "step", "linear", "cumulative"};

// A receptor profile like efc's: rest, press up, dwell, release, rest; n presses.
std::vector<double> presses(int n, int frames, double lo, double hi) {
  std::vector<double> s(frames);
  for (int i = 0; i < frames; ++i) {
    const double u = double(i) / frames * n, c = u - std::floor(u);
    double a = c < 0.2 ? 0 : c < 0.4 ? (c - 0.2) / 0.2 : c < 0.6 ? 1 : c < 0.8 ? 1 - (c - 0.6) / 0.2 : 0;
    s[i] = lo + (hi - lo) * a;
  }
  return s;
}

std::vector<double> sweep(int frames, double lo, double hi) {
  std::vector<double> s(frames);
  for (int i = 0; i < frames; ++i) {
    const double u = double(i) / (frames - 1);
    s[i] = u < 0.5 ? lo + (hi - lo) * 2 * u : hi - (hi - lo) * (2 * u - 1);
  }
  return s;
}

std::string fitted_type(const efc::pipeline::MappingFitResult& r) {
  if (r.best_index < 0) return "none";
  return kTypes[r.best_index];
}

MappingSeries series_for(const MappingModel& truth, const std::vector<double>& s, double noise, unsigned seed) {
  MappingSeries S;
  S.s_R = s;
  S.r_lo = 0;
  S.r_hi = 1;
  S.allow_lag = false;
  std::vector<double> u = efc::pipeline::model_profile(truth, s, 0.01);
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0, noise);
  for (double v : u) S.y.push_back(3.0 + 2.0 * v + g(rng));
  return S;
}

}  // namespace

// Each mapping, seen through a press:2 profile with noise, is the BIC's choice.
TEST(TemplatesFit, EachMappingIsRecoveredFromNoisySignals) {
  const std::vector<double> s = presses(2, 200, 0, 1);
  struct Case {
    MappingModel m;
    const char* want;
  };
  std::vector<Case> cases;
  MappingModel m;
  m.type = "binary", m.threshold = 0.4;
  cases.push_back({m, "binary"});
  m.latching = true;
  cases.push_back({m, "binary"});
  m = {};
  m.type = "step", m.threshold = 0.7, m.hysteresis = 0.25;
  cases.push_back({m, "step"});
  m = {};
  m.type = "linear", m.s0 = 0.1, m.s1 = 0.9;
  cases.push_back({m, "linear"});
  m = {};
  m.type = "cumulative", m.threshold = 0.6;
  cases.push_back({m, "cumulative"});
  for (size_t i = 0; i < cases.size(); ++i)
    for (unsigned seed = 1; seed <= 3; ++seed) {
      const auto r = fit_mappings(series_for(cases[i].m, s, 0.15, seed), efc::pipeline::mapping_prior(false));
      EXPECT_EQ(fitted_type(r), cases[i].want) << "case " << i << " seed " << seed;
      EXPECT_GT(r.delta_bic, 10) << "case " << i;
      if (cases[i].m.latching) {
        EXPECT_TRUE(r.best[r.best_index].latching);
      }
    }
}

// After the receptor's last known position nothing says where it is: a
// grip lost on the way back from a press (the hand letting go of a lever)
// left s_R held mid-travel while the light went off. Those frames are not
// scored; held, they would say it stayed on.
TEST(TemplatesFit, FramesAfterTheReceptorsLastKnownPositionAreNotScored) {
  const std::vector<double> s = presses(2, 120, 0, 1);
  MappingModel truth;
  truth.type = "binary";
  truth.threshold = 0.5;
  const MappingSeries measured = series_for(truth, s, 0.15, 7);
  constexpr int kLost = 100;  // on the way back, at two thirds of the travel
  ASSERT_GT(s[kLost], 0.6);
  MappingSeries unknown = measured, held = measured;
  for (int f = kLost + 1; f < 120; ++f) {
    unknown.s_R[f] = std::nan("");
    held.s_R[f] = s[kLost];
  }
  const auto prior = efc::pipeline::mapping_prior(false);
  const auto all = fit_mappings(measured, prior);
  const auto got = fit_mappings(unknown, prior);
  const auto was = fit_mappings(held, prior);
  ASSERT_GE(all.best_index, 0);
  ASSERT_GE(got.best_index, 0);
  ASSERT_GE(was.best_index, 0);
  EXPECT_EQ(fitted_type(all), "binary");
  EXPECT_EQ(all.n, 120);
  EXPECT_EQ(got.n, kLost + 1);
  EXPECT_EQ(was.n, 120);
  // Left out, the rest fits as well as the whole recording measured does
  // (the switch and a ramp as steep tie on so few frames of each press);
  // held, no model fits the nineteen frames where the light is off.
  const double sigma = all.best[all.best_index].sigma;
  EXPECT_LT(got.best[got.best_index].sigma, 1.1 * sigma);
  EXPECT_NE(fitted_type(got), "cumulative");
  EXPECT_GT(was.best[was.best_index].sigma, 1.4 * sigma);
}

// Pure noise keeps the null model: no mapping earns its parameters.
TEST(TemplatesFit, NoiseAloneKeepsTheNull) {
  const std::vector<double> s = sweep(150, 0, 2);
  MappingSeries S;
  S.s_R = s;
  S.r_lo = 0, S.r_hi = 2;
  std::mt19937 rng(5);
  std::normal_distribution<double> g(0, 1);
  for (size_t i = 0; i < s.size(); ++i) S.y.push_back(g(rng));
  const auto r = fit_mappings(S, efc::pipeline::mapping_prior(false));
  EXPECT_LT(r.delta_bic, 10);
}

// A signal that only rises with its effect (the hot component of a heated
// part's colour: b_sign_all_models) is not read falling with the receptor
// under any map: a lamp's colour moving away from red-hot as it lights, or
// a drift, is not a heater cooled by its knob. Read either way, the same
// fall is a linear map's.
TEST(TemplatesFit, ASignalThatOnlyRisesIsNotReadFalling) {
  const std::vector<double> s = presses(2, 150, 0, 1);
  MappingSeries S;
  S.s_R = s;
  S.allow_lag = false;
  std::mt19937 rng(6);
  std::normal_distribution<double> g(0, 0.01);
  for (double v : s) S.y.push_back(0.5 - 0.2 * v + g(rng));
  S.b_sign = 1;
  const auto either = fit_mappings(S, efc::pipeline::mapping_prior(false));
  EXPECT_EQ(fitted_type(either), "linear");
  EXPECT_GT(either.delta_bic, 100);
  S.b_sign_all_models = true;
  const auto rising = fit_mappings(S, efc::pipeline::mapping_prior(false));
  EXPECT_LT(rising.delta_bic, 10);
  for (auto& y : S.y) y = 1.0 - y;  // rising: read as before
  EXPECT_EQ(fitted_type(fit_mappings(S, efc::pipeline::mapping_prior(false))), "linear");
}

// A first-order lag (a heating element) is fitted with its time constant.
TEST(TemplatesFit, LagIsEstimated) {
  const int N = 300;
  std::vector<double> s(N, 0.0);
  for (int i = 60; i < N; ++i) s[i] = 1.0;
  MappingSeries S;
  S.s_R = s;
  S.dt = 1.0 / 30;
  double x = 0;
  for (int i = 0; i < N; ++i) {
    x += ((s[i] >= 0.5 ? 1.0 : 0.0) - x) * (1 - std::exp(-S.dt / 2.0));
    S.y.push_back(x + 0.01 * std::sin(i * 1.7));
  }
  const auto r = fit_mappings(S, efc::pipeline::mapping_prior(false));
  ASSERT_GE(r.best_index, 0);
  EXPECT_GT(r.best[r.best_index].tau, 0.9);
  EXPECT_LT(r.best[r.best_index].tau, 4.5);
}

// A switch seen through quick presses (the receptor crosses the threshold
// in a frame or two): a linear map whose ramp is narrower than that can
// set the switch between two frames to fit the noise; it is no ramp seen,
// and binary wins. Frame by frame, and binned as droplets and motes are (one
// sample per 5 frames, each its bin's mean, so a press crossing inside a
// bin leaves the fraction of the bin it was on: the models are binned
// alike).
TEST(TemplatesFit, AQuickSwitchIsASwitchFrameByFrameAndBinned) {
  constexpr int kBin = 5;
  const std::vector<double> s = presses(3, 150, 0, 1);
  MappingModel truth;
  truth.type = "binary";
  truth.threshold = 0.43;
  const std::vector<double> u = efc::pipeline::model_profile(truth, s, 0.01);
  for (int bin : {1, kBin})
    for (unsigned seed = 1; seed <= 6; ++seed) {
      MappingSeries S;
      S.s_R = s;
      S.allow_lag = false;
      S.bin_frames = bin;
      S.y.assign(s.size(), NAN);
      std::mt19937 rng(seed);
      std::normal_distribution<double> g(0, 0.02);
      for (size_t b = 0; b < s.size(); b += bin) {
        double sum = 0;
        for (size_t i = b; i < b + bin; ++i) sum += u[i];
        S.y[b + bin / 2] = 1.0 + 2.0 * sum / bin + g(rng);
      }
      const auto r = fit_mappings(S, efc::pipeline::mapping_prior(false));
      EXPECT_EQ(fitted_type(r), "binary") << "bin " << bin << ", seed " << seed;
      ASSERT_GE(r.best_index, 0);
      EXPECT_NEAR(r.best[r.best_index].threshold, 0.43, 0.07) << "bin " << bin << ", seed " << seed;
    }
}

// A step whose switch-off lags its switch-on by about what the receptor
// travels in a frame, its response counted in blocks of five frames (a
// fan's flow) with noise that hides where in a block it switched: widths
// from none to the truth's fit about as well, so the width is no parameter
// the data pin down (BIC's log(n)) and the prior (a step as likely as a
// binary switch, latching or not) decides. A binary switch seen frame by
// frame shows no lag at switch-off: most widths misfit it, and it stays
// binary.
TEST(TemplatesFit, AHysteresisTooNarrowToSeeCostsAStepNothing) {
  constexpr int kBin = 5;
  const std::vector<double> s = presses(3, 150, 0, 1);
  MappingModel step;
  step.type = "step", step.threshold = 0.6, step.hysteresis = 0.15;
  MappingModel binary;
  binary.type = "binary", binary.threshold = 0.45;
  struct Case {
    const MappingModel& truth;
    int bin;
    double noise;
    int at_least;  // of 6 seeds
  };
  for (const Case& c : {Case{step, kBin, 0.3, 5}, Case{binary, 1, 0.1, 6}}) {
    const std::vector<double> u = efc::pipeline::model_profile(c.truth, s, 0.01);
    int right = 0;
    for (unsigned seed = 1; seed <= 6; ++seed) {
      MappingSeries S;
      S.s_R = s;
      S.allow_lag = false;
      S.bin_frames = c.bin;
      S.y.assign(s.size(), NAN);
      std::mt19937 rng(seed);
      std::normal_distribution<double> g(0, c.noise);
      for (size_t b = 0; b + c.bin <= s.size(); b += c.bin) {
        double sum = 0;
        for (size_t i = b; i < b + c.bin; ++i) sum += u[i];
        S.y[b + c.bin / 2] = 1.0 + 2.0 * sum / c.bin + g(rng);
      }
      const auto r = fit_mappings(S, efc::pipeline::mapping_prior(false));
      right += fitted_type(r) == c.truth.type;
      ASSERT_TRUE(r.best[2].valid);
      EXPECT_LE(r.best[2].hysteresis_occam, 0) << "a mean over the widths is at most their best";
    }
    EXPECT_GE(right, c.at_least) << c.truth.type << ", bin " << c.bin;
  }
}

// A lid driven open by a button (binary), its drive settling within a frame
// or two: a critically damped response with a time constant of 0.4 frame,
// simulated finely, to two quick presses whose crossings fall between
// frames. Stepped once a frame, no lag follows it (a tenth of a frame after
// a switch it has barely moved, a frame after it is two-thirds there) and
// a step's second edge wins by moving the release's timing; run within
// the frames, the lags follow it and binary wins.
TEST(TemplatesFit, ADriveThatSettlesWithinAFrameIsNoStep) {
  constexpr int kFine = 64, kFrames = 150;
  const double dt = 1.0 / 30, tau = 0.4 * dt, threshold = 0.36;
  auto button = [](double f) {  // frames: two presses, 7-frame strokes, crossings between frames
    double a = 0;
    for (double start : {40.3, 95.7}) {
      const double u = f - start;
      if (u > 0 && u < 7) a = std::max(a, u / 7);
      if (u >= 7 && u < 25) a = 1;
      if (u >= 25 && u < 32) a = std::max(a, 1 - (u - 25) / 7);
    }
    return a;
  };
  MappingSeries S;
  S.dt = dt;
  S.allow_lag = true;
  S.max_lag_order = 2;
  S.noise_floor = 0.01 * 1.3;  // as infer_templates floors a driven joint's: 1 % of what it moved
  std::mt19937 rng(3);
  std::normal_distribution<double> g(0, 2e-3);
  double x = 0, y = 0;
  const double f = 1 - std::exp(-dt / kFine / tau);
  for (int i = 0; i < kFrames; ++i) {
    S.s_R.push_back(button(i));
    S.y.push_back(1.3 * y + g(rng));
    for (int k = 1; k <= kFine; ++k) {
      const double target = button(i + double(k) / kFine) >= threshold ? 1.0 : 0.0;
      x += (target - x) * f;
      y += (x - y) * f;
    }
  }
  const auto r = fit_mappings(S, efc::pipeline::mapping_prior(false));
  EXPECT_EQ(fitted_type(r), "binary");
  ASSERT_GE(r.best_index, 0);
  EXPECT_NEAR(r.best[r.best_index].threshold, threshold, 0.05);
  EXPECT_LT(r.best[r.best_index].tau, dt);
}

// A lid's brightness that follows its own pose (shading) is not light: with
// the pose's quadratic taken out, nothing is left to follow the receptor;
// a lamp switched on the moving part still shows its switch.
TEST(TemplatesFit, AMovingEffectorsShadingIsNotItsLight) {
  const std::vector<double> s = presses(2, 150, 0, 1);
  std::vector<double> q(s.size()), shaded(s.size()), lit(s.size());
  std::mt19937 rng(4);
  std::normal_distribution<double> g(0, 0.003);
  for (size_t i = 0; i < s.size(); ++i) {
    q[i] = 1.2 * s[i];                                       // the lid follows the receptor
    shaded[i] = 0.3 + 0.2 * std::cos(1.0 - q[i]) + g(rng);  // brighter as it faces the light
    lit[i] = shaded[i] + (s[i] >= 0.5 ? 0.1 : 0.0);          // and a lamp on it switched at 0.5
  }
  q[7] = NAN;  // a frame without the lid's pose keeps its sample
  auto evidence = [&](const std::vector<double>& y) {
    MappingSeries S;
    S.s_R = s;
    S.allow_lag = false;
    S.y = y;
    return fit_mappings(S, efc::pipeline::mapping_prior(false)).delta_bic;
  };
  EXPECT_GT(evidence(shaded), 100);  // as read: the lid's shading follows the receptor
  const std::vector<double> unshaded = efc::pipeline::pose_shading_removed(shaded, q);
  EXPECT_EQ(unshaded[7], shaded[7]);
  EXPECT_LT(evidence(unshaded), 10);
  EXPECT_GT(evidence(efc::pipeline::pose_shading_removed(lit, q)), 30);  // part of the switch goes with the pose
}

// Missing samples and a receptor that never moves: no crash, nothing claimed.
TEST(TemplatesFit, DegenerateInputs) {
  MappingSeries S;
  EXPECT_EQ(fit_mappings(S, {}).best_index, -1);
  S.s_R.assign(50, 0.3);
  S.y.assign(50, std::nan(""));
  EXPECT_EQ(fit_mappings(S, {}).best_index, -1);
  for (int i = 0; i < 50; ++i) S.y[i] = i % 2;
  EXPECT_EQ(fit_mappings(S, {}).best_index, -1);
}

namespace {

struct Score {
  int functions = 0, effect_ok = 0, both_ok = 0;
  int operated = 0, operated_effect_ok = 0, operated_both_ok = 0;  // receptor moved
  int geometry_operated = 0, geometry_ok = 0;  // a driven joint whose receptor moved: always decidable
  double seconds = 0;
};

// Infers every function of a sequence from its truth and compares types.
void score_sequence(const std::string& dir, Score* score, bool verbose) {
  efc::test::TruthInput t;
  std::string why;
  ASSERT_TRUE(efc::test::load_truth_input(dir, &t, &why)) << dir << ": " << why;
  efc::Diagnostics diags;
  efc::pipeline::TemplateOptions opts;
  const auto t0 = std::chrono::steady_clock::now();
  const auto got = efc::pipeline::infer_templates(t.input, opts, diags);
  score->seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(got.size(), t.input.functions.size());
  // The inferred functions in place of the true ones: the compiler accepts them.
  {
    const fs::path tmp = fs::temp_directory_path() / ("efc_tpl_" + std::to_string(::getpid()));
    fs::remove_all(tmp);
    fs::copy(fs::path(dir) / "truth", tmp, fs::copy_options::recursive);
    std::ifstream in(tmp / "spec.json");
    nlohmann::json spec = nlohmann::json::parse(in);
    for (auto& tf : spec["functions"])
      for (const auto& f : got)
        if (tf["name"] == f.name) tf["mapping"] = f.mapping, tf["effect"] = f.effect;
    std::ofstream(tmp / "spec.json") << spec.dump(2);
    efc::Diagnostics sd;
    EXPECT_TRUE(efc::load_spec((tmp / "spec.json").string(), efc::LoadOptions{}, sd).has_value())
        << dir << ":\n" << [&] { std::ostringstream os; sd.print(os, false); return os.str(); }() << spec["functions"].dump(2);
    fs::remove_all(tmp);
  }
  for (const auto& f : got) {
    for (const efc::Function& tf : t.spec->functions) {
      if (tf.name != f.name) continue;
      static const char* E[] = {"geometry", "illumination", "temperature", "fluid", "airflow"};
      static const char* Mp[] = {"binary", "step", "linear", "cumulative"};
      const std::string te = E[static_cast<int>(tf.effect.type)], tm = Mp[static_cast<int>(tf.mapping.type)];
      const bool e_ok = f.effect["type"] == te, m_ok = f.mapping["type"] == tm;
      ++score->functions;
      score->effect_ok += e_ok;
      score->both_ok += e_ok && m_ok;
      // Operated: the receptor went through a tenth of its travel.
      bool operated = false;
      for (const auto& p : t.input.parts)
        if (p.name == f.receptor && !p.q.empty()) {
          const auto [lo, hi] = std::minmax_element(p.q.begin(), p.q.end());
          const double travel = p.range_hi > p.range_lo ? p.range_hi - p.range_lo : 6.283;
          operated = *hi - *lo > 0.1 * travel;
        }
      score->operated += operated;
      score->operated_effect_ok += operated && e_ok;
      score->operated_both_ok += operated && e_ok && m_ok;
      score->geometry_operated += operated && te == "geometry";
      score->geometry_ok += operated && te == "geometry" && e_ok;
      if (verbose || !(e_ok && m_ok)) {
        std::printf("%s%s %-40s %s/%s -> %s/%s conf %.2f %s\n", e_ok && m_ok ? "ok  " : "MISS", operated ? "" : " (idle)",
                    (fs::path(dir).parent_path().filename().string() + ":" + f.name).c_str(), tm.c_str(), te.c_str(),
                    f.mapping["type"].get<std::string>().c_str(), f.effect["type"].get<std::string>().c_str(),
                    f.confidence, "");
        if (std::getenv("EFC_TPL_REPORT")) std::printf("%s\n", f.report.dump().c_str());
      }
    }
  }
}

std::vector<std::string> suite_sequences(const std::string& root) {
  std::vector<std::string> out;
  if (!fs::is_directory(root)) return out;
  for (const auto& e : fs::directory_iterator(root))
    if (fs::is_regular_file(e.path() / "seq" / "meta.json")) out.push_back((e.path() / "seq").string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST(TemplatesSuite, CommittedSuite) {
  Score s;
  for (const std::string& d : suite_sequences(std::string(EFC_SOURCE_DIR) + "/tests/data/synth-suite"))
    score_sequence(d, &s, true);
  ASSERT_GT(s.functions, 0);
  std::printf("committed suite: effect %d/%d, effect+mapping %d/%d, %.3f s\n", s.effect_ok, s.functions, s.both_ok,
              s.functions, s.seconds);
  // The committed suite is 30 frames of one ramp, hold or press per
  // receptor (made before the suite demonstrated its functions): most
  // mappings, and effects that lag (a heater) or barely show (a 2 px LED),
  // cannot be decided there. A driven joint moving with its receptor can.
  EXPECT_GT(s.geometry_operated, 0);
  EXPECT_EQ(s.geometry_ok, s.geometry_operated);
}

// The development figure: EFC_TPL_SUITE=/tmp/tpl-suite (made by efc synth-suite)
// prints the accuracy; skipped otherwise.
TEST(TemplatesSuite, DevSuiteAccuracy) {
  const char* root = std::getenv("EFC_TPL_SUITE");
  if (!root) GTEST_SKIP() << "set EFC_TPL_SUITE to a synth-suite folder";
  Score s;
  for (const std::string& d : suite_sequences(root)) score_sequence(d, &s, std::getenv("EFC_TPL_VERBOSE"));
  std::printf("dev suite %s: effect %d/%d (%.1f %%), effect+mapping %d/%d (%.1f %%), %.2f s per function\n", root,
              s.effect_ok, s.functions, 100.0 * s.effect_ok / std::max(1, s.functions), s.both_ok, s.functions,
              100.0 * s.both_ok / std::max(1, s.functions), s.seconds / std::max(1, s.functions));
  std::printf("  operated receptors only: effect %d/%d (%.1f %%), effect+mapping %d/%d (%.1f %%)\n", s.operated_effect_ok,
              s.operated, 100.0 * s.operated_effect_ok / std::max(1, s.operated), s.operated_both_ok, s.operated,
              100.0 * s.operated_both_ok / std::max(1, s.operated));
}

#include "pipeline/templates/frame_signals.h"

// Development aid: EFC_TPL_DUMP=SEQ prints s_R and every signal per frame.
TEST(TemplatesSuite, DumpSignals) {
  const char* dir = std::getenv("EFC_TPL_DUMP");
  if (!dir) GTEST_SKIP() << "set EFC_TPL_DUMP to a sequence folder";
  efc::test::TruthInput t;
  std::string why;
  ASSERT_TRUE(efc::test::load_truth_input(dir, &t, &why)) << why;
  for (const auto& f : t.input.functions) {
    int r = -1, e = -1;
    for (size_t i = 0; i < t.input.parts.size(); ++i) {
      if (t.input.parts[i].name == f.receptor) r = static_cast<int>(i);
      if (t.input.parts[i].name == f.effector) e = static_cast<int>(i);
    }
    ASSERT_GE(r, 0);
    ASSERT_GE(e, 0);
    int failed = 0;
    const auto sig = efc::pipeline::measure_effectors(t.input, {e}, 2, &failed);
    std::printf("# %s: %s -> %s (seen %d, drops %ld, motes %ld)\n", f.name.c_str(), f.receptor.c_str(),
                f.effector.c_str(), sig[0].frames_seen, sig[0].droplet_points, sig[0].mote_points);
    const auto& q = t.input.parts[r].q;
    const auto& qe = t.input.parts[e].q;
    for (size_t i = 0; i < sig[0].glow.size(); ++i)
      std::printf("%3zu sR %8.4f qE %8.4f glow %7.4f heat %7.4f drop %10.3g mote %10.3g around %7.4f\n", i,
                  i < q.size() ? q[i] : NAN, i < qe.size() ? qe[i] : NAN, sig[0].glow[i], sig[0].heat[i],
                  sig[0].droplets[i] * 1e6, sig[0].motes[i] * 1e6, sig[0].surround[i]);
  }
}

// Development aid: EFC_TPL_PIX=SEQ:FRAME prints bluish pixels with their depth
// and their neighbours' (to see what a droplet looks like to the sensor).
TEST(TemplatesSuite, DumpPixels) {
  const char* arg = std::getenv("EFC_TPL_PIX");
  if (!arg) GTEST_SKIP();
  const std::string a = arg;
  const std::string dir = a.substr(0, a.rfind(':'));
  const int frame = std::stoi(a.substr(a.rfind(':') + 1));
  efc::seq::Sequence S;
  efc::Diagnostics d;
  ASSERT_TRUE(S.open(dir, d));
  efc::seq::Image8 rgb;
  efc::seq::Image16 depth;
  ASSERT_TRUE(S.read_rgb(frame, d, &rgb));
  ASSERT_TRUE(S.read_depth(frame, d, &depth));
  const int W = rgb.width;
  for (int y = 2; y < rgb.height - 2; ++y)
    for (int x = 2; x < W - 2; ++x) {
      const uint8_t* p = &rgb.pixels[3 * (y * W + x)];
      if (!(p[2] > p[0] + 60 && p[2] > 150)) continue;
      std::printf("%3d %3d rgb %3d %3d %3d  d %5d | L %5d R %5d U %5d D %5d\n", x, y, p[0], p[1], p[2],
                  depth.pixels[y * W + x], depth.pixels[y * W + x - 2], depth.pixels[y * W + x + 2],
                  depth.pixels[(y - 2) * W + x], depth.pixels[(y + 2) * W + x]);
    }
}

// ---------------------------------------------------------------- the VLM adapter
#include <csignal>
#include <sys/socket.h>
#include <sys/wait.h>
#include <netinet/in.h>
#include <unistd.h>

namespace {

// The fake server (tests/pipeline_templates_fake_vlm.py) in a child process.
struct FakeVlm {
  pid_t pid = -1;
  int port = 0;
  explicit FakeVlm(const std::string& mode) {
    int fds[2];
    if (pipe(fds) != 0) return;
    pid = fork();
    if (pid == 0) {
      dup2(fds[1], 1);
      close(fds[0]);
      const std::string script = std::string(EFC_SOURCE_DIR) + "/tests/pipeline_templates_fake_vlm.py";
      execlp("python3", "python3", script.c_str(), mode.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    close(fds[1]);
    char buf[32] = {0};
    size_t n = 0;
    while (n < sizeof buf - 1) {
      const ssize_t r = read(fds[0], buf + n, 1);
      if (r <= 0 || buf[n] == '\n') break;
      ++n;
    }
    close(fds[0]);
    port = std::atoi(buf);
  }
  ~FakeVlm() {
    if (pid > 0) {
      kill(pid, SIGTERM);
      waitpid(pid, nullptr, 0);
    }
  }
  std::string endpoint() const { return "http://127.0.0.1:" + std::to_string(port) + "/v1"; }
};

// A loopback port nobody listens on.
int closed_port() {
  const int s = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;
  socklen_t len = sizeof a;
  bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a);
  getsockname(s, reinterpret_cast<sockaddr*>(&a), &len);
  close(s);
  return ntohs(a.sin_port);
}

const std::string kCumulativeGeometry = std::string(EFC_SOURCE_DIR) + "/tests/data/synth-suite/s0001_cumulative-geometry_prismatic/seq";

bool have_vlm() {
  std::string why;
  return efc::pipeline::vlm_available(&why);
}

// The templates of `input` with a twin of its first function, named `name`,
// on the same receptor and effector.
std::vector<efc::pipeline::InferredFunction> with_twin(efc::pipeline::TemplateInput input, const std::string& name) {
  efc::seq::FunctionRef twin = input.functions[0];
  twin.name = name;
  input.functions.push_back(twin);
  efc::Diagnostics diags;
  return efc::pipeline::infer_templates(input, efc::pipeline::TemplateOptions{}, diags);
}

}  // namespace

TEST(TemplatesFit, TwoFunctionsOnOnePartSetDifferentEffects) {
  // Two functions acting on the same effector may not both set one of its
  // effects (efc check, E0307): the second takes its best other effect.
  efc::test::TruthInput t;
  std::string why;
  ASSERT_TRUE(efc::test::load_truth_input(kCumulativeGeometry, &t, &why)) << why;
  ASSERT_EQ(t.input.functions.size(), 1u);
  const auto got = with_twin(t.input, "twin");
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0].effect["type"], "geometry");  // the ram's joint answers for the first
  EXPECT_NE(got[1].effect["type"], got[0].effect["type"]);
}

TEST(TemplatesFit, TheReceptorStateTheEffectorFollowsIsKept) {
  // A receptor's state may come from its own track or from the hand's grip
  // (a round knob's track can be its tracker's drift): the templates keep
  // the one an effect follows. The truth in one place and an unrelated
  // wobble in the other, both ways round.
  efc::test::TruthInput t;
  std::string why;
  ASSERT_TRUE(efc::test::load_truth_input(kCumulativeGeometry, &t, &why)) << why;
  ASSERT_EQ(t.input.functions.size(), 1u);
  int r = -1;
  for (size_t i = 0; i < t.input.parts.size(); ++i)
    if (t.input.parts[i].name == t.input.functions[0].receptor) r = static_cast<int>(i);
  ASSERT_GE(r, 0);
  efc::pipeline::PartObservation& rec = t.input.parts[r];
  const std::vector<double> truth = rec.q;
  ASSERT_FALSE(truth.empty());
  const auto [lo, hi] = std::minmax_element(truth.begin(), truth.end());
  ASSERT_GT(*hi - *lo, 0);
  std::vector<double> wobble(truth.size());
  for (size_t i = 0; i < wobble.size(); ++i) wobble[i] = *lo + 0.5 * (*hi - *lo) * (1 + std::sin(0.7 * i + 1.0));

  efc::Diagnostics diags;
  const auto reference = efc::pipeline::infer_templates(t.input, efc::pipeline::TemplateOptions{}, diags);
  ASSERT_EQ(reference.size(), 1u);
  EXPECT_EQ(reference[0].report["s_R"]["source"], "part");
  EXPECT_TRUE(reference[0].report["s_R"]["evidence_hand"].is_null());  // no hand's state given

  rec.q = wobble;
  rec.q_hand = truth;
  const auto from_hand = efc::pipeline::infer_templates(t.input, efc::pipeline::TemplateOptions{}, diags);
  ASSERT_EQ(from_hand.size(), 1u);
  EXPECT_EQ(from_hand[0].report["s_R"]["source"], "hand");
  EXPECT_EQ(from_hand[0].effect["type"], reference[0].effect["type"]);
  EXPECT_EQ(from_hand[0].mapping["type"], reference[0].mapping["type"]);

  rec.q = truth;
  rec.q_hand = wobble;
  const auto from_part = efc::pipeline::infer_templates(t.input, efc::pipeline::TemplateOptions{}, diags);
  ASSERT_EQ(from_part.size(), 1u);
  EXPECT_EQ(from_part[0].report["s_R"]["source"], "part");
  EXPECT_GT(from_part[0].report["s_R"]["evidence_part"].get<double>(),
            from_part[0].report["s_R"]["evidence_hand"].get<double>());
  EXPECT_EQ(from_part[0].effect["type"], reference[0].effect["type"]);
  EXPECT_EQ(from_part[0].mapping["type"], reference[0].mapping["type"]);
}

TEST(TemplatesFit, AnEffectorsJointIsReadOnlyWhereItWasSeen) {
  // s0021's lid opened a second time out of view; its q, bridged between
  // the shut lid's last frame before and first after (fill_gaps), said it
  // stayed shut while the pedal went down, and a counter fitted better
  // than the switch. The geometry signal reads the frames its track
  // measured (q_seen). The committed ram made a switch: on while the
  // button is past half its travel, pressed twice, hidden the second time
  // (its recording's pixels stay where they were).
  efc::test::TruthInput t;
  std::string why;
  ASSERT_TRUE(efc::test::load_truth_input(kCumulativeGeometry, &t, &why)) << why;
  ASSERT_EQ(t.input.functions.size(), 1u);
  efc::pipeline::PartObservation *rec = nullptr, *eff = nullptr;
  for (efc::pipeline::PartObservation& p : t.input.parts) {
    if (p.name == t.input.functions[0].receptor) rec = &p;
    if (p.name == t.input.functions[0].effector) eff = &p;
  }
  ASSERT_TRUE(rec && eff);
  const size_t n = rec->q.size();
  ASSERT_EQ(n, 30u);
  ASSERT_EQ(eff->q.size(), n);
  const double travel = rec->range_hi - rec->range_lo, lift = eff->range_hi - eff->range_lo;
  ASSERT_GT(travel, 0);
  ASSERT_GT(lift, 0);
  // Pressed over frames 3 to 10 and 17 to 24, held down for two frames.
  const auto pressed = [](int f, int from) {
    const double x = f - from;
    return x < 0 || x > 8 ? 0.0 : x < 3 ? x / 3 : x <= 5 ? 1.0 : (8 - x) / 3;
  };
  std::vector<double> shut_through_the_gap(n), seen(n);
  for (size_t f = 0; f < n; ++f) {
    const double press = std::max(pressed(static_cast<int>(f), 3), pressed(static_cast<int>(f), 17));
    rec->q[f] = rec->range_lo + travel * press;
    const double lid = press >= 0.5 ? eff->range_lo + lift : eff->range_lo;
    const bool hidden = f >= 15 && f <= 27;
    seen[f] = hidden ? std::nan("") : lid;
    shut_through_the_gap[f] = hidden ? eff->range_lo : lid;
  }
  rec->q_hand.clear();
  eff->q = shut_through_the_gap;  // (the parts' poses stay the recording's: its pixels are where they were)

  efc::Diagnostics diags;
  const auto bridged = efc::pipeline::infer_templates(t.input, efc::pipeline::TemplateOptions{}, diags);

  eff->q_seen = seen;
  const auto got = efc::pipeline::infer_templates(t.input, efc::pipeline::TemplateOptions{}, diags);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].effect["type"], "geometry");
  EXPECT_EQ(got[0].mapping["type"], "binary");
  EXPECT_FALSE(got[0].mapping.value("latching", false));
  // Bridged, the second press's frames said shut: a switch that opened the
  // ram half as far explained them best.
  ASSERT_EQ(bridged.size(), 1u);
  EXPECT_LT(bridged[0].effect["range"][1].get<double>(), 0.6 * lift);
  EXPECT_EQ(got[0].report["hypotheses"]["geometry"]["signal"]["observed"], 17);
  EXPECT_NEAR(got[0].effect["range"][1].get<double>(), eff->range_lo + lift, 0.02 * lift);
}

TEST(TemplatesVlm, ParsesRepliesAndRejectsGarbage) {
  using efc::pipeline::parse_vlm_reply;
  auto wrap = [](const std::string& content) {
    return nlohmann::json({{"choices", {{{"message", {{"role", "assistant"}, {"content", content}}}}}}}).dump();
  };
  auto a = parse_vlm_reply(wrap("```json\n{\"effect\": \"Fluid\", \"mapping\": \"linear\", \"reasons\": \"water\"}\n```"));
  EXPECT_TRUE(a.ok) << a.error;
  EXPECT_EQ(a.effect, "fluid");
  EXPECT_EQ(a.mapping, "linear");
  EXPECT_EQ(a.reasons, "water");
  EXPECT_FALSE(parse_vlm_reply(wrap("{\"effect\": \"smell\", \"mapping\": \"linear\"}")).ok);
  EXPECT_FALSE(parse_vlm_reply(wrap("no json here")).ok);
  EXPECT_FALSE(parse_vlm_reply("<html>").ok);
  EXPECT_FALSE(parse_vlm_reply("{\"choices\": []}").ok);
  EXPECT_EQ(efc::pipeline::base64_encode("Man"), "TWFu");
  EXPECT_EQ(efc::pipeline::base64_encode("Ma"), "TWE=");
  EXPECT_EQ(efc::pipeline::base64_encode("M"), "TQ==");
}

TEST(TemplatesVlm, CombinesAsAPrior) {
  efc::pipeline::VlmAnswer a;
  a.ok = true, a.effect = "fluid", a.mapping = "step";
  std::vector<double> e(5, 0.2), m{0.7, 0.1, 0.1, 0.1};
  efc::pipeline::combine_with_vlm(a, &e, &m);
  EXPECT_EQ(std::max_element(e.begin(), e.end()) - e.begin(), 3);  // a tie broken by the VLM
  EXPECT_NEAR(e[3], 0.7, 1e-9);
  EXPECT_EQ(std::max_element(m.begin(), m.end()) - m.begin(), 0);  // decisive data stands
}

TEST(TemplatesVlm, AsksTheServerAndCombines) {
  if (!have_vlm()) GTEST_SKIP() << "libcurl not available";
  FakeVlm server("ok");
  ASSERT_GT(server.port, 0);
  efc::test::TruthInput t;
  std::string why;
  ASSERT_TRUE(efc::test::load_truth_input(kCumulativeGeometry, &t, &why)) << why;
  efc::pipeline::TemplateOptions opts;
  opts.vlm_endpoint = server.endpoint();
  opts.vlm_model = "test-model";
  opts.vlm_timeout_s = 10;
  efc::Diagnostics diags;
  const auto got = efc::pipeline::infer_templates(t.input, opts, diags);
  ASSERT_EQ(got.size(), 1u);
  const auto& r = got[0].report;
  ASSERT_TRUE(r.contains("vlm"));
  EXPECT_TRUE(r["vlm"]["ok"].get<bool>()) << r["vlm"].dump();
  EXPECT_EQ(r["vlm"]["effect"], "illumination");
  EXPECT_EQ(r["vlm"]["mapping"], "cumulative");
  EXPECT_GE(r["vlm"]["images"].get<int>(), 2);
  // The ram's own joint answers decisively: the VLM's 'illumination' does not
  // outvote it.
  EXPECT_EQ(got[0].effect["type"], "geometry");
  for (const auto& d : diags.items()) EXPECT_NE(d.code, "E1063") << d.message;
}

TEST(TemplatesVlm, GarbageErrorsAndClosedPortsAreWarnings) {
  if (!have_vlm()) GTEST_SKIP() << "libcurl not available";
  efc::test::TruthInput t;
  std::string why;
  ASSERT_TRUE(efc::test::load_truth_input(kCumulativeGeometry, &t, &why)) << why;
  efc::pipeline::TemplateOptions plain;
  efc::Diagnostics d0;
  const auto base = efc::pipeline::infer_templates(t.input, plain, d0);
  ASSERT_EQ(base.size(), 1u);
  for (const std::string mode : {"garbage", "error", "closed"}) {
    std::unique_ptr<FakeVlm> server;
    efc::pipeline::TemplateOptions opts;
    if (mode == "closed") {
      opts.vlm_endpoint = "http://127.0.0.1:" + std::to_string(closed_port()) + "/v1";
    } else {
      server = std::make_unique<FakeVlm>(mode);
      ASSERT_GT(server->port, 0);
      opts.vlm_endpoint = server->endpoint();
    }
    opts.vlm_model = "test-model";
    opts.vlm_timeout_s = 2;
    efc::Diagnostics diags;
    const auto got = efc::pipeline::infer_templates(t.input, opts, diags);
    ASSERT_EQ(got.size(), 1u) << mode;
    bool warned = false;
    for (const auto& d : diags.items()) warned = warned || (d.code == "E1063" && d.severity == efc::Severity::Warning);
    EXPECT_TRUE(warned) << mode;
    EXPECT_EQ(got[0].effect, base[0].effect) << mode;
    EXPECT_EQ(got[0].mapping, base[0].mapping) << mode;
  }
}

TEST(TemplatesNames, EachWordNamesOneEffect) {
  using efc::pipeline::effect_named;
  // The effector's head noun first, then the function's.
  EXPECT_EQ(effect_named("hob_lamp", "hob_on"), 1);       // a lamp on a hob lights
  EXPECT_EQ(effect_named("burner_left", "heat_left"), 2);
  EXPECT_EQ(effect_named("spout", "water"), 3);
  EXPECT_EQ(effect_named("blower", "extract"), 4);
  EXPECT_EQ(effect_named("lid", "open_lid"), 0);
  EXPECT_EQ(effect_named("head", "brew"), 3);             // "head" names nothing
  EXPECT_EQ(effect_named("lamps", "lights"), 1);          // plurals
  EXPECT_EQ(effect_named("FanBlade", "stop"), 4);         // camel case
  EXPECT_EQ(effect_named("indicator_led", "fan_stop"), 1);  // the effector's word wins
  EXPECT_EQ(effect_named("head", "speed"), -1);
  EXPECT_EQ(effect_named("", ""), -1);
  EXPECT_EQ(effect_named("grill", "press"), -1);          // a heater or a vent: neither
  EXPECT_EQ(effect_named("gas", "s"), -1);                // no "s" stripped from short words
}

TEST(TemplatesNames, WhereNothingRespondsTheNamesGuessTheEffect) {
  // A receptor that never moves explains no signal at the effector: the
  // effect is a guess (E1062), the names' where they name one.
  efc::test::TruthInput t;
  std::string why;
  ASSERT_TRUE(efc::test::load_truth_input(kCumulativeGeometry, &t, &why)) << why;
  ASSERT_EQ(t.input.functions.size(), 1u);
  for (efc::pipeline::PartObservation& p : t.input.parts)
    if (p.name == t.input.functions[0].receptor) {
      std::fill(p.q.begin(), p.q.end(), 0.0);
      p.q_hand.clear();
    }
  auto guess = [&](const std::string& function_name, std::string* from, std::string* warning) {
    t.input.functions[0].name = function_name;
    efc::Diagnostics diags;
    const auto got = efc::pipeline::infer_templates(t.input, efc::pipeline::TemplateOptions{}, diags);
    EXPECT_EQ(got.size(), 1u);
    if (got.empty()) return std::string();
    EXPECT_FALSE(got[0].report["evident"].get<bool>());
    EXPECT_LE(got[0].confidence, 0.2);
    *from = got[0].report["guess_from"].get<std::string>();
    std::ostringstream os;
    diags.print(os, false);
    *warning = os.str();
    return got[0].effect["type"].get<std::string>();
  };
  std::string from, warning;
  EXPECT_EQ(guess("water", &from, &warning), "fluid");  // the effector, "ram", names nothing
  EXPECT_EQ(from, "names");
  EXPECT_NE(warning.find("E1062"), std::string::npos) << warning;
  EXPECT_NE(warning.find("(fluid, from the names)"), std::string::npos) << warning;
  EXPECT_EQ(guess("blow", &from, &warning), "airflow");
  EXPECT_EQ(guess("lift", &from, &warning), "geometry");  // the ram is movable
  EXPECT_EQ(guess("twist", &from, &warning), "temperature");
  EXPECT_EQ(from, "default");
  EXPECT_NE(warning.find("(temperature)"), std::string::npos) << warning;
  // A second function on the same effector whose names speak of the same
  // effect cannot set it too (E0307): its guess is another, and not the
  // names'.
  t.input.functions[0].name = "water";
  const auto both = with_twin(t.input, "spray");
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both[0].effect["type"], "fluid");
  EXPECT_EQ(both[0].report["guess_from"], "names");
  EXPECT_NE(both[1].effect["type"], "fluid");
  EXPECT_EQ(both[1].report["guess_from"], "other");
}

TEST(TemplatesNames, EachReceptorWordNamesOneMapping) {
  using efc::pipeline::mapping_named;  // 0 binary, 1 step, 2 linear, 3 cumulative
  EXPECT_EQ(mapping_named("door"), 0);          // a door's switch trips at a point of its travel
  EXPECT_EQ(mapping_named("drawer"), 0);
  EXPECT_EQ(mapping_named("power_switch"), 0);
  EXPECT_EQ(mapping_named("fan_slider"), 2);    // a slider sets a level
  EXPECT_EQ(mapping_named("HandWheel"), 2);     // camel case
  EXPECT_EQ(mapping_named("flow_up"), 3);       // an up button adds a step
  EXPECT_EQ(mapping_named("plus_button"), 3);
  EXPECT_EQ(mapping_named("door_plus"), 3);     // the last word that names one
  EXPECT_EQ(mapping_named("doors"), 0);         // plurals
  for (const char* none : {"knob", "dial", "lever", "button", "light_button", "crank", "paddle", ""})
    EXPECT_EQ(mapping_named(none), -1) << none;
}

TEST(TemplatesNames, WhereNothingRespondsTheReceptorsNameGuessesTheMapping) {
  // A receptor that never moves explains nothing: the mapping fitted to the
  // noise says nothing either, and the receptor's name decides where it
  // names a mapping, with the spec's default parameters. Where the effector
  // responds, the name changes nothing.
  efc::test::TruthInput t;
  std::string why;
  ASSERT_TRUE(efc::test::load_truth_input(kCumulativeGeometry, &t, &why)) << why;
  ASSERT_EQ(t.input.functions.size(), 1u);
  efc::Diagnostics diags;
  const auto responding = efc::pipeline::infer_templates(t.input, efc::pipeline::TemplateOptions{}, diags);
  ASSERT_EQ(responding.size(), 1u);
  ASSERT_TRUE(responding[0].report["evident"].get<bool>());
  const std::string receptor = t.input.functions[0].receptor;
  auto with_receptor_named = [&](const std::string& name, bool still) {
    efc::pipeline::TemplateInput in = t.input;
    in.functions[0].receptor = name;
    for (efc::pipeline::PartObservation& p : in.parts)
      if (p.name == receptor) {
        p.name = name;
        if (still) std::fill(p.q.begin(), p.q.end(), 0.0), p.q_hand.clear();
      }
    efc::Diagnostics d;
    auto got = efc::pipeline::infer_templates(in, efc::pipeline::TemplateOptions{}, d);
    std::ostringstream os;
    d.print(os, false);
    if (!got.empty()) got[0].report["warnings"] = os.str();
    return got;
  };
  const auto door = with_receptor_named("door", true);
  ASSERT_EQ(door.size(), 1u);
  EXPECT_FALSE(door[0].report["evident"].get<bool>());
  EXPECT_EQ(door[0].mapping["type"], "binary");
  EXPECT_EQ(door[0].report["mapping_from"], "names");
  EXPECT_NE(door[0].report["warnings"].get<std::string>().find("binary, from the receptor's name"), std::string::npos)
      << door[0].report["warnings"];
  const auto slider = with_receptor_named("fan_slider", true);
  ASSERT_EQ(slider.size(), 1u);
  EXPECT_EQ(slider[0].mapping["type"], "linear");
  const auto up = with_receptor_named("flow_up", true);
  ASSERT_EQ(up.size(), 1u);
  EXPECT_EQ(up[0].mapping["type"], "cumulative");
  const auto knob = with_receptor_named("knob", true);
  ASSERT_EQ(knob.size(), 1u);
  EXPECT_EQ(knob[0].report["mapping_from"], "noise");  // "knob" names none
  // The ram follows the button press by press: the data's cumulative map,
  // whatever the button is called.
  const auto pressed = with_receptor_named("door", false);
  ASSERT_EQ(pressed.size(), 1u);
  EXPECT_TRUE(pressed[0].report["evident"].get<bool>());
  EXPECT_EQ(pressed[0].report["mapping_from"], "data");
  EXPECT_EQ(pressed[0].mapping, responding[0].mapping);
}

TEST(TemplatesSignals, TheSurroundComparesEachSurfacePointWithItself) {
  // A door opening hides a lit front (cell 1, 0.8) and reveals a dark inside
  // (cell 2, 0.2); a wall (cell 3, 0.5) is seen throughout. The lighting is
  // the same all along: the plain mean would fall from 0.65 to 0.35 with the
  // door; the surround stays flat. Then a lamp lights every cell by 0.1 in
  // the last three frames: the surround rises by that.
  using efc::pipeline::CellLum;
  auto frames_for = [](double lamp_rise) {
    std::vector<std::vector<CellLum>> f(10);
    for (int i = 0; i < 10; ++i) {
      const double lit = i >= 7 ? lamp_rise : 0.0;
      if (i < 5) f[i].push_back({1, 4 * (0.8 + lit), 4});
      if (i >= 5) f[i].push_back({2, 2 * (0.2 + lit), 2});
      f[i].push_back({3, 0.5 + lit, 1});
    }
    f[9].push_back({4, 0.99, 1});  // seen once: no reference, left out
    return f;
  };
  const std::vector<double> door = efc::pipeline::surround_from_cells(frames_for(0.0));
  ASSERT_EQ(door.size(), 10u);
  for (double v : door) EXPECT_NEAR(v, door[0], 1e-12);
  const std::vector<double> lamp = efc::pipeline::surround_from_cells(frames_for(0.1));
  // Frame 2: the front at its mean, the wall 0.03 below its (0.53); frame
  // 8: the inside 0.04 above its (0.26), the wall 0.07 above.
  EXPECT_NEAR(lamp[8] - lamp[2], 0.055 + 0.015, 1e-9);
  std::vector<std::vector<CellLum>> gap = frames_for(0.0);
  gap[4].clear();
  EXPECT_TRUE(std::isnan(efc::pipeline::surround_from_cells(gap)[4]));  // a frame that sees no cell
  EXPECT_TRUE(efc::pipeline::surround_from_cells({}).empty());
}

// A heated part's colour blends from its own towards red-hot (1, 0.22,
// 0.04) by f, times the shading. A near-black red burner (the stove's,
// varied): its red chromaticity is already 0.95 cool and falls towards
// red-hot's 0.79 as it heats, most of the way by f = 0.1. How much red-hot
// the colour holds rises in proportion to f, and stays 0 while the burner
// is cool however the light on it changes.
TEST(TemplatesSignals, ADarkBurnersHeatRisesInProportionToItsGlow) {
  const Eigen::Vector3d base(0.041, 0.0, 0.002), hot(1.0, 0.22, 0.04);
  std::vector<Eigen::Vector3d> colour;
  std::vector<double> f_of;
  for (int i = 0; i < 40; ++i) {
    const double f = i < 20 ? 0.0 : 0.025 * (i - 20);  // cool, then heating to 0.475
    const double shade = 0.6 + 0.1 * std::sin(0.7 * i);  // the camera moving about it
    colour.push_back(shade * ((1 - f) * base + f * hot));
    f_of.push_back(f);
  }
  colour[5] = Eigen::Vector3d::Constant(NAN);  // a frame without its pixels
  const std::vector<double> heat = efc::pipeline::hot_component(colour);
  ASSERT_EQ(heat.size(), colour.size());
  EXPECT_TRUE(std::isnan(heat[5]));
  const double hot_sum = hot.sum();
  for (int i = 0; i < 40; ++i) {
    if (i == 5) continue;
    const double shade = 0.6 + 0.1 * std::sin(0.7 * i);
    EXPECT_NEAR(heat[i], shade * f_of[i] * hot_sum, 1e-9) << i;  // 0 while cool, whatever the shading
  }
  // The chromaticity alone fell as the burner heated.
  EXPECT_LT(colour[39].x() / colour[39].sum(), colour[0].x() / colour[0].sum());
  // A part coloured like red-hot itself: its red chromaticity.
  const std::vector<double> ember = efc::pipeline::hot_component({0.5 * hot, 0.4 * hot});
  EXPECT_NEAR(ember[0], 1.0 / hot_sum, 1e-12);
  EXPECT_TRUE(efc::pipeline::hot_component({}).empty());
}

// The same, recorded (`efc synth`, press:2): a knob turns a near-black red
// burner up and back twice, its heat linear in the knob with a half-second
// lag. Read as its red chromaticity, the burner's colour reached most of
// red-hot's at the first touch and stayed there while it cooled: a
// counter. Its hot component rises and falls with the knob. An amber lamp
// on the same box, switched by the knob, stays a light: coloured within
// 0.15 of red-hot, it is read by its red chromaticity, which its emission
// (scaling its colour) leaves alone.
TEST(TemplatesSignals, ADarkBurnerTurnedUpIsHeatedLinearlyAndALampIsLit) {
  efc_test::ProcessTempDir dir("efc-tpl-heat-");
  fs::create_directories(dir.path());
  const std::string box = R"({"efc": 1, "name": "hob", "parts": [
    {"name": "body", "geometry": {"box": {"size": [0.4, 0.4, 0.3], "center": [0, 0, 0.15]}}, "rgba": [0.9, 0.9, 0.92, 1]},
    {"name": "disc", "geometry": {"cylinder": {"radius": 0.09, "length": 0.01, "center": [0, 0, 0.305]}},
     "rgba": RGBA, "joint": {"type": "fixed", "parent": "body"}},
    {"name": "knob", "geometry": {"cylinder": {"radius": 0.025, "length": 0.025, "center": [0.1, -0.2125, 0.2], "axis": [0, -1, 0]}},
     "rgba": [0.6, 0.6, 0.62, 1], "joint": {"type": "revolute", "parent": "body", "axis": [0, -1, 0], "origin": [0.1, -0.2, 0.2], "range": [0, 3.8]}}],
    "functions": [{"name": "f", "receptor": "knob", "effector": "disc", FUNCTION}]})";
  auto infer = [&](const std::string& name, const std::string& rgba, const std::string& function) {
    std::string spec = box;
    spec.replace(spec.find("RGBA"), 4, rgba);
    spec.replace(spec.find("FUNCTION"), 8, function);
    const fs::path spec_path = dir.path() / (name + ".json"), seq = dir.path() / name;
    std::ofstream(spec_path) << spec;
    const auto r = efc_test::run_efc("synth " + spec_path.string() + " -o " + seq.string() +
                                     " --frames 120 --width 200 --height 150 --profile press:2 --noise none --seed 1");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    efc::test::TruthInput t;
    std::string why;
    EXPECT_TRUE(efc::test::load_truth_input(seq.string(), &t, &why)) << why;
    efc::Diagnostics diags;
    return efc::pipeline::infer_templates(t.input, efc::pipeline::TemplateOptions{}, diags);
  };
  const auto burner = infer("burner", "[0.041, 0.0, 0.002, 1]",
                            R"("mapping": {"type": "linear"}, "effect": {"type": "temperature", "range": [20, 300],
                               "time_constant": 0.5, "position": [0, 0, 0.31]})");
  ASSERT_EQ(burner.size(), 1u);
  EXPECT_EQ(burner[0].effect["type"], "temperature");
  EXPECT_EQ(burner[0].mapping["type"], "linear") << burner[0].report["hypotheses"]["temperature"].dump();
  EXPECT_EQ(burner[0].report["mapping_from"], "data");
  const auto lamp = infer("lamp", "[1, 0.3, 0.1, 1]",
                          R"("mapping": {"type": "binary"}, "effect": {"type": "illumination", "range": [0, 5],
                             "color": [1.0, 0.4, 0.1]})");
  ASSERT_EQ(lamp.size(), 1u);
  EXPECT_EQ(lamp[0].effect["type"], "illumination");
  EXPECT_EQ(lamp[0].mapping["type"], "binary");
}
