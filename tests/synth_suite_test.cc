// The suite plan (synth/suite/): every object it makes passes the compiler's
// checks through the real loader, the first 20 entries cover every mapping x
// effect pair, the plan is deterministic and prefix-stable, knobs stay in
// their ranges, and a bad examples folder is an error rather than a crash.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>

#include <nlohmann/json.hpp>

#include "compiler/core/load.h"
#include "compiler/core/resolve.h"
#include "synth/suite/example_variation.h"
#include "synth/suite/function_pairs.h"
#include "synth/suite/generated_object.h"
#include "synth/suite/scene_draw.h"
#include "synth/suite/suite_plan.h"

namespace efc::synth {
namespace {

namespace fs = std::filesystem;

const std::string kExamples = std::string(EFC_SOURCE_DIR) + "/examples";
const std::vector<uint64_t> kSeeds = {1, 42, 2024, 0xC0FFEEULL};
constexpr double kPi = 3.14159265358979323846;

// A scratch folder, removed with everything in it.
class ScratchDir {
 public:
  ScratchDir() {
    std::string tmpl = (fs::temp_directory_path() / "synth_suite_test_XXXXXX").string();
    path_ = mkdtemp(tmpl.data()) ? tmpl : "";
  }
  ~ScratchDir() {
    std::error_code ec;
    if (!path_.empty()) fs::remove_all(path_, ec);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

std::string describe(const Diagnostics& diags) {
  std::string out;
  for (const auto& d : diags.items()) out += d.code + " " + d.pointer + ": " + d.message + "\n";
  return out;
}

// Writes the spec as `efc synth-suite` does (DIR/<name>/spec.json plus its
// files) and loads it with the real loader.
struct Loaded {
  std::optional<Object> obj;
  Diagnostics diags;
};
Loaded write_and_load(const std::string& root, const std::string& name,
                      const std::string& spec_json,
                      const std::vector<std::pair<std::string, std::string>>& files) {
  const fs::path dir = fs::path(root) / name;
  fs::create_directories(dir);
  std::ofstream(dir / "spec.json") << spec_json;
  for (const auto& [source, relative] : files) {
    fs::create_directories((dir / relative).parent_path());
    fs::copy_file(source, dir / relative, fs::copy_options::overwrite_existing);
  }
  Loaded out;
  out.obj = load_spec((dir / "spec.json").string(), LoadOptions{}, out.diags);
  return out;
}

const Function* find_function(const Object& obj, const std::string& name) {
  for (const auto& f : obj.functions)
    if (f.name == name) return &f;
  return nullptr;
}

double max_extent(const Part& p) {
  double e = 0;
  for (int k = 0; k < 3; ++k) e = std::max(e, p.bbox_max[k] - p.bbox_min[k]);
  return e;
}

std::vector<SuiteEntry> plan(int count, uint64_t seed, const std::string& examples = kExamples) {
  std::string error;
  std::vector<SuiteEntry> entries = plan_suite(count, seed, examples, nullptr, &error);
  EXPECT_EQ(error, "");
  EXPECT_EQ(entries.size(), static_cast<size_t>(count));
  return entries;
}

// Every function's switching point lies well inside the receptor's travel, so
// the profiles reach it and return below it.
void expect_reachable_switching_points(const Object& obj, const std::string& context) {
  for (const auto& f : obj.functions) {
    if (f.mapping.type == MappingType::Linear) continue;
    double lo, hi;
    receptor_range(obj, f, &lo, &hi);
    const double t = *f.mapping.threshold, span = hi - lo;
    EXPECT_GE(t, lo + 0.1 * span) << context << " " << f.name;
    EXPECT_LE(t, lo + 0.9 * span) << context << " " << f.name;
    if (f.mapping.type == MappingType::Step) {
      EXPECT_GT(t - *f.mapping.hysteresis, lo) << context << " " << f.name;
    }
  }
}

TEST(SynthSuite, EveryEntryLoadsAndNamesItsFunction) {
  ScratchDir scratch;
  ASSERT_FALSE(scratch.path().empty());
  for (uint64_t seed : kSeeds) {
    for (const SuiteEntry& e : plan(60, seed)) {
      SCOPED_TRACE(e.name + " (" + e.origin + ", seed " + std::to_string(seed) + ")");
      Loaded l = write_and_load(scratch.path() + "/" + std::to_string(seed), e.name, e.spec_json,
                                e.files_to_copy);
      ASSERT_TRUE(l.obj) << describe(l.diags) << e.spec_json;
      EXPECT_EQ(l.diags.error_count(), 0u) << describe(l.diags);
      EXPECT_EQ(l.obj->name, e.object);
      const Function* f = find_function(*l.obj, e.function);
      ASSERT_NE(f, nullptr);
      EXPECT_EQ(to_string(f->mapping.type), e.mapping);
      EXPECT_EQ(to_string(f->effect.type), e.effect);
      EXPECT_EQ(f->receptor, e.receptor);
      EXPECT_EQ(f->effector, e.effector);
      const Part& receptor = l.obj->parts[f->receptor_index];
      EXPECT_EQ(to_string(receptor.joint->type), e.receptor_joint);
      // The flag bounds rotated boxes by their sphere, so it may only err
      // towards "not small"; generated objects have no rotated boxes.
      if (e.small_receptor) {
        EXPECT_LE(max_extent(receptor), kSmallReceptorSize + 1e-9);
      }
      if (e.origin == "generated") {
        EXPECT_EQ(e.small_receptor, max_extent(receptor) <= kSmallReceptorSize + 1e-9);
      }
    }
  }
}

TEST(SynthSuite, FirstTwentyCoverEveryPairOnce) {
  for (uint64_t seed : kSeeds) {
    const std::vector<SuiteEntry> entries = plan(20, seed);
    std::set<std::pair<std::string, std::string>> pairs;
    for (const auto& e : entries) pairs.insert({e.mapping, e.effect});
    EXPECT_EQ(pairs.size(), 20u) << "seed " << seed;
    for (const auto& p : suite::all_function_pairs())
      EXPECT_TRUE(pairs.count({p.mapping, p.effect}))
          << p.mapping << "-" << p.effect << " seed " << seed;
  }
}

TEST(SynthSuite, JointTypesSmallReceptorsAndBothOriginsAppear) {
  for (uint64_t seed : kSeeds) {
    const std::vector<SuiteEntry> entries = plan(60, seed);
    std::map<std::string, int> joints;
    int small = 0, examples = 0;
    for (size_t i = 0; i < 20; ++i) {
      joints[entries[i].receptor_joint]++;
      small += entries[i].small_receptor;
    }
    for (const auto& e : entries) examples += e.origin != "generated";
    EXPECT_GE(joints["revolute"], 1) << "seed " << seed;
    EXPECT_GE(joints["prismatic"], 1) << "seed " << seed;
    EXPECT_GE(joints["continuous"], 1) << "seed " << seed;
    EXPECT_GE(small, 4) << "seed " << seed;  // 20 %
    EXPECT_GE(examples, 10) << "seed " << seed;
    EXPECT_GE(60 - examples, 10) << "seed " << seed;
    for (const auto& e : entries)
      if (e.receptor_joint == "continuous") {
        EXPECT_NE(e.mapping, "binary") << e.name;
      }
  }
}

void expect_same(const SuiteEntry& a, const SuiteEntry& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.origin, b.origin);
  EXPECT_EQ(a.spec_json, b.spec_json);
  EXPECT_EQ(a.function, b.function);
  EXPECT_EQ(a.small_receptor, b.small_receptor);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.profile, b.profile);
  EXPECT_EQ(a.files_to_copy, b.files_to_copy);
  EXPECT_EQ(entry_to_json(a).dump(), entry_to_json(b).dump());
  EXPECT_EQ(a.knobs.object_scale, b.knobs.object_scale);
  EXPECT_EQ(a.knobs.camera_distance, b.knobs.camera_distance);
  EXPECT_EQ(a.knobs.light_azimuth, b.knobs.light_azimuth);
  EXPECT_EQ(a.knobs.room_style, b.knobs.room_style);
  EXPECT_EQ(a.knobs.noise, b.knobs.noise);
}

TEST(SynthSuite, SameSeedSamePlanAndPrefixesAgree) {
  const std::vector<SuiteEntry> a = plan(40, 7), b = plan(40, 7), prefix = plan(20, 7),
                                other = plan(40, 8);
  for (size_t i = 0; i < a.size(); ++i) expect_same(a[i], b[i]);
  for (size_t i = 0; i < prefix.size(); ++i) expect_same(prefix[i], a[i]);
  int differing = 0;
  for (size_t i = 0; i < a.size(); ++i) differing += a[i].spec_json != other[i].spec_json;
  EXPECT_GE(differing, 35);
  std::set<std::string> specs;
  for (const auto& e : a) specs.insert(e.spec_json);
  EXPECT_EQ(specs.size(), a.size()) << "two entries of one plan show the same object";
}

TEST(SynthSuite, KnobsStayInTheirRanges) {
  const suite::KnobRanges& r = suite::knob_ranges();
  std::map<NoiseLevel, int> noise;
  std::set<std::string> profiles;
  for (uint64_t seed : kSeeds) {
    for (const SuiteEntry& e : plan(60, seed)) {
      const SceneKnobs& k = e.knobs;
      auto in = [&](double v, const suite::KnobRange& range, const char* what) {
        EXPECT_GE(v, range.lo) << e.name << " " << what;
        EXPECT_LE(v, range.hi) << e.name << " " << what;
      };
      in(k.object_yaw, r.object_yaw, "object_yaw");
      in(k.object_x, r.object_offset, "object_x");
      in(k.object_y, r.object_offset, "object_y");
      in(k.camera_distance, r.camera_distance, "camera_distance");
      in(k.camera_height, r.camera_height, "camera_height");
      // A side receptor moves the camera to 0.55-0.85 rad round towards it
      // (ASideReceptorIsFilmedFromItsSide); the drawn range holds otherwise.
      if (std::abs(k.camera_azimuth) > r.camera_azimuth.hi) EXPECT_LE(std::abs(k.camera_azimuth), 0.85 + 1e-9) << e.name;
      else in(k.camera_azimuth, r.camera_azimuth, "camera_azimuth");
      in(k.head_bob, r.head_bob, "head_bob");
      in(k.glance, r.glance, "glance");
      in(k.fast_turns, r.fast_turns, "fast_turns");
      in(k.jitter, r.jitter, "jitter");
      in(k.light_intensity, r.light_intensity, "light_intensity");
      in(k.light_azimuth, r.light_azimuth, "light_azimuth");
      in(k.ambient, r.ambient, "ambient");
      in(k.room_style, r.room_style, "room_style");
      in(k.hand_scale, r.hand_scale, "hand_scale");
      in(k.skin_tone, r.skin_tone, "skin_tone");
      if (e.origin == "generated") {
        EXPECT_EQ(k.object_scale, 1.0);
      } else {
        in(k.object_scale, {0.75, 1.3}, "object_scale");
      }
      noise[k.noise]++;
      profiles.insert(e.profile);
    }
  }
  EXPECT_GT(noise[NoiseLevel::None], 0);
  EXPECT_GT(noise[NoiseLevel::Mild], noise[NoiseLevel::None]);
  EXPECT_GT(noise[NoiseLevel::Realistic], noise[NoiseLevel::None]);
  // Every recording demonstrates its function: two or three presses.
  EXPECT_EQ(profiles, (std::set<std::string>{"press:2", "press:3"}));
}

TEST(SynthSuite, ForcedNoiseChangesOnlyTheNoise) {
  std::string error;
  const NoiseLevel forced = NoiseLevel::Realistic;
  const std::vector<SuiteEntry> free = plan(30, 5);
  const std::vector<SuiteEntry> fixed = plan_suite(30, 5, kExamples, &forced, &error);
  ASSERT_EQ(fixed.size(), free.size()) << error;
  for (size_t i = 0; i < free.size(); ++i) {
    EXPECT_EQ(fixed[i].knobs.noise, NoiseLevel::Realistic);
    EXPECT_EQ(fixed[i].spec_json, free[i].spec_json);
    EXPECT_EQ(fixed[i].knobs.camera_distance, free[i].knobs.camera_distance);
    EXPECT_EQ(fixed[i].profile, free[i].profile);
  }
}

TEST(SynthSuite, NamesAreUniqueAndFileNameSafe) {
  const std::regex safe("s[0-9]{4}_[a-z]+-[a-z]+_[a-z]+");
  for (uint64_t seed : kSeeds) {
    std::set<std::string> names;
    const std::vector<SuiteEntry> entries = plan(60, seed);
    for (size_t i = 0; i < entries.size(); ++i) {
      const SuiteEntry& e = entries[i];
      EXPECT_TRUE(std::regex_match(e.name, safe)) << e.name;
      EXPECT_EQ(e.name, "s" + std::string(4 - std::to_string(i).size(), '0') + std::to_string(i) +
                            "_" + e.mapping + "-" + e.effect + "_" + e.receptor_joint);
      EXPECT_TRUE(names.insert(e.name).second) << e.name;
    }
  }
}

TEST(SynthSuite, BadInputsAreErrorsNotCrashes) {
  std::string error;
  EXPECT_TRUE(plan_suite(5, 1, "/nonexistent/examples", nullptr, &error).empty());
  EXPECT_NE(error.find("/nonexistent/examples"), std::string::npos) << error;

  ScratchDir scratch;
  std::ofstream(scratch.path() + "/broken.json") << "{\"efc\": 1, \"parts\": [";
  EXPECT_TRUE(plan_suite(5, 1, scratch.path(), nullptr, &error).empty());
  EXPECT_NE(error.find("broken.json"), std::string::npos) << error;

  fs::remove(scratch.path() + "/broken.json");
  std::ofstream(scratch.path() + "/odd.json")
      << "{\"efc\": 1, \"name\": \"odd\", \"parts\": [{\"name\": 3}]}";
  EXPECT_TRUE(plan_suite(5, 1, scratch.path(), nullptr, &error).empty());
  EXPECT_NE(error.find("odd.json"), std::string::npos) << error;

  fs::remove(scratch.path() + "/odd.json");
  std::ofstream(scratch.path() + "/meshless.json")
      << R"({"efc": 1, "name": "m", "parts": [{"name": "b", "geometry": {"mesh": "meshes/none.obj"}}]})";
  EXPECT_TRUE(plan_suite(5, 1, scratch.path(), nullptr, &error).empty());
  EXPECT_NE(error.find("meshless.json"), std::string::npos) << error;
  EXPECT_NE(error.find("none.obj"), std::string::npos) << error;

  EXPECT_TRUE(plan_suite(-1, 1, kExamples, nullptr, &error).empty());
  EXPECT_NE(error, "");
}

// A movable part inside another part's box (the air conditioner's louvre in
// its body, the toaster's carriage) is never in view: such an example gives
// the suite no function. The same example with the part moved out of the box
// does.
TEST(SynthSuite, ExamplesWithAnEnclosedMovingPartAreNotFilmed) {
  std::vector<suite::ExampleSpec> examples;
  std::string error;
  ASSERT_TRUE(suite::load_examples(kExamples, &examples, &error)) << error;
  std::set<std::string> filmed;
  for (const auto& f : suite::operable_functions(examples)) filmed.insert(examples[f.example].name);
  for (const char* hidden : {"air_conditioner", "toaster", "toilet"}) EXPECT_EQ(filmed.count(hidden), 0u) << hidden;
  for (const char* seen : {"stove", "fridge", "desk_lamp", "kitchen_drawer"}) EXPECT_EQ(filmed.count(seen), 1u) << seen;

  ScratchDir inside, outside;
  std::ifstream in(kExamples + "/air_conditioner.json");
  nlohmann::json doc = nlohmann::json::parse(in);
  std::ofstream(fs::path(inside.path()) / "ac.json") << doc.dump(2);
  for (auto& part : doc["parts"])
    if (part["name"] == "louvre") part["geometry"]["box"]["center"] = {0, -0.14, 0.003};  // in front of the body
  std::ofstream(fs::path(outside.path()) / "ac.json") << doc.dump(2);
  ASSERT_TRUE(suite::load_examples(inside.path(), &examples, &error)) << error;
  EXPECT_TRUE(suite::operable_functions(examples).empty());
  ASSERT_TRUE(suite::load_examples(outside.path(), &examples, &error)) << error;
  EXPECT_EQ(suite::operable_functions(examples).size(), 3u);
}

// A receptor on a side face is filmed from that side: the camera stands
// 0.55-0.85 rad round from the front towards it (positive azimuth: +x).
TEST(SynthSuite, ASideReceptorIsFilmedFromItsSide) {
  ScratchDir scratch;
  int side_entries = 0;
  for (uint64_t seed : kSeeds) {
    for (const SuiteEntry& e : plan(40, seed)) {
      Loaded l = write_and_load(scratch.path(), e.name, e.spec_json, e.files_to_copy);
      ASSERT_TRUE(l.obj) << e.name << "\n" << describe(l.diags);
      const Part* base = nullptr;
      const Part* receptor = nullptr;
      for (const Part& p : l.obj->parts) {
        if (p.name == e.receptor) receptor = &p;
        if (!base && !p.joint) base = &p;
      }
      ASSERT_TRUE(base && receptor) << e.name;
      const double cx = 0.5 * (receptor->bbox_min[0] + receptor->bbox_max[0]);
      const double side = cx > base->bbox_max[0] ? 1 : cx < base->bbox_min[0] ? -1 : 0;
      if (side == 0) {  // the front, or a side face it barely stands out of
        EXPECT_LE(std::abs(e.knobs.camera_azimuth), 0.85 + 1e-9) << e.name;
        continue;
      }
      ++side_entries;
      EXPECT_GE(side * e.knobs.camera_azimuth, 0.55 - 1e-9) << e.name;
      EXPECT_LE(side * e.knobs.camera_azimuth, 0.85 + 1e-9) << e.name;
    }
  }
  EXPECT_GE(side_entries, 3);
}

TEST(SynthSuite, NoExamplesFolderMeansGeneratedOnly) {
  ScratchDir scratch;
  const std::vector<SuiteEntry> entries = plan(25, 3, "");
  for (const auto& e : entries) {
    EXPECT_EQ(e.origin, "generated");
    Loaded l = write_and_load(scratch.path(), e.name, e.spec_json, e.files_to_copy);
    EXPECT_TRUE(l.obj) << e.name << "\n" << describe(l.diags);
  }
}

TEST(SynthSuite, ExampleVariationsPassTheChecks) {
  std::vector<suite::ExampleSpec> examples;
  std::string error;
  ASSERT_TRUE(suite::load_examples(kExamples, &examples, &error)) << error;
  ASSERT_GE(examples.size(), 19u);
  ScratchDir scratch;
  std::set<double> scales;
  for (const auto& example : examples) {
    for (uint64_t seed = 0; seed < 30; ++seed) {
      SCOPED_TRACE(example.name + " seed " + std::to_string(seed));
      suite::SuiteRng rng(seed);
      suite::VariedExample varied;
      ASSERT_TRUE(suite::vary_example(example, rng, &varied, &error)) << error;
      scales.insert(varied.scale);
      const std::string name = example.name + "_" + std::to_string(seed);
      Loaded l = write_and_load(scratch.path(), name, varied.spec.dump(2), varied.files);
      ASSERT_TRUE(l.obj) << describe(l.diags) << varied.spec.dump(2);
      // Same structure: parts, functions and their templates.
      ASSERT_EQ(varied.spec["functions"].size(),
                example.doc.value("functions", suite::SpecJson::array()).size());
      for (size_t i = 0; i < varied.spec["functions"].size(); ++i) {
        EXPECT_EQ(varied.spec["functions"][i]["name"], example.doc["functions"][i]["name"]);
        EXPECT_EQ(varied.spec["functions"][i]["mapping"]["type"],
                  example.doc["functions"][i]["mapping"]["type"]);
      }
      EXPECT_NE(varied.spec, example.doc);
    }
  }
  EXPECT_GT(scales.size(), 100u);
}

TEST(SynthSuite, MeshesTravelWithTheSpec) {
  std::vector<suite::ExampleSpec> examples;
  std::string error;
  ASSERT_TRUE(suite::load_examples(kExamples, &examples, &error)) << error;
  const auto faucet = std::find_if(examples.begin(), examples.end(),
                                   [](const auto& e) { return e.name == "kitchen_faucet"; });
  ASSERT_NE(faucet, examples.end());
  suite::SuiteRng rng(9);
  suite::VariedExample varied;
  ASSERT_TRUE(suite::vary_example(*faucet, rng, &varied, &error)) << error;
  ASSERT_EQ(varied.files.size(), 2u);
  std::set<std::string> relative;
  for (const auto& [source, rel] : varied.files) {
    EXPECT_TRUE(fs::path(source).is_absolute()) << source;
    EXPECT_TRUE(fs::exists(source)) << source;
    relative.insert(rel);
  }
  EXPECT_EQ(relative,
            (std::set<std::string>{"meshes/faucet_spout.obj", "meshes/faucet_handle.obj"}));
  // Without the copies the spec does not load: the paths really are relative.
  ScratchDir scratch;
  EXPECT_FALSE(write_and_load(scratch.path(), "bare", varied.spec.dump(2), {}).obj);
  EXPECT_TRUE(write_and_load(scratch.path(), "copied", varied.spec.dump(2), varied.files).obj);
}

// Every request the plan can make, for several seeds: the object loads with
// no error and no warning, stands on the floor at a realistic size, has its
// receptor in front, keeps its switching points reachable, and is small when
// asked to be.
TEST(SynthSuite, GeneratedObjectsPassTheChecksForEveryRequest) {
  ScratchDir scratch;
  int built = 0;
  for (const auto& pair : suite::all_function_pairs()) {
    for (const auto& joint : suite::receptor_joint_types()) {
      if (joint == "continuous" && !suite::continuous_receptor_allowed(pair.mapping)) continue;
      for (bool small : {false, true}) {
        for (uint64_t seed = 0; seed < 8; ++seed) {
          const std::string name = pair.mapping + "_" + pair.effect + "_" + joint +
                                   (small ? "_small_" : "_") + std::to_string(seed);
          SCOPED_TRACE(name);
          suite::SuiteRng rng(seed * 7919 + built);
          const suite::GeneratedObject g =
              suite::generate_object({pair.mapping, pair.effect, joint, small}, rng);
          Loaded l = write_and_load(scratch.path(), name, g.spec.dump(2), {});
          ASSERT_TRUE(l.obj) << describe(l.diags) << g.spec.dump(2);
          EXPECT_EQ(l.diags.warning_count(), 0u) << describe(l.diags);
          const Object& obj = *l.obj;
          const Function* f = find_function(obj, g.function);
          ASSERT_NE(f, nullptr);
          EXPECT_EQ(to_string(f->mapping.type), pair.mapping);
          EXPECT_EQ(to_string(f->effect.type), pair.effect);
          const Part& receptor = obj.parts[f->receptor_index];
          EXPECT_EQ(to_string(receptor.joint->type), joint);
          EXPECT_EQ(max_extent(receptor) <= kSmallReceptorSize + 1e-9, small)
              << max_extent(receptor);
          Vec3 lo{1e9, 1e9, 1e9}, hi{-1e9, -1e9, -1e9};
          for (const Part& p : obj.parts)
            for (int k = 0; k < 3; ++k) {
              lo[k] = std::min(lo[k], p.bbox_min[k]);
              hi[k] = std::max(hi[k], p.bbox_max[k]);
            }
          EXPECT_GE(lo[2], -1e-9);
          const double size = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
          EXPECT_GE(size, 0.1);
          EXPECT_LE(size, 1.2);
          EXPECT_LT((receptor.bbox_min[1] + receptor.bbox_max[1]) / 2, 0)
              << "receptor behind the middle";
          expect_reachable_switching_points(obj, name);
          ++built;
        }
      }
    }
  }
  EXPECT_EQ(built, (15 * 3 + 5 * 2) * 2 * 8);
}

TEST(SynthSuite, GeneratedObjectsVary) {
  // Over a few hundred requests every receptor and effector family appears,
  // with the tricks meant for careless estimators.
  std::set<std::string> receptors, effectors;
  int decoys = 0, indicators = 0, negative_gains = 0, reversed = 0, side = 0;
  for (uint64_t seed = 0; seed < 400; ++seed) {
    suite::SuiteRng pick(seed);
    const auto& pair = pick.pick(suite::all_function_pairs());
    std::string joint = pick.pick(suite::receptor_joint_types());
    if (!suite::continuous_receptor_allowed(pair.mapping)) joint = "revolute";
    const suite::GeneratedObject g =
        suite::generate_object({pair.mapping, pair.effect, joint, pick.chance(0.5)}, pick);
    receptors.insert(g.receptor);
    effectors.insert(g.effector);
    for (const auto& p : g.spec["parts"])
      decoys += p["name"].get<std::string>().rfind("decoy_", 0) == 0;
    indicators += g.spec["functions"].size() > 1;
    const auto& f = g.spec["functions"][0];
    negative_gains += f["mapping"].value("gain", 0.0) < 0;
    reversed += f["effect"]["range"][1].get<double>() < f["effect"]["range"][0].get<double>();
    side += g.spec["description"].get<std::string>().find("on the right") != std::string::npos;
  }
  EXPECT_EQ(receptors, (std::set<std::string>{"knob", "rocker", "lever", "button", "slider",
                                              "drawer", "dial", "crank"}));
  EXPECT_EQ(effectors,
            (std::set<std::string>{"burner", "pot", "lamp", "led", "panel", "spout", "nozzle",
                                   "grille", "vent", "lid", "door", "tray", "ram", "flap"}));
  EXPECT_GT(decoys, 10);
  EXPECT_GT(indicators, 40);
  EXPECT_GT(negative_gains, 3);
  EXPECT_GT(reversed, 10);
  EXPECT_GT(side, 20);
}

TEST(SynthSuite, EntryJsonListsTheIndexFields) {
  const std::vector<SuiteEntry> entries = plan(60, 11);
  for (const auto& e : entries) {
    const nlohmann::json j = entry_to_json(e);
    EXPECT_EQ(j["name"], e.name);
    EXPECT_EQ(j["spec"], e.name + "/spec.json");
    EXPECT_EQ(j["function"], e.function);
    EXPECT_EQ(j["mapping"], e.mapping);
    EXPECT_EQ(j["effect"], e.effect);
    EXPECT_EQ(j["receptor_joint"], e.receptor_joint);
    EXPECT_EQ(j["small_receptor"], e.small_receptor);
    EXPECT_EQ(j["seed"].get<uint64_t>(), e.seed);
    EXPECT_EQ(j["profile"], e.profile);
    EXPECT_EQ(j["knobs"], to_json(e.knobs));
    EXPECT_EQ(j["knobs"]["noise"], to_string(e.knobs.noise));
    EXPECT_EQ(j["files"].size(), e.files_to_copy.size());
    EXPECT_EQ(j["origin"], e.origin);
  }
}

}  // namespace
}  // namespace efc::synth
