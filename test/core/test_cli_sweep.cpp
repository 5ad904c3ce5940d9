// Tests of `cable_sim sweep` (src/cli/cmd_sweep.cpp): runs the built binary (CABLE_SIM_EXE) on a
// small sweep of eight short cases of the three-leg test buoy (test/data/small_system.yaml):
// the pool on 2 processes gives the bits of the cases run one by one with `cable_sim dynamic`; a
// sweep killed part way resumes and skips what was finished; a case that fails is recorded and the
// others go on; the GNU parallel job list run by Debian's `parallel`, and one task of the Slurm
// array script, give the same bits; the summary tables agree with the series files.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_runner.hpp"

namespace fs = std::filesystem;
using namespace md_cli_test;

namespace {

const std::string kData = std::string(MD_SOURCE_DIR) + "/test/data/";
constexpr std::size_t kCases = 8;
constexpr double kMbl = 1.2e5;  // [N], set on the chain by the sweep

std::string q(const std::string& s) { return shellQuote(s); }

struct Result {
  int code = -1;
  std::string out;
};

/// Run a shell command line, stdout and stderr together into a file; its exit code.
Result sh(const std::string& cmd, const fs::path& log) {
  Result r;
  const int st = std::system((cmd + " >" + q(log.string()) + " 2>&1").c_str());
  r.code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  r.out = readText(log);
  return r;
}

Result cableSim(const std::string& args, const fs::path& log) { return sh(q(kExe) + " " + args, log); }

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> v;
  std::istringstream in(text);
  std::string l;
  while (std::getline(in, l))
    if (!l.empty()) v.push_back(l);
  return v;
}

/// The eight cases: two sea states, two headings, two seeds of each; 2 s of a 3-leg buoy.
std::string sweepText() {
  return "name: small buoy sweep\n"
         "base: " + kData + "small_system.yaml\n"
         "set:\n"
         "  dynamics.duration: 2\n"
         "  environment.waves: {type: jonswap, hs: 1.0, tp: 5, components: 16, ramp: 1}\n"
         "  materials.chain.mbl: 1.2e5\n"
         "variations:\n"
         "  - {name: hs, key: environment.waves.hs, values: [0.5, 1.5]}\n"
         "  - {name: heading, key: environment.waves.direction_deg, values: [0, 90]}\n"
         "  - {name: seed, key: environment.waves.seed, values: [1, 2], seeds: true}\n"
         "statistics: {gumbel_fit: moments, skip_time: 0.5}\n";
}

/// The sweep run once on the pool, and every case once by `cable_sim dynamic`: the references.
class CliSweep : public ::testing::Test {
 protected:
  static fs::path root_;
  static std::vector<std::string> cases_;
  static Result pool_;

  static void SetUpTestSuite() {
    if (kExe == nullptr) return;
    root_ = fs::temp_directory_path() / ("md_test_cli_sweep_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    writeText(root_ / "sweep.yaml", sweepText());
    pool_ = cableSim("sweep " + q((root_ / "sweep.yaml").string()) + " --out " + q((root_ / "pool").string()) +
                         " --jobs 2 --no-progress",
                     root_ / "pool.log");
    cases_ = lines(readText(root_ / "pool" / "cases.txt"));
    for (const auto& c : cases_)
      cableSim("dynamic " + q((root_ / "pool" / "cases" / (c + ".yaml")).string()) + " --out " +
                   q((root_ / "alone" / c).string()),
               root_ / ("alone_" + c + ".log"));
  }
  static void TearDownTestSuite() {
    if (!root_.empty()) fs::remove_all(root_);
  }
  void SetUp() override {
    // As the other CLI tests: a build without the tool's path fails here, it does not skip.
    ASSERT_NE(kExe, nullptr) << "CABLE_SIM_EXE is not defined: cable_sim's path was not given to this test";
  }

  /// The series of every case in `dir`'s results equal, bit for bit, those of the lone runs.
  static void expectSameAsAlone(const fs::path& dir) {
    for (const auto& c : cases_) {
      const fs::path a = root_ / "alone" / c / "system_timeseries.csv";
      const fs::path b = dir / "results" / c / "system_timeseries.csv";
      ASSERT_TRUE(fs::exists(b)) << b;
      const std::string ta = readText(a);
      EXPECT_GT(ta.size(), 100u) << a;
      EXPECT_EQ(ta, readText(b)) << c;
    }
  }
};

fs::path CliSweep::root_;
std::vector<std::string> CliSweep::cases_;
Result CliSweep::pool_;

}  // namespace

