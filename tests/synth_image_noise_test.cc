// The synthetic sensor noise (synth/image/noise.h): identity at None,
// reproducible from a seed, and each model shaped as documented.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>

#include "synth/image/noise.h"
#include "synth/image/rng.h"

namespace efc::synth {
namespace {

constexpr double kPi = 3.14159265358979323846;

seq::Intrinsics intrinsics(int w, int h) {
  seq::Intrinsics k;
  k.fx = k.fy = 525.0;
  k.cx = (w - 1) / 2.0;
  k.cy = (h - 1) / 2.0;
  return k;
}

// Depth of the plane n . P = d seen through each pixel (z = d / (n . ray)).
std::vector<float> plane_depth(const seq::Intrinsics& k, int w, int h, double nx, double ny,
                               double nz, double d) {
  std::vector<float> depth(static_cast<size_t>(w) * h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      double rx = (x - k.cx) / k.fx, ry = (y - k.cy) / k.fy;
      depth[static_cast<size_t>(y) * w + x] = static_cast<float>(d / (nx * rx + ny * ry + nz));
    }
  }
  return depth;
}

double dropout_fraction(const std::vector<float>& depth, size_t begin = 0, size_t end = SIZE_MAX) {
  end = std::min(end, depth.size());
  size_t zeros = 0;
  for (size_t i = begin; i < end; ++i) zeros += depth[i] == 0;
  return static_cast<double>(zeros) / static_cast<double>(end - begin);
}

// ---------------------------------------------------------------- rng

TEST(SynthRng, Splitmix64MatchesTheReferenceSequence) {
  // The reference implementation's output for seed 1234567 (Vigna's splitmix64.c).
  Rng rng(1234567);
  EXPECT_EQ(rng.next(), 6457827717110365317ULL);
  EXPECT_EQ(rng.next(), 3203168211198807973ULL);
  EXPECT_EQ(rng.next(), 9817491932198370423ULL);
}

TEST(SynthRng, StreamSeedSeparatesItsInputs) {
  std::set<uint64_t> seen;
  for (uint64_t s = 0; s < 4; ++s)
    for (uint64_t a = 0; a < 16; ++a)
      for (uint64_t b = 0; b < 8; ++b) seen.insert(stream_seed(s, a, b));
  EXPECT_EQ(seen.size(), 4u * 16u * 8u);
  EXPECT_NE(stream_seed(1, 2, 3), stream_seed(1, 3, 2));
  EXPECT_EQ(stream_seed(7, 9), stream_seed(7, 9, 0));
}

TEST(SynthRng, DistributionsHaveTheirMoments) {
  Rng rng(42);
  const int n = 200000;
  double sum = 0, sum2 = 0, usum = 0;
  int lo_hits = 0, hi_hits = 0, chances = 0;
  for (int i = 0; i < n; ++i) {
    double v = rng.normal();
    sum += v;
    sum2 += v * v;
    double u = rng.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    usum += u;
    int k = rng.integer(-2, 2);
    ASSERT_GE(k, -2);
    ASSERT_LE(k, 2);
    lo_hits += k == -2;
    hi_hits += k == 2;
    chances += rng.chance(0.25);
  }
  EXPECT_NEAR(sum / n, 0.0, 0.01);
  EXPECT_NEAR(std::sqrt(sum2 / n), 1.0, 0.01);
  EXPECT_NEAR(usum / n, 0.5, 0.005);
  EXPECT_NEAR(lo_hits / double(n), 0.2, 0.01);
  EXPECT_NEAR(hi_hits / double(n), 0.2, 0.01);
  EXPECT_NEAR(chances / double(n), 0.25, 0.01);
  EXPECT_EQ(rng.integer(3, 3), 3);
  EXPECT_FALSE(Rng(1).chance(0.0));
  EXPECT_TRUE(Rng(1).chance(1.0));
}

// ---------------------------------------------------------------- knobs

TEST(SynthKnobs, NoiseLevelNamesRoundTrip) {
  for (NoiseLevel level : {NoiseLevel::None, NoiseLevel::Mild, NoiseLevel::Realistic}) {
    NoiseLevel parsed = level == NoiseLevel::None ? NoiseLevel::Mild : NoiseLevel::None;
    ASSERT_TRUE(parse_noise_level(to_string(level), &parsed)) << to_string(level);
    EXPECT_EQ(parsed, level);
  }
  EXPECT_STREQ(to_string(NoiseLevel::Realistic), "realistic");
  NoiseLevel untouched = NoiseLevel::Mild;
  EXPECT_FALSE(parse_noise_level("Realistic", &untouched));
  EXPECT_FALSE(parse_noise_level("", &untouched));
  EXPECT_FALSE(parse_noise_level("high", &untouched));
  EXPECT_EQ(untouched, NoiseLevel::Mild);
}

TEST(SynthKnobs, KnobsAsJsonNameEveryField) {
  SceneKnobs k;
  k.object_yaw = 0.5;
  k.fast_turns = 3;
  k.skin_tone = 2;
  k.noise = NoiseLevel::Realistic;
  const nlohmann::json j = to_json(k);
  EXPECT_EQ(j.size(), 18u);
  EXPECT_EQ(j.at("object_yaw").get<double>(), 0.5);
  EXPECT_EQ(j.at("fast_turns").get<int>(), 3);
  EXPECT_EQ(j.at("skin_tone").get<int>(), 2);
  EXPECT_EQ(j.at("camera_distance").get<double>(), 3.2);
  EXPECT_EQ(j.at("noise").get<std::string>(), "realistic");
}

// ---------------------------------------------------------------- None = identity

TEST(SynthNoise, NoneChangesNothingBitForBit) {
  const NoiseParams none = noise_params(NoiseLevel::None);
  const int w = 40, h = 30;
  const auto k = intrinsics(w, h);
  std::vector<float> depth = plane_depth(k, w, h, 0, 0.9, 0.2, 0.2);  // grazing
  depth[5] = 0;
  depth[6] = 0.05f;   // below any sensor's range
  depth[7] = 40.0f;   // beyond it
  depth[8] = std::nanf("");
  std::vector<uint8_t> rgb(static_cast<size_t>(w) * h * 3, 0);  // black: dark dropouts if any
  const std::vector<float> before = depth;
  Rng rng(stream_seed(1, 0, kDepthStream));
  add_depth_noise(none, k, w, h, rgb.data(), &depth, rng);
  ASSERT_EQ(depth.size(), before.size());
  EXPECT_EQ(std::memcmp(depth.data(), before.data(), depth.size() * sizeof(float)), 0);

  std::vector<seq::Pose> poses(50);
  for (size_t i = 0; i < poses.size(); ++i) {
    poses[i].t = i / 30.0;
    poses[i].p = {0.1 * i, -0.3, 1.7};
    poses[i].q = {0.1, 0.2, 0.3, 0.9};  // not quite unit: must stay untouched
  }
  auto drifted = drift_poses(none, poses, 5);
  ASSERT_EQ(drifted.size(), poses.size());
  for (size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(drifted[i].t, poses[i].t);
    EXPECT_EQ(drifted[i].p, poses[i].p);
    EXPECT_EQ(drifted[i].q, poses[i].q);
  }

  std::vector<seq::HandPoint> hands(50);
  for (size_t i = 0; i < hands.size(); ++i) {
    hands[i].t = i / 30.0;
    hands[i].seen = i % 3 != 0;
    hands[i].p = {0.01 * i, 0.2, 0.9};
  }
  auto jittered = jitter_hands(none, hands, 5);
  ASSERT_EQ(jittered.size(), hands.size());
  for (size_t i = 0; i < hands.size(); ++i) {
    EXPECT_EQ(jittered[i].seen, hands[i].seen);
    EXPECT_EQ(jittered[i].p, hands[i].p);
  }

  MaskSet set;
  set.names = {"a", "b"};
  for (int m = 0; m < 2; ++m) {
    seq::Image8 img{w, h, 1, std::vector<uint8_t>(static_cast<size_t>(w) * h, 0)};
    for (int i = 100 + m * 200; i < 300 + m * 200; ++i) img.pixels[i] = 7;  // not even binary
    set.masks.push_back(img);
  }
  const MaskSet original = set;
  for (int frame = 0; frame < 200; ++frame) {
    MaskNoiseLog log = add_mask_noise(none, frame, &set, {{0, 1}}, 9);
    EXPECT_TRUE(log.empty());
  }
  EXPECT_EQ(set.masks[0].pixels, original.masks[0].pixels);
  EXPECT_EQ(set.masks[1].pixels, original.masks[1].pixels);
}

// ---------------------------------------------------------------- reproducibility

TEST(SynthNoise, SameSeedSameBytesOtherSeedOtherBytes) {
  const NoiseParams p = noise_params(NoiseLevel::Realistic);
  const int w = 64, h = 48;
  const auto k = intrinsics(w, h);
  const std::vector<float> truth = plane_depth(k, w, h, 0.3, 0.2, 0.93, 1.2);
  std::vector<uint8_t> rgb(static_cast<size_t>(w) * h * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<uint8_t>(i * 7);
  auto run = [&](uint64_t seed) {
    std::vector<float> d = truth;
    Rng rng(stream_seed(seed, 3, kDepthStream));
    add_depth_noise(p, k, w, h, rgb.data(), &d, rng);
    return d;
  };
  auto a = run(11), b = run(11), c = run(12);
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
  EXPECT_NE(std::memcmp(a.data(), c.data(), a.size() * sizeof(float)), 0);
  EXPECT_NE(std::memcmp(a.data(), truth.data(), a.size() * sizeof(float)), 0);

  std::vector<seq::Pose> poses(100);
  std::vector<seq::HandPoint> hands(100);
  for (size_t i = 0; i < poses.size(); ++i) {
    poses[i].t = hands[i].t = i / 30.0;
    hands[i].seen = true;
  }
  auto pa = drift_poses(p, poses, 11), pb = drift_poses(p, poses, 11), pc = drift_poses(p, poses, 12);
  auto ha = jitter_hands(p, hands, 11), hb = jitter_hands(p, hands, 11), hc = jitter_hands(p, hands, 12);
  bool pose_differs = false, hand_differs = false;
  for (size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(pa[i].p, pb[i].p);
    EXPECT_EQ(pa[i].q, pb[i].q);
    EXPECT_EQ(ha[i].seen, hb[i].seen);
    EXPECT_EQ(ha[i].p, hb[i].p);
    pose_differs |= pa[i].p != pc[i].p;
    hand_differs |= ha[i].p != hc[i].p;
  }
  EXPECT_TRUE(pose_differs);
  EXPECT_TRUE(hand_differs);
}

// ---------------------------------------------------------------- depth

// sigma measured on a fronto-parallel plane (no grazing, no dark pixels).
double measured_sigma(const NoiseParams& p, double z, uint64_t seed) {
  const int w = 160, h = 120;
  const auto k = intrinsics(w, h);
  const std::vector<float> truth = plane_depth(k, w, h, 0, 0, 1, z);
  std::vector<float> d = truth;
  Rng rng(stream_seed(seed, 0, kDepthStream));
  add_depth_noise(p, k, w, h, nullptr, &d, rng);
  double sum2 = 0;
  size_t n = 0;
  for (size_t i = 0; i < d.size(); ++i) {
    if (d[i] == 0) continue;
    double e = static_cast<double>(d[i]) - truth[i];
    sum2 += e * e;
    ++n;
  }
  EXPECT_GT(n, d.size() * 9 / 10);
  return std::sqrt(sum2 / n);
}

TEST(SynthNoise, DepthSigmaGrowsWithTheSquareOfRange) {
  const NoiseParams mild = noise_params(NoiseLevel::Mild);
  const double s1 = measured_sigma(mild, 1.0, 1), s3 = measured_sigma(mild, 3.0, 1);
  // mild: sigma = 0.8 mm + 1.0 mm z^2
  EXPECT_NEAR(s1, 0.0018, 0.0018 * 0.05);
  EXPECT_NEAR(s3, 0.0098, 0.0098 * 0.05);
  EXPECT_NEAR(s3 / s1, 0.0098 / 0.0018, 0.5);
  EXPECT_GT(s3 / s1, 4.0);  // linear growth would give 3

  // realistic: Kinect's 1.2 mm + 1.9 mm (z - 0.4)^2, plus the disparity
  // quantisation's uniform error (step z^2 / (8 f b), variance step^2 / 12).
  const NoiseParams real = noise_params(NoiseLevel::Realistic);
  auto expected = [](double z) {
    double axial = 0.0012 + 0.0019 * (z - 0.4) * (z - 0.4);
    double step = z * z / (8 * 525.0 * 0.075);
    return std::sqrt(axial * axial + step * step / 12);
  };
  const double r1 = measured_sigma(real, 1.0, 2), r3 = measured_sigma(real, 3.0, 2);
  EXPECT_NEAR(r1, expected(1.0), expected(1.0) * 0.15);
  EXPECT_NEAR(r3, expected(3.0), expected(3.0) * 0.15);
  EXPECT_GT(r3 / r1, 5.0);
}

TEST(SynthNoise, RealisticDepthComesInDisparitySteps) {
  const NoiseParams p = noise_params(NoiseLevel::Realistic);
  const int w = 64, h = 48;
  const auto k = intrinsics(w, h);
  std::vector<float> d = plane_depth(k, w, h, 0, 0, 1, 2.0);
  Rng rng(3);
  add_depth_noise(p, k, w, h, nullptr, &d, rng);
  const double fb = 525.0 * 0.075;
  for (float z : d) {
    if (z == 0) continue;
    double steps = fb / z * 8.0;  // disparity in 1/8 pixels: an integer
    ASSERT_NEAR(steps, std::round(steps), 1e-3) << z;
  }
}

TEST(SynthNoise, GrazingSurfacesDropOutFrontalOnesDoNot) {
  const NoiseParams p = noise_params(NoiseLevel::Realistic);
  const int w = 64, h = 48;
  const auto k = intrinsics(w, h);
  const double tilt = 80 * kPi / 180;  // the surface seen 80 deg off its normal
  const std::vector<float> grazing =
      plane_depth(k, w, h, 0, std::sin(tilt), std::cos(tilt), std::cos(tilt));
  const std::vector<float> frontal = plane_depth(k, w, h, 0, 0, 1, 1.0);
  double graze_drop = 0, front_drop = 0;
  const int frames = 20;
  for (int f = 0; f < frames; ++f) {
    std::vector<float> g = grazing, fr = frontal;
    Rng rg(stream_seed(4, f, kDepthStream)), rf(stream_seed(5, f, kDepthStream));
    add_depth_noise(p, k, w, h, nullptr, &g, rg);
    add_depth_noise(p, k, w, h, nullptr, &fr, rf);
    graze_drop += dropout_fraction(g) / frames;
    front_drop += dropout_fraction(fr) / frames;
  }
  // 80 +- 3 deg on a 70..85 ramp: about two thirds lost.
  EXPECT_GT(graze_drop, 0.45);
  EXPECT_LT(graze_drop, 0.9);
  // Frontal: only the speckle rate.
  EXPECT_LT(front_drop, 2 * p.depth_speckle_prob + 0.002);
}

TEST(SynthNoise, DarkSurfacesDropMore) {
  const NoiseParams p = noise_params(NoiseLevel::Realistic);
  const int w = 100, h = 100;
  const auto k = intrinsics(w, h);
  std::vector<float> d = plane_depth(k, w, h, 0, 0, 1, 1.0);
  std::vector<uint8_t> rgb(static_cast<size_t>(w) * h * 3, 200);
  std::fill(rgb.begin(), rgb.begin() + rgb.size() / 2, 0);  // top half black
  Rng rng(6);
  add_depth_noise(p, k, w, h, rgb.data(), &d, rng);
  const double dark = dropout_fraction(d, 0, d.size() / 2);
  const double bright = dropout_fraction(d, d.size() / 2);
  EXPECT_NEAR(dark, p.depth_dark_max_prob, 0.05);
  EXPECT_LT(bright, 0.02);
}

TEST(SynthNoise, DepthOfTheWrongSizeIsLeftAlone) {
  const NoiseParams p = noise_params(NoiseLevel::Realistic);
  std::vector<float> d(50, 1.0f);
  Rng rng(1);
  add_depth_noise(p, intrinsics(10, 10), 10, 10, nullptr, &d, rng);
  EXPECT_EQ(d, std::vector<float>(50, 1.0f));
  add_depth_noise(p, intrinsics(10, 10), 10, 10, nullptr, nullptr, rng);
}

TEST(SynthNoise, ReadingsOutsideTheWorkingRangeAreDropped) {
  const NoiseParams p = noise_params(NoiseLevel::Realistic);
  const int w = 20, h = 10;
  const auto k = intrinsics(w, h);
  std::vector<float> d(static_cast<size_t>(w) * h, 0.2f);     // too near
  std::fill(d.begin() + d.size() / 2, d.end(), 8.0f);         // too far
  Rng rng(7);
  add_depth_noise(p, k, w, h, nullptr, &d, rng);
  EXPECT_EQ(dropout_fraction(d), 1.0);
}

TEST(SynthNoise, QuantizeRoundsToTheNearestUnitAndKeepsNoReading) {
  std::vector<float> d = {0.0f, 1.2344f, 1.2346f, -1.0f, std::nanf(""), 65.535f, 70.0f, 0.0004f};
  seq::Image16 img = quantize_depth(d, 4, 2, 0.001);
  EXPECT_EQ(img.width, 4);
  EXPECT_EQ(img.height, 2);
  ASSERT_EQ(img.pixels.size(), 8u);
  EXPECT_EQ(img.pixels[0], 0);
  EXPECT_EQ(img.pixels[1], 1234);
  EXPECT_EQ(img.pixels[2], 1235);
  EXPECT_EQ(img.pixels[3], 0);
  EXPECT_EQ(img.pixels[4], 0);
  EXPECT_EQ(img.pixels[5], 65535);
  EXPECT_EQ(img.pixels[6], 0);  // beyond 16 bits: no reading, not a wrong one
  EXPECT_EQ(img.pixels[7], 0);
  // Short input: the rest is no reading; another scale.
  seq::Image16 short_img = quantize_depth({2.0f}, 2, 1, 0.0005);
  ASSERT_EQ(short_img.pixels.size(), 2u);
  EXPECT_EQ(short_img.pixels[0], 4000);
  EXPECT_EQ(short_img.pixels[1], 0);
}

// ---------------------------------------------------------------- poses

std::vector<seq::Pose> walking_camera(int frames, double fps) {
  std::vector<seq::Pose> poses(frames);
  for (int i = 0; i < frames; ++i) {
    double t = i / fps;
    poses[i].t = t;
    poses[i].p = {0.5 * std::sin(0.3 * t), 1.6 + 0.01 * std::sin(2 * t), 0.2 * t};
    double yaw = 0.4 * std::sin(0.5 * t);
    poses[i].q = {0.0, 0.0, std::sin(yaw / 2), std::cos(yaw / 2)};
  }
  return poses;
}

// Per-axis rotation error (world frame) of `noisy` against `truth`.
std::array<double, 3> rotation_error(const seq::Pose& noisy, const seq::Pose& truth) {
  const auto& a = noisy.q;
  std::array<double, 4> b = {-truth.q[0], -truth.q[1], -truth.q[2], truth.q[3]};  // conjugate
  std::array<double, 4> e = {a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
                             a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
                             a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
                             a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]};
  double s = e[3] < 0 ? -2.0 : 2.0;
  return {s * e[0], s * e[1], s * e[2]};
}

TEST(SynthNoise, DriftedPosesKeepTimesAndUnitQuaternions) {
  const auto truth = walking_camera(300, 30);
  for (NoiseLevel level : {NoiseLevel::Mild, NoiseLevel::Realistic}) {
    auto noisy = drift_poses(noise_params(level), truth, 3);
    ASSERT_EQ(noisy.size(), truth.size());
    for (size_t i = 0; i < truth.size(); ++i) {
      EXPECT_EQ(noisy[i].t, truth[i].t);
      const auto& q = noisy[i].q;
      EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0, 1e-12);
      double same_side = 0;
      for (int c = 0; c < 4; ++c) same_side += q[c] * truth[i].q[c];
      EXPECT_GT(same_side, 0.9);  // close to the truth and on its side
    }
  }
}

