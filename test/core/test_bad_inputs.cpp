// The corpus of bad problem and system files under test/data/bad/ (issue 22): each is run through
// the cable_sim binary, which must exit with the code its header states and print every word its
// header lists. Header lines (at the top of each file):
//   # command: static [OPTIONS...]      the subcommand, the file goes right after it
//   # exit: 3                           the expected exit code (cli_app.hpp)
//   # words: key | value | constraint   pieces of the message, separated by " | "
// The expectations were written from the file's intent, not copied from the program's output.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace fs = std::filesystem;
using namespace md_cli_test;

namespace {

/// The corpus must cover the classes of issue 22 with room to spare.
constexpr std::size_t kMinCorpusFiles = 40;

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  const auto e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

struct Expectation {
  std::vector<std::string> command;  ///< subcommand and its options
  int exit_code = -1;
  std::vector<std::string> words;
};

Expectation readHeader(const fs::path& p) {
  Expectation e;
  std::istringstream in(readText(p));
  std::string line;
  while (std::getline(in, line) && line.rfind("#", 0) == 0) {
    auto field = [&](const std::string& key) -> std::string {
      const std::string k = "# " + key + ":";
      return line.rfind(k, 0) == 0 ? trim(line.substr(k.size())) : std::string("\x01");
    };
    std::string v;
    if ((v = field("command")) != "\x01") {
      std::istringstream ws(v);
      for (std::string w; ws >> w;) e.command.push_back(w);
    } else if ((v = field("exit")) != "\x01") {
      e.exit_code = std::atoi(v.c_str());
    } else if ((v = field("words")) != "\x01") {
      std::size_t start = 0;
      while (true) {
        const std::size_t bar = v.find(" | ", start);
        e.words.push_back(trim(v.substr(start, bar == std::string::npos ? std::string::npos : bar - start)));
        if (bar == std::string::npos) break;
        start = bar + 3;
      }
    }
  }
  return e;
}

std::vector<fs::path> corpus() {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(fs::path(MD_SOURCE_DIR) / "test" / "data" / "bad"))
    if (e.path().extension() == ".yaml") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

TEST(BadInputs, CorpusIsLargeAndEveryFileStatesItsExpectation) {
  const auto files = corpus();
  EXPECT_GE(files.size(), kMinCorpusFiles);
  for (const auto& f : files) {
    const Expectation e = readHeader(f);
    EXPECT_FALSE(e.command.empty()) << f << ": no '# command:' line";
    EXPECT_GE(e.exit_code, 2) << f << ": no '# exit:' line (a bad input never exits 0 or 1)";
    EXPECT_FALSE(e.words.empty()) << f << ": no '# words:' line";
  }
}

TEST(BadInputs, EachFileExitsWithItsCodeAndNamesItsWords) {
  ASSERT_NE(kExe, nullptr) << "CABLE_SIM_EXE is not defined: see the test_bad_inputs lines in CMakeLists.txt";
  ASSERT_TRUE(fs::exists(kExe)) << kExe;
  const fs::path dir = fs::temp_directory_path() / ("md_test_bad_inputs_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const auto& f : corpus()) {
    SCOPED_TRACE(f.filename().string());
    const Expectation e = readHeader(f);
    ASSERT_FALSE(e.command.empty());
    std::vector<std::string> args{e.command.front(), f.string()};
    args.insert(args.end(), e.command.begin() + 1, e.command.end());
    if (e.command.front() == "dynamic") args.push_back("--no-progress");
    const RunResult r = runCableSim(args, dir);
    EXPECT_EQ(r.code, e.exit_code) << r.err;
    for (const auto& w : e.words) EXPECT_NE(r.err.find(w), std::string::npos) << "missing \"" << w << "\" in: " << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
}