TEST_F(CliSweep, PoolOfTwoGivesTheBitsOfTheCasesRunOneByOne) {
  ASSERT_EQ(pool_.code, 0) << pool_.out;
  ASSERT_EQ(cases_.size(), kCases);
  EXPECT_EQ(cases_.front(), "hs-0.5_heading-0_seed-1");
  EXPECT_NE(pool_.out.find("ran 8 cases on 2 processes: 8 done, 0 failed"), std::string::npos) << pool_.out;
  expectSameAsAlone(root_ / "pool");
  // Each case's results hold the run's log; nothing is left in a temporary folder.
  for (const auto& e : fs::directory_iterator(root_ / "pool" / "results"))
    EXPECT_NE(e.path().filename().string()[0], '.') << e.path();
}

TEST_F(CliSweep, SummaryAgreesWithTheSeriesFiles) {
  ASSERT_EQ(pool_.code, 0) << pool_.out;
  const fs::path dir = root_ / "pool";
  const std::vector<std::string> rows = lines(readText(dir / "summary.csv"));
  ASSERT_EQ(rows.size(), 1 + kCases * 3);  // header, 3 legs a case
  EXPECT_EQ(rows[0], "case,storm,line,samples,max_tension,mean_tension,std_tension,mbl,utilization,top_offset");
  // Row of the first case's leg_nw against its series (t >= skip_time 0.5 s), computed here.
  const std::vector<std::string> ts = lines(readText(dir / "results" / cases_[0] / "system_timeseries.csv"));
  const std::string head = ts[0];
  std::vector<std::string> cols;
  {
    std::stringstream ss(head);
    std::string c;
    while (std::getline(ss, c, ',')) cols.push_back(c);
  }
  const std::size_t col = static_cast<std::size_t>(std::find(cols.begin(), cols.end(), "leg_nw_top_tension") - cols.begin());
  ASSERT_LT(col, cols.size());
  double mx = -1e300;
  int n = 0;
  for (std::size_t k = 1; k < ts.size(); ++k) {
    std::vector<double> v;
    std::stringstream ss(ts[k]);
    std::string c;
    while (std::getline(ss, c, ',')) v.push_back(std::stod(c));
    if (v[0] < 0.5) continue;
    mx = std::max(mx, v[col]);
    ++n;
  }
  const std::string want_prefix = cases_[0] + ",hs-0.5_heading-0,leg_nw," + std::to_string(n) + ",";
  const auto it = std::find_if(rows.begin(), rows.end(), [&](const std::string& r) { return r.rfind(want_prefix, 0) == 0; });
  ASSERT_NE(it, rows.end()) << want_prefix;
  std::vector<std::string> cells;
  {
    std::stringstream ss(*it);
    std::string c;
    while (std::getline(ss, c, ',')) cells.push_back(c);
  }
  ASSERT_GE(cells.size(), 10u);
  constexpr double kPrinted = 1e-11;  // the CSVs carry 12 significant digits
  EXPECT_NEAR(std::stod(cells[4]), mx, kPrinted * mx);
  EXPECT_NEAR(std::stod(cells[7]), kMbl, 0.0);
  EXPECT_NEAR(std::stod(cells[8]), mx / kMbl, 1e-10);
  EXPECT_GT(std::stod(cells[9]), 0.0);  // the buoy moved
  // storms.csv: 4 storms x 3 legs, each over 2 seeds with a fit.
  const std::vector<std::string> storms = lines(readText(dir / "storms.csv"));
  ASSERT_EQ(storms.size(), 1u + 4 * 3);
  for (std::size_t k = 1; k < storms.size(); ++k) EXPECT_NE(storms[k].find(",2,"), std::string::npos) << storms[k];
  EXPECT_NE(storms[1].find(",moments,"), std::string::npos) << storms[1];
  const std::string status = readText(dir / "status.csv");
  EXPECT_EQ(std::count(status.begin(), status.end(), '\n'), static_cast<long>(1 + kCases));
  EXPECT_EQ(status.find("failed"), std::string::npos) << status;
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    EXPECT_GT(fs::file_size(dir / "utilization_vs_hs.png"), 1000u);
    EXPECT_GT(fs::file_size(dir / "utilization_vs_heading.png"), 1000u);
    EXPECT_FALSE(fs::exists(dir / "utilization_vs_seed.png"));  // the seeds are fitted, not plotted
    EXPECT_GT(fs::file_size(dir / "exceedance_hs-0.5_heading-0.png"), 1000u) << "a storm's maxima and their fit";
  }
  // The report: every storm's most loaded line, and no vessel section for a system without one.
  const std::string report = readText(dir / "report.md");
  EXPECT_NE(report.find(std::to_string(kCases) + " of " + std::to_string(kCases) + " cases done"), std::string::npos) << report;
  EXPECT_NE(report.find("| hs-0.5_heading-0 | leg_"), std::string::npos) << report;
  EXPECT_EQ(report.find("Vessel offset"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "offsets.csv"));
}