TEST(SynthNoise, DriftGrowsWithTimeAndLevel) {
  const auto truth = walking_camera(1800, 30);  // a minute
  double mild_end2 = 0, real_end2 = 0, mild_early2 = 0;
  const int seeds = 20;
  for (int s = 0; s < seeds; ++s) {
    auto mild = drift_poses(noise_params(NoiseLevel::Mild), truth, 100 + s);
    auto real = drift_poses(noise_params(NoiseLevel::Realistic), truth, 200 + s);
    for (int a = 0; a < 3; ++a) {
      double em = mild.back().p[a] - truth.back().p[a];
      double er = real.back().p[a] - truth.back().p[a];
      double e0 = mild[30].p[a] - truth[30].p[a];  // after one second
      mild_end2 += em * em / (3 * seeds);
      real_end2 += er * er / (3 * seeds);
      mild_early2 += e0 * e0 / (3 * seeds);
    }
  }
  const double T = truth.back().t;
  // Per axis: walk^2 T + jitter^2.
  EXPECT_NEAR(std::sqrt(mild_end2), std::sqrt(0.002 * 0.002 * T + 0.0005 * 0.0005),
              0.3 * 0.002 * std::sqrt(T));
  EXPECT_NEAR(std::sqrt(real_end2), std::sqrt(0.01 * 0.01 * T + 0.002 * 0.002),
              0.3 * 0.01 * std::sqrt(T));
  EXPECT_GT(std::sqrt(real_end2), 3 * std::sqrt(mild_end2));
  EXPECT_GT(std::sqrt(mild_end2), 3 * std::sqrt(mild_early2));  // sqrt(60) ~ 7.7
}

