// The batch library (batch/) on its own: manifest lines, job ids, shards,
// records, merging and the Slurm script's quoting; and every code it emits
// is documented for efc explain.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "batch/atomic_file.h"
#include "batch/command.h"
#include "batch/layout.h"
#include "batch/manifest.h"
#include "batch/merge.h"
#include "batch/record.h"
#include "batch/shard.h"
#include "batch/slurm.h"
#include "compiler/diagnostics.h"

namespace {

namespace fs = std::filesystem;
using namespace efc::batch;
using json = nlohmann::ordered_json;

fs::path fresh_dir(const std::string& stem) {
  fs::path p = fs::temp_directory_path() / ("efc-batch-lib-" + std::to_string(getpid()) + "-" + stem);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

std::string read(const fs::path& p) {
  std::string s;
  read_whole_file(p.string(), &s);
  return s;
}

TEST(BatchManifest, WordsQuotesAndComments) {
  std::vector<Word> w;
  int col = 0;
  std::string why;
  ASSERT_TRUE(split_words("  a.json --x 'two words' \"q\\\"uote\" back\\ slash # comment", &w, &col, &why));
  ASSERT_EQ(w.size(), 5u);
  EXPECT_EQ(w[0].text, "a.json");
  EXPECT_EQ(w[0].col, 3);
  EXPECT_EQ(w[2].text, "two words");
  EXPECT_EQ(w[3].text, "q\"uote");
  EXPECT_EQ(w[4].text, "back slash");
  ASSERT_TRUE(split_words("# only a comment", &w, &col, &why));
  EXPECT_TRUE(w.empty());
  ASSERT_TRUE(split_words("a#b", &w, &col, &why));  // '#' inside a word is a character
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].text, "a#b");
  EXPECT_FALSE(split_words("spec.json --profile 'open", &w, &col, &why));
  EXPECT_EQ(col, 21);
  EXPECT_NE(why.find("unterminated"), std::string::npos);
  EXPECT_FALSE(split_words("spec.json \\", &w, &col, &why));
  EXPECT_EQ(col, 11);
}

