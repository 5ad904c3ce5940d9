// The one helper of the command-line tests (test_cli, test_cli_gnss, test_cli_vessel,
// test_cli_sweep, test_bad_inputs): the built cable_sim's path (CABLE_SIM_EXE, given by
// CMakeLists.txt), running it with arguments and capturing its exit code, stdout and stderr, and a
// scratch folder per test. Header-only: each test executable compiles its own copy.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace md_cli_test {

namespace fs = std::filesystem;

#ifdef CABLE_SIM_EXE
inline const char* const kExe = CABLE_SIM_EXE;
#else
inline const char* const kExe = nullptr;
#endif

inline std::string readText(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

inline void writeText(const fs::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::binary);
  f << text;
  ASSERT_TRUE(f.good()) << p;
}

/// s in single quotes for /bin/sh, its own single quotes escaped.
inline std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// What a run of cable_sim gave: exit code (-1 if it did not exit), stdout, stderr.
struct RunResult {
  int code = -1;
  std::string out, err;
};

/// Run cable_sim with `args`, its stdout and stderr captured through files in `dir`.
inline RunResult runCableSim(const std::vector<std::string>& args, const fs::path& dir) {
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  std::string cmd = shellQuote(kExe);
  for (const auto& a : args) cmd += " " + shellQuote(a);
  cmd += " >" + shellQuote(out.string()) + " 2>" + shellQuote(err.string());
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = readText(out);
  r.err = readText(err);
  return r;
}

/// A test fixture with the tool's path checked (a build without it fails, it does not skip) and
/// a scratch folder dir_ = <tmp>/md_<prefix>_<pid>_<test>, removed after a test that passed.
class CliFixture : public ::testing::Test {
 protected:
  explicit CliFixture(std::string prefix) : prefix_(std::move(prefix)) {}
  void SetUp() override {
    ASSERT_NE(kExe, nullptr) << "CABLE_SIM_EXE is not defined: cable_sim's path was not given to this test";
    ASSERT_TRUE(fs::exists(kExe)) << "cable_sim binary not found at " << kExe;
    dir_ = fs::temp_directory_path() / ("md_" + prefix_ + "_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    if (!HasFailure()) fs::remove_all(dir_, ec);
  }
  RunResult run(const std::vector<std::string>& args) const { return runCableSim(args, dir_); }

  fs::path dir_;

 private:
  std::string prefix_;
};

}  // namespace md_cli_test