TEST(SynthNoise, PerFrameJitterIsInItsBand) {
  const auto truth = walking_camera(3000, 30);
  const double dt = 1.0 / 30;
  const double deg = kPi / 180;
  for (NoiseLevel level : {NoiseLevel::Mild, NoiseLevel::Realistic}) {
    const NoiseParams p = noise_params(level);
    auto noisy = drift_poses(p, truth, 77);
    double dp2 = 0, dr2 = 0;
    size_t n = 0;
    for (size_t i = 1; i < truth.size(); ++i) {
      auto r0 = rotation_error(noisy[i - 1], truth[i - 1]);
      auto r1 = rotation_error(noisy[i], truth[i]);
      for (int a = 0; a < 3; ++a) {
        double e0 = noisy[i - 1].p[a] - truth[i - 1].p[a];
        double e1 = noisy[i].p[a] - truth[i].p[a];
        dp2 += (e1 - e0) * (e1 - e0);
        dr2 += (r1[a] - r0[a]) * (r1[a] - r0[a]);
        ++n;
      }
    }
    // Frame-to-frame change of the error, per axis: one walk step plus two jitters.
    const double want_p = std::sqrt(p.pose_walk_m * p.pose_walk_m * dt +
                                    2 * p.pose_jitter_m * p.pose_jitter_m);
    const double want_r = deg * std::sqrt(p.pose_walk_deg * p.pose_walk_deg * dt +
                                          2 * p.pose_jitter_deg * p.pose_jitter_deg);
    EXPECT_NEAR(std::sqrt(dp2 / n), want_p, 0.1 * want_p) << to_string(level);
    EXPECT_NEAR(std::sqrt(dr2 / n), want_r, 0.15 * want_r) << to_string(level);
  }
}