TEST(BatchManifest, JobIdsAreSafeUniqueAndStable) {
  EXPECT_EQ(job_id(3, "/x/examples/desk_lamp.json"), "00003-desk_lamp");
  EXPECT_EQ(job_id(12, "/data/suite/s0001_x/seq"), "00012-seq");
  EXPECT_EQ(job_id(7, "/a/../../etc/passwd"), "00007-passwd");
  EXPECT_EQ(job_id(8, "/a/$(rm -rf ~) 'x'.json"), "00008-__rm_-rf_____x_");
  EXPECT_EQ(job_id(9, "/a/..hidden.json"), "00009-hidden");
  EXPECT_EQ(job_id(10, "/"), "00010");
  const std::string long_id = job_id(1, "/" + std::string(300, 'a') + ".json");
  EXPECT_LE(long_id.size(), 46u);
  for (const std::string& id : {job_id(8, "/a/b c/\n\t*?.json"), long_id})
    for (char c : id)
      EXPECT_TRUE(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.') << id;
}

TEST(BatchManifest, ReadsJobsAndReportsEveryBadLine) {
  const fs::path dir = fresh_dir("manifest");
  fs::create_directories(dir / "sub");
  write(dir / "sub/list.txt", "# specs\n\nlamp.json --target mujoco\n  /abs/fan.json   # the fan\n../up/x.efc 'a b'\n");
  efc::Diagnostics d;
  std::vector<Job> jobs;
  bool io = false;
  ASSERT_TRUE(read_manifest((dir / "sub/list.txt").string(), d, &jobs, &io));
  ASSERT_EQ(jobs.size(), 3u);
  EXPECT_EQ(jobs[0].line, 3);
  EXPECT_EQ(jobs[0].index, 0);
  EXPECT_EQ(jobs[0].path, (dir / "sub/lamp.json").string());
  EXPECT_EQ(jobs[0].args, (std::vector<std::string>{"--target", "mujoco"}));
  EXPECT_EQ(jobs[0].text, "lamp.json --target mujoco");
  EXPECT_EQ(jobs[1].path, "/abs/fan.json");
  EXPECT_EQ(jobs[1].id, "00004-fan");
  EXPECT_EQ(jobs[2].path, (dir / "up/x.efc").string());
  EXPECT_EQ(jobs[2].args, std::vector<std::string>{"a b"});

  write(dir / "bad.txt", "ok.json\nbad.json \"open\nfine.json\nother.json 'x\n");
  d.clear();
  jobs.clear();
  EXPECT_FALSE(read_manifest((dir / "bad.txt").string(), d, &jobs, &io));
  EXPECT_FALSE(io);
  ASSERT_EQ(d.error_count(), 2u);
  EXPECT_EQ(d.items()[0].code, "E1100");
  EXPECT_EQ(d.items()[0].line, 2);
  EXPECT_EQ(d.items()[0].col, 10);
  EXPECT_EQ(d.items()[1].line, 4);
  EXPECT_TRUE(jobs.empty());

  write(dir / "empty.txt", "# nothing\n\n");
  d.clear();
  EXPECT_FALSE(read_manifest((dir / "empty.txt").string(), d, &jobs, &io));
  EXPECT_EQ(d.items().at(0).code, "E1102");
  d.clear();
  EXPECT_FALSE(read_manifest((dir / "absent.txt").string(), d, &jobs, &io));
  EXPECT_TRUE(io);
  EXPECT_EQ(d.items().at(0).code, "E1101");
  fs::remove_all(dir);
}

TEST(BatchCommand, OutputFlagPlacement) {
  OutputKind kind;
  std::string why;
  EXPECT_FALSE(check_command({}, &kind, &why));
  EXPECT_FALSE(check_command({"batch"}, &kind, &why));
  EXPECT_FALSE(check_command({"frobnicate"}, &kind, &why));
  EXPECT_FALSE(check_command({"compile", "-o", "x"}, &kind, &why));
  EXPECT_FALSE(check_command({"infer", "--output=x"}, &kind, &why));
  ASSERT_TRUE(check_command({"compile", "--target", "all"}, &kind, &why));
  EXPECT_EQ(kind, OutputKind::Folder);
  ASSERT_TRUE(check_command({"play", "--profile", "ramp"}, &kind, &why));
  EXPECT_EQ(kind, OutputKind::None);
  EXPECT_TRUE(check_command({"convert", "-o", "x.efc"}, &kind, &why));  // its -o is a file in the job's folder

  Job job;
  job.path = "/s/lamp.json";
  job.args = {"--seed", "3"};
  EXPECT_EQ(job_argv("/bin/efc", {"synth", "--frames", "20"}, job, OutputKind::Folder, "/d/jobs/1"),
            (std::vector<std::string>{"/bin/efc", "synth", "/s/lamp.json", "--frames", "20", "--seed", "3", "-o",
                                      "/d/jobs/1"}));
  EXPECT_EQ(job_argv("/bin/efc", {"check"}, job, OutputKind::None, "/d/jobs/1"),
            (std::vector<std::string>{"/bin/efc", "check", "/s/lamp.json", "--seed", "3"}));

  job.line = 4;
  job.args = {"--frames", "3", "-oX"};
  job.arg_cols = {10, 19, 21};
  efc::Diagnostics d;
  EXPECT_FALSE(check_line_args({job}, OutputKind::Folder, "m.txt", d));
  ASSERT_EQ(d.error_count(), 1u);
  EXPECT_EQ(d.items()[0].line, 4);
  EXPECT_EQ(d.items()[0].col, 21);
  EXPECT_TRUE(check_line_args({job}, OutputKind::None, "m.txt", d));
}

TEST(BatchShard, ParseSelectAndEnvironment) {
  Shard s;
  std::string why;
  ASSERT_TRUE(parse_shard("1/3", &s, &why));
  EXPECT_TRUE(s.on);
  EXPECT_EQ(s.index, 1);
  EXPECT_EQ(s.count, 3);
  for (const char* bad : {"3/3", "-1/3", "1/0", "1", "a/b", "1/3x", " 1/3", "1//3"})
    EXPECT_FALSE(parse_shard(bad, &s, &why)) << bad;
  std::vector<Job> jobs(7);
  for (int i = 0; i < 7; ++i) jobs[i].index = i;
  ASSERT_TRUE(parse_shard("1/3", &s, &why));
  const std::vector<Job> sel = select_shard(jobs, s);
  ASSERT_EQ(sel.size(), 2u);
  EXPECT_EQ(sel[0].index, 1);
  EXPECT_EQ(sel[1].index, 4);
  EXPECT_EQ(results_name(s), "results-1-of-3.jsonl");
  EXPECT_EQ(results_name(Shard{}), "results.jsonl");
  int i = 0, n = 0;
  EXPECT_TRUE(parse_results_name("results-1-of-3.jsonl", &i, &n));
  EXPECT_FALSE(parse_results_name("results-3-of-3.jsonl", &i, &n));
  EXPECT_FALSE(parse_results_name("results.jsonl", &i, &n));

  unsetenv("SLURM_ARRAY_TASK_ID");
  unsetenv("SLURM_ARRAY_TASK_COUNT");
  unsetenv("SLURM_ARRAY_TASK_MIN");
  Shard e;
  EXPECT_EQ(shard_from_env(&e, &why), 0);
  setenv("SLURM_ARRAY_TASK_ID", "5", 1);
  setenv("SLURM_ARRAY_TASK_COUNT", "4", 1);
  setenv("SLURM_ARRAY_TASK_MIN", "3", 1);
  EXPECT_EQ(shard_from_env(&e, &why), 1);
  EXPECT_EQ(e.index, 2);
  EXPECT_EQ(e.count, 4);
  setenv("SLURM_ARRAY_TASK_ID", "9", 1);
  EXPECT_EQ(shard_from_env(&e, &why), -1);
  unsetenv("SLURM_ARRAY_TASK_ID");
  unsetenv("SLURM_ARRAY_TASK_COUNT");
  unsetenv("SLURM_ARRAY_TASK_MIN");
}

TEST(BatchRecord, CompleteMatchingAndAtomic) {
  const fs::path dir = fresh_dir("record");
  Job job;
  job.line = 2;
  job.text = "lamp.json";
  job.path = "/x/lamp.json";
  job.id = "00002-lamp";
  Outcome o;
  o.exit_code = 1;
  o.seconds = 0.5;
  o.peak_rss_mb = 12;
  o.started = o.finished = utc_now();
  o.diagnostics = std::string("bad byte \xff here\n") + std::string(40000, 'x');
  const json r = make_record(job, {"check"}, o, "host");
  EXPECT_TRUE(record_complete(r));
  EXPECT_TRUE(record_matches(r, job, {"check"}));
  EXPECT_FALSE(record_matches(r, job, {"compile"}));
  Job moved = job;
  moved.text = "lamp.json --x";
  EXPECT_FALSE(record_matches(r, moved, {"check"}));
  EXPECT_LT(r["diagnostics"].get<std::string>().size(), kDiagnosticsLimit + 200);
  EXPECT_NE(r["diagnostics"].get<std::string>().find("more bytes in logs/00002-lamp.stderr"), std::string::npos);
  EXPECT_EQ(r["output"], "jobs/00002-lamp");

  std::string error;
  ASSERT_TRUE(write_file_atomically((dir / "r.json").string(), r.dump(), &error)) << error;
  EXPECT_TRUE(read_record((dir / "r.json").string()).has_value());
  write(dir / "half.json", r.dump().substr(0, 100));
  EXPECT_FALSE(read_record((dir / "half.json").string()).has_value());
  json partial = r;
  partial.erase("exit_code");
  write(dir / "partial.json", partial.dump());
  EXPECT_FALSE(read_record((dir / "partial.json").string()).has_value());
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(kTempPrefix), std::string::npos) << e.path();
  EXPECT_FALSE(write_file_atomically((dir / "no/such/r.json").string(), "x", &error));
  fs::remove_all(dir);
}