TEST_F(CliSweep, AKilledSweepResumesAndSkipsWhatWasFinished) {
  const fs::path dir = root_ / "killed";
  const std::string args = "sweep " + q((root_ / "sweep.yaml").string()) + " --out " + q(dir.string()) + " --jobs 1 --no-progress";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::setpgid(0, 0);  // its own group: the kill below takes the pool and its children
    const std::string cmd = q(kExe) + " " + args + " >/dev/null 2>&1";
    ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::setpgid(pid, pid);
  // Wait for the first finished case (at most a minute), then kill the whole sweep.
  auto finished = [&]() {
    std::size_t n = 0;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir / "results", ec))
      if (e.path().filename().string()[0] != '.') ++n;
    return n;
  };
  for (int k = 0; k < 600 && finished() == 0; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  ::kill(-pid, SIGKILL);
  int st = 0;
  ::waitpid(pid, &st, 0);
  const std::size_t before = finished();
  ASSERT_GE(before, 1u);
  std::cout << "killed with " << before << " of " << kCases << " cases finished\n";
  // Again: the finished cases are skipped, the rest run, and every result has the lone run's bits.
  const Result again = cableSim(args, root_ / "killed_again.log");
  ASSERT_EQ(again.code, 0) << again.out;
  if (before < kCases) {
    EXPECT_NE(again.out.find(std::to_string(before) + " already done (skipped)"), std::string::npos) << again.out;
    EXPECT_NE(again.out.find("ran " + std::to_string(kCases - before) + " cases"), std::string::npos) << again.out;
  }
  expectSameAsAlone(dir);
  // A third start runs nothing.
  const Result third = cableSim(args, root_ / "killed_third.log");
  EXPECT_EQ(third.code, 0) << third.out;
  EXPECT_NE(third.out.find("8 already done (skipped)"), std::string::npos) << third.out;
}

TEST_F(CliSweep, AFailedCaseIsRecordedAndTheOthersGoOn) {
  // Three cases of the small catenary, the middle one with a Newton tolerance no step can meet
  // and no fallback step (which would otherwise take every step the implicit scheme cannot).
  writeText(root_ / "fail.yaml",
            "base: " + kData + "small_catenary.yaml\n"
            "set: {dynamics.duration: 0.5, dynamics.dt: 0.1,\n"
            "      dynamics.top_motion: {type: sinusoid, amplitude_x: 1, period: 4}}\n"
            "variations:\n"
            "  - name: solver\n"
            "    values:\n"
            "      - {label: a}\n"
            "      - {label: impossible, set: {dynamics.tolerance: 1.0e-300, dynamics.max_cut_levels: 0, dynamics.max_iterations: 2,\n"
            "                                     dynamics.fallback: false}}\n"
            "      - {label: b, set: {dynamics.dt: 0.05}}\n");
  const fs::path dir = root_ / "fail";
  const Result r = cableSim("sweep " + q((root_ / "fail.yaml").string()) + " --out " + q(dir.string()) + " --jobs 2 --no-progress",
                         root_ / "fail.log");
  EXPECT_EQ(r.code, 4) << r.out;
  EXPECT_NE(r.out.find("2 done, 1 failed"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir / "results" / "solver-a" / "timeseries.csv"));
  EXPECT_TRUE(fs::exists(dir / "results" / "solver-b" / "timeseries.csv"));
  EXPECT_FALSE(fs::exists(dir / "results" / "solver-impossible"));
  const std::string why = readText(dir / "failed" / "solver-impossible" / "error.txt");
  EXPECT_NE(why.find("exit code 4"), std::string::npos) << why;
  EXPECT_TRUE(fs::exists(dir / "failed" / "solver-impossible" / "run.log"));
  const std::string status = readText(dir / "status.csv");
  EXPECT_NE(status.find("solver-impossible,failed,\"exit code 4"), std::string::npos) << status;
  EXPECT_NE(status.find("solver-a,done,"), std::string::npos) << status;
  // The summary has the two good cases (one line each).
  EXPECT_EQ(lines(readText(dir / "summary.csv")).size(), 3u);
}

TEST_F(CliSweep, GnuParallelRunsTheJobList) {
  ASSERT_EQ(std::system("command -v parallel >/dev/null 2>&1"), 0)
      << "GNU parallel is not installed (Debian package parallel; scripts/setup installs it)";
  const fs::path dir = root_ / "parallel";
  const Result emit = cableSim("sweep " + q((root_ / "sweep.yaml").string()) + " --out " + q(dir.string()) + " --emit gnu-parallel",
                            root_ / "emit_parallel.log");
  ASSERT_EQ(emit.code, 0) << emit.out;
  EXPECT_EQ(lines(readText(dir / "jobs.txt")).size(), kCases);
  EXPECT_FALSE(fs::exists(dir / "summary.csv"));  // nothing ran
  const Result par = sh("parallel --will-cite --jobs 2 --halt never < " + q((dir / "jobs.txt").string()), root_ / "parallel.log");
  EXPECT_EQ(par.code, 0) << par.out;
  const Result col = cableSim("sweep --collect " + q(dir.string()), root_ / "collect.log");
  EXPECT_EQ(col.code, 0) << col.out;
  EXPECT_NE(col.out.find("8 of 8 cases done"), std::string::npos) << col.out;
  expectSameAsAlone(dir);
  EXPECT_EQ(readText(dir / "summary.csv"), readText(root_ / "pool" / "summary.csv"));
}