// ---------------------------------------------------------------- hands

TEST(SynthNoise, HandsAreMissedAtTheirRateAndJitteredBySigma) {
  for (NoiseLevel level : {NoiseLevel::Mild, NoiseLevel::Realistic}) {
    const NoiseParams p = noise_params(level);
    std::vector<seq::HandPoint> truth(20000);
    for (size_t i = 0; i < truth.size(); ++i) {
      truth[i].t = i / 30.0;
      truth[i].seen = i % 10 != 0;
      truth[i].p = {0.3, -0.1 + 1e-5 * i, 0.9};
    }
    auto noisy = jitter_hands(p, truth, 8);
    ASSERT_EQ(noisy.size(), truth.size());
    size_t seen = 0, missed = 0, n = 0;
    double e2 = 0;
    for (size_t i = 0; i < truth.size(); ++i) {
      EXPECT_EQ(noisy[i].t, truth[i].t);
      if (!truth[i].seen) {
        EXPECT_FALSE(noisy[i].seen);
        continue;
      }
      ++seen;
      if (!noisy[i].seen) {
        ++missed;
        continue;
      }
      for (int a = 0; a < 3; ++a) {
        double e = noisy[i].p[a] - truth[i].p[a];
        e2 += e * e;
        ++n;
      }
    }
    EXPECT_NEAR(double(missed) / seen, p.hand_miss_prob, 0.008) << to_string(level);
    EXPECT_NEAR(std::sqrt(e2 / n), p.hand_sigma_m, 0.05 * p.hand_sigma_m) << to_string(level);
  }
}