TEST(BatchLayout, OnlyBatchFoldersAreUsed) {
  const fs::path dir = fresh_dir("layout");
  std::string why;
  EXPECT_TRUE(usable_batch_dir((dir / "new").string(), &why));
  fs::create_directories(dir / "b/records");
  write(dir / "b/results-0-of-2.jsonl", "");
  write(dir / "b/batch.json", "{}");
  EXPECT_TRUE(usable_batch_dir((dir / "b").string(), &why)) << why;
  write(dir / "b/thesis.tex", "mine");
  EXPECT_FALSE(usable_batch_dir((dir / "b").string(), &why));
  EXPECT_NE(why.find("thesis.tex"), std::string::npos);
  write(dir / "file", "x");
  EXPECT_FALSE(usable_batch_dir((dir / "file").string(), &why));
  fs::remove_all(dir);
}

// Shards made by hand: what --merge accepts and what it refuses.
TEST(BatchMerge, JoinsShardsAndReportsWhatIsMissing) {
  const fs::path dir = fresh_dir("merge");
  std::vector<Job> jobs;
  for (int i = 0; i < 5; ++i) {
    Job j;
    j.line = i + 1;
    j.index = i;
    j.text = "s" + std::to_string(i) + ".json";
    j.path = "/x/" + j.text;
    j.id = job_id(j.line, j.path);
    jobs.push_back(j);
  }
  Layout layout{dir.string()};
  std::string why;
  ASSERT_TRUE(make_batch_dir(layout, &why));
  write(layout.batch_json(), batch_info("/x/m.txt", {"check"}, jobs).dump());
  auto shard_text = [&](int i, int n) {
    std::string t;
    for (const Job& j : jobs) {
      if (j.index % n != i) continue;
      Outcome o;
      o.exit_code = j.index == 3 ? 1 : 0;
      o.started = o.finished = "t";
      t += record_line(make_record(j, {"check"}, o, "h")) + "\n";
    }
    return t;
  };
  efc::Diagnostics d;
  MergeSummary s;
  EXPECT_EQ(merge_shards(dir.string(), d, &s), 1);  // no shards at all
  EXPECT_EQ(d.items().at(0).code, "E1112");

  write(dir / "results-0-of-2.jsonl", shard_text(0, 2));
  d.clear();
  EXPECT_EQ(merge_shards(dir.string(), d, &s), 1);  // shard 1 missing
  ASSERT_EQ(d.error_count(), 1u) << d.items().at(1).message;
  EXPECT_EQ(d.items()[0].code, "E1112");
  EXPECT_NE(d.items()[0].hint.find("--shard 1/2"), std::string::npos) << d.items()[0].hint;
  EXPECT_FALSE(fs::exists(dir / "results.jsonl"));

  // Shard 1 killed after its first job: job s3 (index 3) is missing.
  const std::string one = shard_text(1, 2);
  write(dir / "results-1-of-2.jsonl", one.substr(0, one.find('\n') + 1));
  d.clear();
  EXPECT_EQ(merge_shards(dir.string(), d, &s), 1);
  ASSERT_EQ(d.error_count(), 1u);
  EXPECT_EQ(d.items()[0].code, "E1113");
  EXPECT_EQ(d.items()[0].line, 4);

  write(dir / "results-1-of-2.jsonl", one);
  write(dir / "results-0-of-3.jsonl", shard_text(0, 3));
  d.clear();
  EXPECT_EQ(merge_shards(dir.string(), d, &s), 1);
  EXPECT_EQ(d.items().at(0).code, "E1114");
  fs::remove(dir / "results-0-of-3.jsonl");

  d.clear();
  ASSERT_EQ(merge_shards(dir.string(), d, &s), 0) << (d.items().empty() ? "" : d.items()[0].message);
  EXPECT_EQ(s.shards, 2);
  EXPECT_EQ(s.jobs, 5);
  EXPECT_EQ(s.failed, 1);
  std::istringstream merged(read(dir / "results.jsonl"));
  std::string line;
  int k = 0;
  for (; std::getline(merged, line); ++k) EXPECT_EQ(json::parse(line)["id"], jobs[k].id);  // manifest order
  EXPECT_EQ(k, 5);

  write(dir / "results-0-of-2.jsonl", shard_text(0, 2) + "{\"job\": \n");
  d.clear();
  EXPECT_EQ(merge_shards(dir.string(), d, &s), 1);
  EXPECT_EQ(d.items().at(0).code, "E1114");
  EXPECT_EQ(d.items().at(0).line, 4);
  d.clear();
  EXPECT_EQ(merge_shards((dir / "absent").string(), d, &s), 2);
  fs::remove_all(dir);
}

