// The paper's metrics (eval/), each formula against values worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "eval/chamfer.h"
#include "eval/eval_report.h"
#include "eval/pair_list.h"
#include "eval/paper_metrics.h"
#include "eval/part_matching.h"
#include "eval/surface_sampling.h"

namespace {

using namespace efc;
using namespace efc::eval;

constexpr double kHalfPi = kPi / 2;

// ---------------------------------------------------------------- axes
TEST(AxisError, EqualFlippedAndPerpendicularAxes) {
  EXPECT_NEAR(axis_error_rad({0, 0, 1}, {0, 0, 1}), 0, 1e-12);
  EXPECT_NEAR(axis_error_rad({0, 0, 1}, {0, 0, -3}), 0, 1e-12);  // reversed and unnormalised: same axis
  EXPECT_NEAR(axis_error_rad({1, 0, 0}, {0, 1, 0}), kHalfPi, 1e-12);
  EXPECT_NEAR(axis_error_rad({1, 0, 0}, {std::cos(0.3), std::sin(0.3), 0}), 0.3, 1e-12);
  EXPECT_NEAR(axis_error_rad({1, 1e-17, 0}, {1, 0, 0}), 0, 1e-12);  // |dot| rounded past 1 is clipped
}

TEST(AxisLineDistance, ParallelLinesGiveThePointToLineDistance) {
  // Both along z; the second passes through (3, 4, 7): 5 m from the first.
  EXPECT_NEAR(axis_line_distance({{0, 0, 0}, {0, 0, 1}}, {{3, 4, 7}, {0, 0, -1}}), 5, 1e-12);
}

TEST(AxisLineDistance, SkewLinesGiveTheirCommonPerpendicular) {
  // x axis, and a line along y at height 2: the common perpendicular is 2 m of z.
  EXPECT_NEAR(axis_line_distance({{0, 0, 0}, {1, 0, 0}}, {{5, -1, 2}, {0, 1, 0}}), 2, 1e-12);
  // Along (0, 1, 1) through (0, 0, 3): the common normal is (0, -1, 1)/sqrt(2), 3/sqrt(2) m.
  EXPECT_NEAR(axis_line_distance({{0, 0, 0}, {1, 0, 0}}, {{0, 0, 3}, {0, 1, 1}}), 3 / std::sqrt(2.0), 1e-12);
}

TEST(AxisLineDistance, IntersectingLinesAreZeroApart) {
  EXPECT_NEAR(axis_line_distance({{0, 0, 0}, {1, 0, 0}}, {{1, 2, 0}, {0, 1, 0}}), 0, 1e-12);
}

TEST(ScoreJoint, PrismaticTruthHasNoOriginError) {
  const JointScore s = score_joint(JointType::Prismatic, {{0, 5, 0}, {0, 0, 1}}, JointType::Prismatic,
                                   {{0, 0, 0}, {0, 0, 1}});
  EXPECT_TRUE(s.type_correct);
  EXPECT_FALSE(s.failed);
  EXPECT_EQ(s.origin_error_m, 0);
}

TEST(ScoreJoint, RevoluteAndContinuousAreOneType) {
  const JointScore s = score_joint(JointType::Continuous, {{0, 0.1, 0}, {0, 0, -1}}, JointType::Revolute,
                                   {{0, 0, 0}, {0, 0, 1}});
  EXPECT_TRUE(s.type_correct);
  EXPECT_NEAR(s.axis_error_rad, 0, 1e-12);
  EXPECT_NEAR(s.origin_error_m, 0.1, 1e-12);
  EXPECT_FALSE(score_joint(JointType::Prismatic, {}, JointType::Revolute, {}).type_correct);
}

// ---------------------------------------------------------------- surfaces
Geometry box(const Vec3& size, const Vec3& center = {0, 0, 0}) {
  Geometry g;
  g.kind = GeomKind::Box;
  g.size = size;
  g.center = center;
  return g;
}

Geometry sphere(double r, const Vec3& center = {0, 0, 0}) {
  Geometry g;
  g.kind = GeomKind::Sphere;
  g.radius = r;
  g.center = center;
  return g;
}

TEST(SurfaceSampling, PointsLieOnTheSurfaceAndRepeat) {
  const std::vector<Vec3> a = sample_surface(box({1, 1, 1}), 500, 7);
  ASSERT_EQ(a.size(), 500u);
  for (const Vec3& p : a) {
    const double m = std::max({std::fabs(p[0]), std::fabs(p[1]), std::fabs(p[2])});
    EXPECT_NEAR(m, 0.5, 1e-12);
  }
  EXPECT_EQ(a, sample_surface(box({1, 1, 1}), 500, 7));
  Geometry cyl;
  cyl.kind = GeomKind::Cylinder;
  cyl.radius = 0.2, cyl.length = 1, cyl.axis = {1, 0, 0};
  for (const Vec3& p : sample_surface(cyl, 200, 3)) {
    const double r = std::hypot(p[1], p[2]);
    EXPECT_TRUE(std::fabs(r - 0.2) < 1e-12 || std::fabs(std::fabs(p[0]) - 0.5) < 1e-12);
    EXPECT_LE(r, 0.2 + 1e-12);
  }
}

TEST(SurfaceSampling, CompoundsShareTheirPointsByArea) {
  Geometry g;
  g.kind = GeomKind::Compound;
  g.children = {box({1, 1, 1}, {-10, 0, 0}), box({2, 2, 2}, {10, 0, 0})};  // areas 6 and 24
  int small = 0;
  for (const Vec3& p : sample_surface(g, 4000, 1)) small += p[0] < 0;
  EXPECT_NEAR(small / 4000.0, 0.2, 0.03);
}

TEST(KdTree, FindsTheSameNearestPointAsBruteForce) {
  const std::vector<Vec3> pts = sample_surface(sphere(1), 300, 11);
  const KdTree tree(pts);
  for (const Vec3& q : sample_surface(box({3, 2, 1}), 100, 5)) {
    double best = INFINITY;
    for (const Vec3& p : pts)
      best = std::min(best, (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                                (p[2] - q[2]) * (p[2] - q[2]));
    EXPECT_DOUBLE_EQ(tree.nearest_squared(q), best);
  }
}

TEST(Chamfer, ABoxAgainstItselfIsZero) {
  const std::vector<Vec3> a = sample_surface(box({1, 1, 1}), 2000, 1);
  EXPECT_EQ(chamfer_distance(a, a), 0);
  // Another sampling of the same box: only the sampling gap remains (~1e-4 m^2).
  EXPECT_LT(chamfer_distance(a, sample_surface(box({1, 1, 1}), 2000, 2)), 2e-3);
}

TEST(Chamfer, SurfacesApartByAKnownGap) {
  // Two tiny spheres 1 m apart: every nearest neighbour is ~1 m away, so each
  // side's mean of squares is ~1 m^2 and the two-way sum ~2 m^2.
  EXPECT_NEAR(chamfer_distance(sample_surface(sphere(1e-3), 2000, 1),
                               sample_surface(sphere(1e-3, {1, 0, 0}), 2000, 1)),
              2.0, 0.01);
  // Concentric spheres of radius 1 and 1.5: 0.5 m apart everywhere, 2 x 0.25
  // m^2 (plus the sampling gap, under 3%).
  EXPECT_NEAR(chamfer_distance(sample_surface(sphere(1), 2000, 1), sample_surface(sphere(1.5), 2000, 1)), 0.5,
              0.015);
  // A unit box shifted by 1 cm along x: the two x faces (1/3 of the surface)
  // are 1 cm apart; with identical samples the rest is no farther than 1 cm.
  const double cd = chamfer_distance(sample_surface(box({1, 1, 1}), 2000, 1),
                                     sample_surface(box({1, 1, 1}, {0.01, 0, 0}), 2000, 1));
  EXPECT_GE(cd, 2 * 1e-4 / 3 * 0.9);
  EXPECT_LE(cd, 2 * 1e-4 + 1e-12);
  EXPECT_TRUE(std::isinf(chamfer_distance({}, {{0, 0, 0}})));
}

// ---------------------------------------------------------------- masks
TEST(MaskIoU, EmptyUnionScoresOneAndOverlapsScoreTheirRatio) {
  EXPECT_EQ(mask_iou({0, 0, 0, 0}, {0, 0, 0, 0}), 1);
  EXPECT_EQ(mask_iou({255, 255, 0, 0}, {0, 255, 255, 0}), 1.0 / 3);
  EXPECT_EQ(mask_iou({255, 0, 0, 0}, {0, 0, 0, 0}), 0);
  EXPECT_TRUE((MaskScore{"a", 0.5}.success()));
  EXPECT_FALSE((MaskScore{"a", 0.49}.success()));
}

// ---------------------------------------------------------------- specs
Part make_part(const std::string& name, PartRole role, const Vec3& centre) {
  Part p;
  p.name = name;
  p.role = role;
  p.geometry = box({0.1, 0.1, 0.1}, centre);
  p.bbox_min = {centre[0] - 0.05, centre[1] - 0.05, centre[2] - 0.05};
  p.bbox_max = {centre[0] + 0.05, centre[1] + 0.05, centre[2] + 0.05};
  return p;
}

Part with_joint(Part p, JointType type, const Vec3& axis, const Vec3& origin) {
  p.joint = Joint{};
  p.joint->type = type;
  p.joint->parent = "body";
  p.joint->axis = axis;
  p.joint->origin = origin;
  return p;
}

Function make_function(const std::string& name, const std::string& r, const std::string& e, MappingType m,
                       EffectType fx) {
  Function f;
  f.name = name, f.receptor = r, f.effector = e;
  f.mapping.type = m;
  f.effect.type = fx;
  return f;
}

// A body, a knob (receptor) that turns about z at x = 0.1, a lamp (effector).
PlacedSpec lamp() {
  PlacedSpec s;
  s.object.name = "lamp";
  s.object.parts = {make_part("body", PartRole::Base, {0, 0, 0}),
                    with_joint(make_part("knob", PartRole::Receptor, {0.1, 0, 0}), JointType::Revolute,
                               {0, 0, 1}, {0.1, 0, 0}),
                    with_joint(make_part("bulb", PartRole::Effector, {0, 0, 0.3}), JointType::Fixed, {0, 0, 1},
                               {0, 0, 0})};
  s.object.functions = {
      make_function("light", "knob", "bulb", MappingType::Linear, EffectType::Illumination)};
  return s;
}

TEST(PartMatching, ByNameThenByRoleNearestFirst) {
  PlacedSpec gt = lamp(), pred = lamp();
  pred.object.parts[1].name = "dial";  // receptor, renamed
  pred.object.parts[2].name = "far_light";  // an effector far away
  pred.object.parts[2].bbox_min = {5, 5, 5}, pred.object.parts[2].bbox_max = {5.1, 5.1, 5.1};
  pred.object.parts.push_back(make_part("near_light", PartRole::Effector, {0, 0, 0.31}));
  pred.object.parts.push_back(make_part("body2", PartRole::Other, {0.1, 0, 0}));  // nearer the knob, wrong role
  const std::vector<int> m = match_parts(gt.object, gt.world, pred.object, pred.world);
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m[0], 0);  // body by name
  EXPECT_EQ(m[1], 1);  // knob -> dial (the only receptor)
  EXPECT_EQ(m[2], 3);  // bulb -> near_light (the nearer effector)
}

TEST(EvaluatePair, ASpecAgainstItselfScoresPerfectly) {
  const PlacedSpec gt = lamp();
  const PairResult r = evaluate_pair(gt, &gt, EvalOptions{});
  ASSERT_EQ(r.joints.size(), 1u);  // the fixed bulb is no joint to score
  EXPECT_EQ(r.fixed_parts, 1);      // but a fixed part the prediction kept fixed
  EXPECT_TRUE(r.spurious_joints.empty());
  EXPECT_TRUE(r.joints[0].score.type_correct);
  EXPECT_EQ(r.joints[0].score.axis_error_rad, 0);
  EXPECT_EQ(r.joints[0].score.origin_error_m, 0);
  ASSERT_EQ(r.functions.size(), 1u);
  EXPECT_TRUE(r.functions[0].correct());
  ASSERT_EQ(r.chamfer.size(), 3u);
  for (const ChamferResult& c : r.chamfer) EXPECT_EQ(c.cd_m2, 0.0);
  EXPECT_EQ(r.failures(), 0);
}

TEST(EvaluatePair, WorldFramesAreAppliedBeforeComparing) {
  PlacedSpec gt = lamp(), pred = lamp();
  // The prediction's frame sits 1 m along x, turned 90 degrees about x (its y
  // is the world's z): the same knob axis written in that frame.
  pred.world.rotation = {{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}};
  pred.world.translation = {1, 0, 0};
  pred.object.parts[1].joint->axis = {0, 1, 0};
  pred.object.parts[1].joint->origin = {-0.9, 0, 0};  // world (0.1, 0, 0)
  const PairResult r = evaluate_pair(gt, &pred, EvalOptions{});
  EXPECT_NEAR(r.joints[0].score.axis_error_rad, 0, 1e-12);
  EXPECT_NEAR(r.joints[0].score.origin_error_m, 0, 1e-12);
}

TEST(EvaluatePair, AFailedPredictionScoresTheFailureValues) {
  const PlacedSpec gt = lamp();
  const PairResult r = evaluate_pair(gt, nullptr, EvalOptions{});
  ASSERT_EQ(r.joints.size(), 1u);
  EXPECT_TRUE(r.joints[0].score.failed);
  EXPECT_FALSE(r.joints[0].score.type_correct);
  EXPECT_EQ(r.joints[0].score.axis_error_rad, kHalfPi);
  EXPECT_EQ(r.joints[0].score.origin_error_m, 1.0);
  EXPECT_FALSE(r.functions[0].effect_correct || r.functions[0].mapping_correct);
  for (const ChamferResult& c : r.chamfer) EXPECT_FALSE(c.cd_m2.has_value());
  EXPECT_EQ(r.failures(), 1);
}

TEST(EvaluatePair, APartWithoutAMovableJointIsAFailure) {
  PlacedSpec gt = lamp(), pred = lamp();
  pred.object.parts[1].joint->type = JointType::Fixed;
  pred.object.functions[0].name = "glow";  // matched by its receptor and effector instead
  pred.object.functions[0].mapping.type = MappingType::Step;
  const PairResult r = evaluate_pair(gt, &pred, EvalOptions{});
  EXPECT_TRUE(r.joints[0].score.failed);
  EXPECT_EQ(r.joints[0].score.axis_error_rad, kHalfPi);
  EXPECT_TRUE(r.functions[0].effect_correct);
  EXPECT_FALSE(r.functions[0].mapping_correct);
}

// The truth's fixed bulb, predicted turning: the type accuracy (movable
// joints of the truth) cannot see it; the spurious joints do.
TEST(EvaluatePair, AFixedPartPredictedMovableIsASpuriousJoint) {
  PlacedSpec gt = lamp(), pred = lamp();
  pred.object.parts[2].joint->type = JointType::Revolute;
  const PairResult r = evaluate_pair(gt, &pred, EvalOptions{});
  ASSERT_EQ(r.joints.size(), 1u);
  EXPECT_TRUE(r.joints[0].score.type_correct);
  EXPECT_EQ(r.fixed_parts, 1);
  EXPECT_EQ(r.spurious_joints, std::vector<std::string>{"bulb"});
  const Aggregate a = aggregate({r, evaluate_pair(gt, &gt, EvalOptions{}), evaluate_pair(gt, nullptr, EvalOptions{})});
  EXPECT_EQ(a.fixed_parts, 3);
  EXPECT_EQ(a.spurious_joints, 1);  // a failed prediction moves nothing
  EXPECT_NEAR(*a.spurious_joint_rate_pct, 100.0 / 3, 1e-12);
  EXPECT_DOUBLE_EQ(*a.type_accuracy_pct, 200.0 / 3);
  const nlohmann::json j = aggregate_to_json(a);
  EXPECT_EQ(j["articulation"]["spurious_joints"], 1);
  EXPECT_EQ(j["articulation"]["fixed_parts"], 3);
  EXPECT_EQ(pair_to_json(r, "p", "g")["spurious_joints"], nlohmann::json::array({"bulb"}));
  EXPECT_NE(pair_to_text(r, "p", "g").find("predicted movable: bulb"), std::string::npos);
  EXPECT_NE(aggregate_to_text(a).find("fixed parts predicted movable: 1 of 3"), std::string::npos);
}

TEST(Aggregate, MeansMedianAndGating) {
  const PlacedSpec gt = lamp();
  PairResult good = evaluate_pair(gt, &gt, EvalOptions{});
  good.chamfer[0].cd_m2 = 3.0;  // chamfer values 3, 0, 0 -> median 0, mean 1
  PairResult failed = evaluate_pair(gt, nullptr, EvalOptions{});
  Aggregate a = aggregate({good, failed});
  EXPECT_EQ(a.joints, 2);
  EXPECT_DOUBLE_EQ(*a.type_accuracy_pct, 50);
  EXPECT_DOUBLE_EQ(*a.axis_error_rad_mean, kHalfPi / 2);
  EXPECT_DOUBLE_EQ(*a.origin_error_m_mean, 0.5);
  EXPECT_DOUBLE_EQ(*a.failure_rate_pct, 50);
  EXPECT_EQ(a.chamfer_parts, 3);
  EXPECT_DOUBLE_EQ(*a.chamfer_m2_median, 0);
  EXPECT_DOUBLE_EQ(*a.chamfer_m2_mean, 1);
  EXPECT_DOUBLE_EQ(*a.overall_accuracy_pct, 50);
  EXPECT_FALSE(a.masks_given);
  // The good pair's receptor mask misses: its template no longer counts.
  good.masks = std::vector<MaskScore>{{"knob", 0.2}, {"bulb", 0.9}};
  good.functions[0].masks_ok = false;
  a = aggregate({good, failed});
  EXPECT_TRUE(a.masks_given);
  EXPECT_DOUBLE_EQ(*a.overall_accuracy_pct, 50);
  EXPECT_DOUBLE_EQ(*a.gated_overall_accuracy_pct, 0);
  EXPECT_DOUBLE_EQ(*a.mask_mean_iou, 0.55);
  EXPECT_DOUBLE_EQ(*a.mask_success_rate_pct, 50);
  EXPECT_FALSE(aggregate({}).type_accuracy_pct.has_value());
}

// ---------------------------------------------------------------- frames and lists
TEST(WorldFrameExtension, IdentityWhenAbsentAndLocatedErrorWhenMalformed) {
  Object obj;
  obj.file = "p.json";
  Diagnostics diags;
  WorldFrame w;
  ASSERT_TRUE(object_to_world(obj, diags, &w));
  EXPECT_EQ(w.point({1, 2, 3}), (Vec3{1, 2, 3}));
  obj.extensions["x-efc-object-to-world"] = {0, -1, 0, 1, 1, 0, 0, 2, 0, 0, 1, 3, 0, 0, 0, 1};
  ASSERT_TRUE(object_to_world(obj, diags, &w));
  EXPECT_EQ(w.point({1, 0, 0}), (Vec3{1, 3, 3}));  // rotated 90 degrees about z, then moved
  EXPECT_EQ(w.direction({0, 2, 0}), (Vec3{-1, 0, 0}));
  obj.extensions["x-efc-object-to-world"] = {1, 0, 0};
  obj.positions["/x-efc-object-to-world"] = {4, 28};
  EXPECT_FALSE(object_to_world(obj, diags, &w));
  ASSERT_EQ(diags.items().size(), 1u);
  EXPECT_EQ(diags.items()[0].code, "E1020");
  EXPECT_EQ(diags.items()[0].line, 4);
  EXPECT_EQ(diags.items()[0].col, 28);
}

TEST(PairList, ReadsPairsRelativeToTheListAndLocatesBadLines) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("efc-eval-list-" + std::to_string(getpid()));
  fs::create_directories(dir / "seq");
  std::ofstream(dir / "gt.json") << "{}";
  std::ofstream(dir / "pairs.txt") << "# pred gt\n\npred.json gt.json   # a comment\n"
                                      "p2.json gt.json masks seq\n"
                                      "only_one\n"
                                      "p.json missing.json\n";
  Diagnostics diags;
  std::vector<PairEntry> pairs;
  bool io_error = true;
  EXPECT_FALSE(read_pair_list((dir / "pairs.txt").string(), diags, &pairs, &io_error));
  EXPECT_FALSE(io_error);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0].pred, (dir / "pred.json").string());
  EXPECT_EQ(pairs[0].line, 3);
  EXPECT_EQ(pairs[1].gt_seq, (dir / "seq").string());
  ASSERT_EQ(diags.items().size(), 2u);
  EXPECT_EQ(diags.items()[0].code, "E1021");
  EXPECT_EQ(diags.items()[0].line, 5);
  EXPECT_EQ(diags.items()[0].col, 1);
  EXPECT_EQ(diags.items()[1].line, 6);
  EXPECT_EQ(diags.items()[1].col, 8);
  Diagnostics d2;
  EXPECT_FALSE(read_pair_list((dir / "nope.txt").string(), d2, &pairs, &io_error));
  EXPECT_TRUE(io_error);
  EXPECT_EQ(d2.items()[0].code, "E1022");
  fs::remove_all(dir);
}

}  // namespace