// ---------------------------------------------------------------- masks

seq::Image8 blank(int w, int h) {
  return seq::Image8{w, h, 1, std::vector<uint8_t>(static_cast<size_t>(w) * h, 0)};
}

void fill_box(seq::Image8* m, int x0, int y0, int x1, int y1) {
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) m->pixels[static_cast<size_t>(y) * m->width + x] = 255;
}

size_t area(const seq::Image8& m) {
  return static_cast<size_t>(std::count_if(m.pixels.begin(), m.pixels.end(),
                                           [](uint8_t v) { return v != 0; }));
}

TEST(SynthMasks, MorphologyUsesADisc) {
  seq::Image8 dot = blank(11, 11);
  dot.pixels[5 * 11 + 5] = 255;
  seq::Image8 d1 = dot, d2 = dot;
  dilate_mask(&d1, 1);
  dilate_mask(&d2, 2);
  EXPECT_EQ(area(d1), 5u);   // the plus: |offset| <= 1
  EXPECT_EQ(area(d2), 13u);  // offsets with dx^2 + dy^2 <= 4
  EXPECT_EQ(d2.pixels[3 * 11 + 5], 255);   // (0, -2) inside
  EXPECT_EQ(d2.pixels[3 * 11 + 4], 0);     // (-1, -2) outside the disc

  seq::Image8 box = blank(30, 30);
  fill_box(&box, 10, 10, 20, 20);
  seq::Image8 e1 = box, e2 = box;
  erode_mask(&e1, 1);
  erode_mask(&e2, 2);
  EXPECT_EQ(area(e1), 64u);
  EXPECT_EQ(area(e2), 36u);
  erode_mask(&e1, 0);
  EXPECT_EQ(area(e1), 64u);

  // The frame border is not the object's outline.
  seq::Image8 corner = blank(20, 20);
  fill_box(&corner, 0, 0, 10, 10);
  erode_mask(&corner, 1);
  EXPECT_EQ(area(corner), 81u);
  EXPECT_EQ(corner.pixels[0], 255);

  // Not a grey image of its size: untouched, no crash.
  seq::Image8 bad{10, 10, 1, std::vector<uint8_t>(5, 255)};
  dilate_mask(&bad, 2);
  erode_mask(nullptr, 2);
  EXPECT_EQ(bad.pixels.size(), 5u);
}

