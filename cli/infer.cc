// efc infer SEQ -o OUT [--report] [--no-hands] [--vlm URL] [--threads N]:
// a recording in, a spec out (pipeline/infer/infer.h).
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "cli/commands.h"
#include "pipeline/infer/infer.h"

namespace efc {

namespace {

// The report's stages and parts as a short table (--report).
void print_summary(const nlohmann::ordered_json& report) {
  std::cout << "stage            seconds\n";
  for (const auto& s : report["stages"]) {
    char line[128];
    std::snprintf(line, sizeof line, "%-16s %7.2f\n", s["name"].get<std::string>().c_str(), s["seconds"].get<double>());
    std::cout << line;
  }
  std::cout << "part             joint       source  confidence\n";
  for (const auto& p : report["parts"]) {
    const auto& j = p["joint"];
    char line[160];
    std::snprintf(line, sizeof line, "%-16s %-11s %-7s %s\n", p["name"].get<std::string>().c_str(),
                  j["type"].get<std::string>().c_str(), j["source"].get<std::string>().c_str(),
                  j.contains("confidence") ? std::to_string(j["confidence"].get<double>()).c_str() : "-");
    std::cout << line;
  }
  std::cout << "function         effect        mapping     confidence\n";
  for (const auto& f : report["functions"]) {
    char line[160];
    std::snprintf(line, sizeof line, "%-16s %-13s %-11s %.3f\n", f["name"].get<std::string>().c_str(),
                  f["effect"].value("type", "?").c_str(), f["mapping"].value("type", "?").c_str(),
                  f["confidence"].get<double>());
    std::cout << line;
  }
}

}  // namespace

int cmd_infer(Report& report, const InferArgs& args) {
  if (args.threads < 1 || args.threads > 64)
    return report.fail("E0910", "--threads must be between 1 and 64", kExitUsage);
  pipeline::InferOptions opts;
  opts.observe.threads = args.threads;
  opts.templates.threads = args.threads;
  opts.use_hands = !args.no_hands;
  opts.templates.vlm_endpoint = args.vlm;
  if (opts.templates.vlm_endpoint.empty())
    if (const char* env = std::getenv("EFC_VLM_ENDPOINT")) opts.templates.vlm_endpoint = env;
  if (const char* env = std::getenv("EFC_VLM_MODEL")) opts.templates.vlm_model = env;
  if (isatty(2)) opts.progress = [&report](const std::string& line) { report.note(line); };
  pipeline::InferResult result;
  int rc = pipeline::infer_sequence(args.sequence, opts, report.diags(), &result);
  if (rc == kExitOk) rc = pipeline::write_infer_output(result, args.output, report.diags());
  report.flush();
  if (rc == kExitOk && args.report) print_summary(result.report);
  return rc;
}

}  // namespace efc