TEST(BatchSlurm, ScriptQuotesEverything) {
  EXPECT_EQ(shell_quote("a b"), "'a b'");
  EXPECT_EQ(shell_quote("it's"), "'it'\\''s'");
  EXPECT_TRUE(sbatch_safe("/scratch/run 1/out-2.x"));
  for (const char* bad : {"a%b", "a\"b", "a\nb", "a\\b", "a#b", "a$b", "a'b"}) EXPECT_FALSE(sbatch_safe(bad)) << bad;
  SlurmOptions o;
  o.parallel = 2;
  o.cpus_per_task = 2;
  o.mem = "4G";
  o.time = "00:10:00";
  std::string script, why;
  ASSERT_TRUE(
      slurm_script("/opt/efc", "/m/list $(id).txt", "/d/out", {"infer", "--vlm", "x'; rm -rf /"}, 4, o, &script, &why));
  EXPECT_NE(script.find("#SBATCH --array=0-3%2\n"), std::string::npos) << script;
  EXPECT_NE(script.find("#SBATCH --cpus-per-task=2\n"), std::string::npos);
  EXPECT_NE(script.find("#SBATCH --mem=\"4G\"\n"), std::string::npos);
  EXPECT_NE(script.find("#SBATCH --time=\"00:10:00\"\n"), std::string::npos);
  EXPECT_NE(script.find("#SBATCH --output=\"/d/out/logs/%A_%a.out\"\n"), std::string::npos);
  EXPECT_NE(script.find("exec '/opt/efc' batch '/m/list $(id).txt' -o '/d/out' --shard "
                        "\"${SLURM_ARRAY_TASK_ID}/${SLURM_ARRAY_TASK_COUNT}\" -j \"${SLURM_CPUS_PER_TASK:-1}\" -- "
                        "'infer' '--vlm' 'x'\\''; rm -rf /'\n"),
            std::string::npos)
      << script;
  EXPECT_FALSE(slurm_script("/opt/efc", "/m", "/d/100%", {"check"}, 1, o, &script, &why));
  o.partition = "gpu\n#SBATCH --uid=0";
  EXPECT_FALSE(slurm_script("/opt/efc", "/m", "/d/out", {"check"}, 1, o, &script, &why));
}

// The codes batch/ emits are documented (codes_catalogue_test looks at the
// other folders).
TEST(BatchCodes, EveryEmittedCodeIsExplained) {
  const std::regex code_literal("\"([EW][0-9]{4})\"");
  int seen = 0;
  for (const auto& e : fs::recursive_directory_iterator(fs::path(EFC_SOURCE_DIR) / "batch")) {
    if (e.path().extension() != ".cc") continue;
    const std::string text = read(e.path());
    for (std::sregex_iterator it(text.begin(), text.end(), code_literal), end; it != end; ++it) {
      EXPECT_NE(efc::find_code((*it)[1]), nullptr) << (*it)[1] << " in " << e.path();
      ++seen;
    }
  }
  EXPECT_GT(seen, 5);
  for (int c = 1100; c <= 1118; ++c) {
    const efc::CodeInfo* info = efc::find_code("E" + std::to_string(c));
    if (info) {
      EXPECT_GT(std::string(info->explanation).size(), 40u) << c;
    }
  }
}

}  // namespace