MaskSet three_parts(int w, int h) {
  MaskSet set;
  set.names = {"handle", "spout", "hand"};
  for (int k = 0; k < 3; ++k) {
    seq::Image8 m = blank(w, h);
    fill_box(&m, 5 + 25 * k, 10, 25 + 25 * k, 40);
    set.masks.push_back(m);
  }
  return set;
}

TEST(SynthMasks, LoggedEditsMatchTheMasks) {
  const int w = 80, h = 50;
  const MaskSet truth = three_parts(w, h);
  for (NoiseLevel level : {NoiseLevel::Mild, NoiseLevel::Realistic}) {
    const NoiseParams p = noise_params(level);
    size_t eroded = 0, dilated = 0, missed = 0, untouched = 0, frames = 600;
    for (size_t f = 0; f < frames; ++f) {
      MaskSet set = truth;
      MaskNoiseLog log = add_mask_noise(p, static_cast<int>(f), &set, {}, 21);
      EXPECT_EQ(log.frame, static_cast<int>(f));
      EXPECT_TRUE(log.swapped.empty());  // no pairs given: never
      EXPECT_EQ(log.eroded.size(), log.eroded_px.size());
      EXPECT_EQ(log.dilated.size(), log.dilated_px.size());
      auto listed = [](const std::vector<std::string>& v, const std::string& s) {
        return std::find(v.begin(), v.end(), s) != v.end();
      };
      for (size_t k = 0; k < 3; ++k) {
        const std::string& name = set.names[k];
        size_t before = area(truth.masks[k]), after = area(set.masks[k]);
        if (listed(log.missed, name)) {
          EXPECT_EQ(after, 0u);
          ++missed;
        } else if (listed(log.eroded, name)) {
          EXPECT_LT(after, before);
          ++eroded;
        } else if (listed(log.dilated, name)) {
          EXPECT_GT(after, before);
          ++dilated;
        } else {
          EXPECT_EQ(set.masks[k].pixels, truth.masks[k].pixels);
          ++untouched;
        }
      }
      for (int r : log.eroded_px) EXPECT_TRUE(r >= 1 && r <= p.mask_radius_px);
      for (int r : log.dilated_px) EXPECT_TRUE(r >= 1 && r <= p.mask_radius_px);
    }
    EXPECT_GT(eroded, 100u) << to_string(level);
    EXPECT_GT(dilated, 100u) << to_string(level);
    EXPECT_GT(untouched, 100u) << to_string(level);
    EXPECT_NEAR(double(missed) / (3 * frames), p.mask_miss_prob, 0.012) << to_string(level);
    EXPECT_GT(missed, 0u) << to_string(level);
  }
}