TEST_F(CliSweep, SlurmArrayScriptParsesAndOneTaskRunsItsCase) {
  const fs::path dir = root_ / "slurm";
  const std::string emit_args = "sweep " + q((root_ / "sweep.yaml").string()) + " --out " + q(dir.string()) + " --emit slurm";
  const Result emit = cableSim(emit_args, root_ / "emit_slurm.log");
  ASSERT_EQ(emit.code, 0) << emit.out;
  const fs::path script = dir / "sweep.slurm";
  EXPECT_EQ(sh("bash -n " + q(script.string()), root_ / "bash_n.log").code, 0);
  std::map<std::string, std::string> sbatch;
  const std::regex line_re("^#SBATCH --([a-z-]+)=(.+)$");
  for (const auto& l : lines(readText(script))) {
    std::smatch m;
    if (std::regex_match(l, m, line_re)) sbatch[m[1]] = m[2];
    else EXPECT_NE(l.rfind("#SBATCH", 0), 0u) << "malformed: " << l;
  }
  EXPECT_EQ(sbatch["array"], "0-7");
  EXPECT_TRUE(std::regex_match(sbatch["time"], std::regex("^[0-9]+:[0-5][0-9]:00$"))) << sbatch["time"];
  EXPECT_EQ(sbatch["output"], fs::absolute(dir).lexically_normal().string() + "/slurm/%A_%a.out");
  EXPECT_EQ(sbatch["ntasks"], "1");
  EXPECT_EQ(sbatch["job-name"], "small_buoy_sweep");  // no spaces: sbatch splits the line there
  // Task 3 as Slurm would start it: line 4 of cases.txt.
  const Result task = sh("SLURM_ARRAY_TASK_ID=3 bash " + q(script.string()), root_ / "task3.log");
  ASSERT_EQ(task.code, 0) << task.out;
  const std::string c3 = cases_[3];
  EXPECT_EQ(readText(dir / "results" / c3 / "system_timeseries.csv"),
            readText(root_ / "alone" / c3 / "system_timeseries.csv"));
  // Emitted again, the array leaves the finished case out.
  ASSERT_EQ(cableSim(emit_args, root_ / "emit_slurm2.log").code, 0);
  EXPECT_NE(readText(script).find("#SBATCH --array=0-2,4-7\n"), std::string::npos) << readText(script);
  // Collect before the rest is run: 1 done, 7 not run, exit 4.
  const Result col = cableSim("sweep --collect " + q(dir.string()), root_ / "collect_slurm.log");
  EXPECT_EQ(col.code, 4) << col.out;
  EXPECT_NE(col.out.find("1 of 8 cases done, 0 failed, 7 not run"), std::string::npos) << col.out;
}

TEST_F(CliSweep, BadSweepFilesAndCaseNamesAreRefused) {
  writeText(root_ / "bad.yaml", "base: " + kData + "small_system.yaml\n"
                                "variations: [{name: d, values: [{label: x, remove: \"lines[name=leg_q]\"}]}]\n");
  Result r = cableSim("sweep " + q((root_ / "bad.yaml").string()) + " --out " + q((root_ / "bad").string()), root_ / "bad.log");
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_NE(r.out.find("lines[name=leg_q]"), std::string::npos) << r.out;
  // A key the problem format does not have is caught when the case file is checked.
  writeText(root_ / "bad2.yaml", "base: " + kData + "small_system.yaml\n"
                                 "set: {dynamics.duration: 1, environment.wavez.hs: 2}\n");
  r = cableSim("sweep " + q((root_ / "bad2.yaml").string()) + " --out " + q((root_ / "bad2").string()), root_ / "bad2.log");
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_NE(r.out.find("case base"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("wavez"), std::string::npos) << r.out;
  r = cableSim("sweep --run-case nope --out " + q((root_ / "bad2").string()), root_ / "bad3.log");
  EXPECT_EQ(r.code, 3) << r.out;
  r = cableSim("sweep " + q((root_ / "sweep.yaml").string()) + " --out " + q((root_ / "x").string()) + " --emit pbs",
               root_ / "bad4.log");
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("gnu-parallel or slurm"), std::string::npos) << r.out;
}
