// Every diagnostic code the sources emit is documented for `efc explain`.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "compiler/diagnostics.h"

namespace fs = std::filesystem;

TEST(CodeCatalogue, EveryEmittedCodeIsExplained) {
  const std::regex code_literal("\"([EW][0-9]{4})\"");
  int seen = 0;
  for (const char* dir : {"compiler", "backends", "harness", "cli", "eval", "sequence", "synth", "pipeline"}) {
    for (const auto& e : fs::recursive_directory_iterator(fs::path(EFC_SOURCE_DIR) / dir)) {
      if (e.path().extension() != ".cc" || e.path().filename() == "codes.cc") continue;
      std::ifstream in(e.path());
      std::stringstream ss;
      ss << in.rdbuf();
      const std::string text = ss.str();
      for (std::sregex_iterator it(text.begin(), text.end(), code_literal), end; it != end; ++it) {
        const std::string code = (*it)[1];
        EXPECT_NE(efc::find_code(code), nullptr) << code << " used in " << e.path() << " is not in codes.cc";
        ++seen;
      }
    }
  }
  EXPECT_GT(seen, 50);
}