TEST(SynthMasks, AFrameAloneEqualsTheSameFrameInABatch) {
  const NoiseParams p = noise_params(NoiseLevel::Realistic);
  const MaskSet truth = three_parts(80, 50);
  const std::vector<std::pair<int, int>> pairs = {{0, 1}};
  const int frames = 200;
  std::vector<MaskSet> forward(frames, truth), backward(frames, truth);
  std::vector<MaskNoiseLog> forward_log(frames), backward_log(frames);
  for (int f = 0; f < frames; ++f) forward_log[f] = add_mask_noise(p, f, &forward[f], pairs, 5);
  for (int f = frames - 1; f >= 0; --f) backward_log[f] = add_mask_noise(p, f, &backward[f], pairs, 5);
  bool any_change = false;
  for (int f = 0; f < frames; ++f) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(forward[f].masks[k].pixels, backward[f].masks[k].pixels) << f;
      any_change |= forward[f].masks[k].pixels != truth.masks[k].pixels;
    }
    EXPECT_EQ(forward_log[f].eroded, backward_log[f].eroded);
    EXPECT_EQ(forward_log[f].dilated, backward_log[f].dilated);
    EXPECT_EQ(forward_log[f].missed, backward_log[f].missed);
    EXPECT_EQ(forward_log[f].swapped, backward_log[f].swapped);
  }
  EXPECT_TRUE(any_change);
  MaskSet alone = truth;
  add_mask_noise(p, 137, &alone, pairs, 5);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(alone.masks[k].pixels, forward[137].masks[k].pixels);
  // The mask order in the set does not change a mask's noise either.
  MaskSet reordered;
  reordered.names = {truth.names[2], truth.names[0], truth.names[1]};
  reordered.masks = {truth.masks[2], truth.masks[0], truth.masks[1]};
  add_mask_noise(p, 137, &reordered, {}, 5);
  MaskSet plain = truth;
  add_mask_noise(p, 137, &plain, {}, 5);
  EXPECT_EQ(reordered.masks[1].pixels, plain.masks[0].pixels);
  EXPECT_EQ(reordered.masks[0].pixels, plain.masks[2].pixels);
}

TEST(SynthMasks, SwapsOnlyWhenRealisticAndOnlyBetweenGivenPairs) {
  const int w = 80, h = 50;
  const MaskSet truth = three_parts(w, h);
  const std::vector<std::pair<int, int>> pairs = {{0, 1}};
  const int frames = 3000;
  int mild_swaps = 0, real_swaps = 0;
  for (int f = 0; f < frames; ++f) {
    MaskSet mild = truth, real = truth;
    mild_swaps += static_cast<int>(
        add_mask_noise(noise_params(NoiseLevel::Mild), f, &mild, pairs, 31).swapped.size());
    MaskNoiseLog log = add_mask_noise(noise_params(NoiseLevel::Realistic), f, &real, pairs, 31);
    real_swaps += static_cast<int>(log.swapped.size());
    for (const auto& s : log.swapped) {
      EXPECT_EQ(s.first, "handle");
      EXPECT_EQ(s.second, "spout");
      // "handle" now shows the spout's region (its centre survives a 2 px erosion).
      bool handle_missed =
          std::find(log.missed.begin(), log.missed.end(), "handle") != log.missed.end();
      if (!handle_missed) {
        EXPECT_EQ(real.masks[0].pixels[25 * w + 40], 255);
        EXPECT_EQ(real.masks[0].pixels[25 * w + 15], 0);
      }
    }
  }
  EXPECT_EQ(mild_swaps, 0);
  // 1.5 % of 3000 = 45.
  EXPECT_GT(real_swaps, 25);
  EXPECT_LT(real_swaps, 70);
}

TEST(SynthMasks, BadInputsAreSkippedNotCrashed) {
  const NoiseParams p = noise_params(NoiseLevel::Realistic);
  EXPECT_TRUE(add_mask_noise(p, 0, nullptr, {{0, 1}}, 1).empty());
  MaskSet set;
  set.names = {"a", "b", "c"};
  set.masks = {blank(10, 10), seq::Image8{10, 10, 1, {}}};  // one image short, one empty
  for (int f = 0; f < 300; ++f) {
    MaskSet copy = set;
    add_mask_noise(p, f, &copy, {{0, 1}, {1, 2}, {-1, 7}, {0, 0}}, 1);
    // A swap may move the broken image; it is never resized or filled.
    EXPECT_EQ(copy.masks[0].pixels.size() + copy.masks[1].pixels.size(), 100u);
    EXPECT_EQ(copy.masks.size(), 2u);
  }
}

}  // namespace
}  // namespace efc::synth
