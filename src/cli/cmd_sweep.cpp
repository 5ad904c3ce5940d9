// cable_sim sweep: load-case sweeps (docs/design_analysis.md). The sweep file is expanded into
// complete problem files (core/io/sweep_io), which run on a local process pool (one child
// process per case: this binary's `sweep --run-case`), or are handed to GNU parallel or a Slurm
// job array; `--collect` summarises what came back (core/io/sweep_summary) in CSV tables and plots.
//
// Output folder DIR:
//   manifest.yaml          the variations and cases (what --collect reads)
//   cases.txt              one case name a line (the Slurm array's index -> case)
//   cases/<case>.yaml      the case's problem file: `cable_sim dynamic DIR/cases/<case>.yaml` reruns it
//   results/<case>/        a finished case: what `cable_sim dynamic --out` writes, and run.log
//   failed/<case>/         a failed case: its outputs so far, run.log and error.txt
//   summary.csv, storms.csv, status.csv, offsets.csv, utilization_vs_<variation>.png   (the summary)
//   report.md, exceedance_<storm>.png, vessel_offset.png   (the report: sweep_report.hpp)
//   jobs.txt / sweep.slurm (--emit)
// The summary and the report (--collect, and at the end of a local run): sweep_collect.cpp.
// A case runs into results/.<case>.tmp.<host>.<pid> and is renamed when it ends: a results/<case>
// folder is always complete, and a sweep started again skips it.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <ostream>
#include <sstream>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "cli_common.hpp"
#include "mooring_dynamics/core/io/problem_io.hpp"
#include "mooring_dynamics/core/io/sweep_io.hpp"
#include "mooring_dynamics/core/io/sweep_summary.hpp"
#include "sweep_collect.hpp"

namespace mooring_dynamics {
namespace cli {
namespace detail {

namespace {

/// Wall time of one node and base time step of a case, for the Slurm time limit. Measured with
/// `cable_sim dynamic` on the 2-core development machine: config/three_leg_buoy.yaml (3-D, 453
/// nodes, 120 steps, no waves) 2.1e-5 s; test/data/small_system.yaml in regular waves (93 nodes,
/// 200 steps) 9.7e-5 s; config/three_leg_buoy_sweep.yaml's H_s = 6 m cases (100 wave components,
/// time-step cuts; 453 nodes, 240 steps) 1.9e-4 s. The largest, rounded up; 2-D lines cost less.
constexpr double kSecondsPerNodeStep = 2.0e-4;
/// The Slurm time limit is this many times the estimate (slower nodes, time-step cuts), at least kMinSlurmMinutes.
constexpr double kSlurmTimeFactor = 4.0;
constexpr double kMinSlurmMinutes = 10.0;

std::string readText(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::string hostName() {
  char buf[256] = {0};
  if (::gethostname(buf, sizeof buf - 1) != 0) return "host";
  std::string h;
  for (const char* c = buf; *c; ++c) h += (std::isalnum(static_cast<unsigned char>(*c)) || *c == '-') ? *c : '-';
  return h.empty() ? "host" : h;
}

std::string exitMeaning(int code) {
  switch (code) {
    case kExitOk: return "success";
    case kExitInternal: return "internal error";
    case kExitUsage: return "usage error";
    case kExitBadInput: return "bad input";
    case kExitNotConverged: return "did not converge / stopped early";
    case kExitIo: return "I/O error";
    default: return "unexpected exit code";
  }
}

// ---------------------------------------------------------------------------------------------
// One case (`sweep --run-case NAME --out DIR`): run in this process into a temporary folder,
// renamed when done.

/// Remove temporary folders of `name` left on this host by processes that no longer run.
void removeStaleTemps(const SweepDirs& d, const std::string& name, const std::string& host) {
  std::error_code ec;
  const std::string prefix = "." + name + ".tmp." + host + ".";
  for (const auto& e : fs::directory_iterator(d.results, ec)) {
    const std::string f = e.path().filename().string();
    if (f.rfind(prefix, 0) != 0) continue;
    const std::string pid_text = f.substr(prefix.size());
    if (pid_text.empty() || pid_text.find_first_not_of("0123456789") != std::string::npos) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(pid_text));
    if (::kill(pid, 0) != 0 && errno == ESRCH) fs::remove_all(e.path(), ec);
  }
}

int runOneCase(const fs::path& dir, const std::string& name, std::ostream& out, std::ostream& err) {
  const SweepDirs d(dir);
  const fs::path problem = d.caseFile(name);
  if (!fs::is_regular_file(problem)) {
    err << kProg << ": error: --run-case " << name << ": no case file " << problem.string()
        << " (write the cases first with 'cable_sim sweep SWEEP.yaml --out DIR [--emit ...]')\n";
    return kExitBadInput;
  }
  std::error_code ec;
  if (fs::is_directory(d.results / name, ec)) {
    out << name << ": already done (" << (d.results / name).string() << ")\n";
    return kExitOk;
  }
  const std::string host = hostName();
  fs::create_directories(d.results, ec);
  removeStaleTemps(d, name, host);
  const fs::path tmp = d.results / ("." + name + ".tmp." + host + "." + std::to_string(::getpid()));
  fs::remove_all(tmp, ec);
  if (!makeOutputDir(tmp, err)) return kExitIo;
  std::ofstream log(tmp / "run.log", std::ios::binary);
  std::ostringstream errors;
  int code = kExitInternal;
  {
    ParsedArgs a;
    a.positionals.push_back(problem.string());
    a.values["out"] = tmp.string();
    a.flags = {"out", "no-progress"};
    try {
      code = runDynamicCmd(a, log, errors);
    } catch (const std::exception& e) {
      errors << kProg << ": error: " << e.what() << "\n";
      code = kExitInternal;
    }
  }
  log << errors.str();
  log.close();
  if (code == kExitOk) {
    fs::remove_all(d.failed / name, ec);
    fs::rename(tmp, d.results / name, ec);
    if (ec) {  // another process finished it first (the same case run twice): keep theirs
      fs::remove_all(tmp, ec);
      if (!fs::is_directory(d.results / name)) {
        err << kProg << ": error: cannot move " << tmp.string() << " to " << (d.results / name).string() << "\n";
        return kExitIo;
      }
    }
    out << name << ": done\n";
    return kExitOk;
  }
  std::ofstream(tmp / "error.txt", std::ios::binary)
      << "exit code " << code << " (" << exitMeaning(code) << ")\n" << errors.str();
  fs::create_directories(d.failed, ec);
  fs::remove_all(d.failed / name, ec);
  fs::rename(tmp, d.failed / name, ec);
  if (ec) fs::remove_all(tmp, ec);
  err << name << ": FAILED (exit code " << code << ", " << exitMeaning(code) << "): " << errors.str();
  return code;
}

// ---------------------------------------------------------------------------------------------
// Writing the cases

/// Number of nodes and time steps of a case (for the Slurm estimate).
double caseWork(const fs::path& problem) {
  auto nodes = [](const std::vector<core::Segment>& segs) {
    double n = 1.0;
    for (const auto& s : segs) n += std::ceil(s.length / s.spacing);
    return n;
  };
  double n = 0.0, duration = 0.0, dt = 0.1;
  if (core::isSystemFile(problem.string())) {
    const core::SystemProblem s = core::loadSystemFromFile(problem.string());
    for (const auto& l : s.lines) n += nodes(l.segments);
    duration = s.dynamics.duration;
    dt = s.dynamics.dt;
  } else {
    const core::Problem p = core::loadProblemFromFile(problem.string());
    n = nodes(p.segments);
    duration = p.dynamics.duration;
    dt = p.dynamics.dt;
  }
  return n * (dt > 0.0 ? duration / dt : 0.0);
}

/// Loads a case's problem file as `cable_sim dynamic` will; the message when it is not runnable.
std::string checkCase(const fs::path& file) {
  try {
    if (core::isSystemFile(file.string())) {
      const core::SystemProblem s = core::loadSystemFromFile(file.string());
      const std::string v = s.validate();
      if (!v.empty()) return v;
      if (!(s.dynamics.duration > 0.0) && !(s.vessel.present && !s.vessel.motion_table.empty()))
        return "dynamics.duration: not given; a sweep runs `cable_sim dynamic` on every case (set dynamics.duration)";
      return "";
    }
    const core::Problem p = core::loadProblemFromFile(file.string());
    const std::string v = p.validate();
    if (!v.empty()) return v;
    if (!(p.dynamics.duration > 0.0))
      return "dynamics.duration: not given; a sweep runs `cable_sim dynamic` on every case (set dynamics.duration)";
    return "";
  } catch (const std::exception& e) {
    return e.what();
  }
}

struct Written {
  core::SweepSpec spec;
  std::vector<core::SweepCase> cases;
};

/// Expand the sweep into DIR; false (message on err) on a bad sweep or case.
int writeCases(const std::string& sweep_path, const SweepDirs& d, Written& w, std::ostream& out, std::ostream& err) {
  try {
    w.spec = core::loadSweepFromFile(sweep_path);
    w.cases = core::expandSweep(w.spec);
  } catch (const std::exception& e) {
    err << kProg << ": error: " << e.what() << "\n";
    return kExitBadInput;
  }
  for (const fs::path& p : {d.root, d.cases, d.results, d.failed})
    if (!makeOutputDir(p, err)) return kExitIo;
  std::size_t stale = 0;
  for (const auto& c : w.cases) {
    std::string text;
    try {
      text = core::caseProblemText(w.spec, c, d.cases.string());
    } catch (const std::exception& e) {
      err << kProg << ": error: " << sweep_path << ": case " << c.name << ": " << e.what() << "\n";
      return kExitBadInput;
    }
    const fs::path f = d.caseFile(c.name);
    std::error_code ec;
    if (fs::exists(f, ec) && readText(f) == text) continue;
    // A new or changed case: results of an earlier version of it are stale.
    if (fs::exists(d.results / c.name, ec) || fs::exists(d.failed / c.name, ec)) ++stale;
    fs::remove_all(d.results / c.name, ec);
    fs::remove_all(d.failed / c.name, ec);
    if (!writeFile(f, [&](std::ostream& o) { o << text; }, err)) return kExitIo;
    const std::string bad = checkCase(f);
    if (!bad.empty()) {
      err << kProg << ": error: " << sweep_path << ": case " << c.name << " (" << f.string() << "): " << bad << "\n";
      fs::remove(f, ec);
      return kExitBadInput;
    }
  }
  const core::SweepManifest m = core::manifestOf(w.spec, w.cases);
  if (!writeFile(d.root / "manifest.yaml", [&](std::ostream& o) { o << core::manifestText(m); }, err)) return kExitIo;
  if (!writeFile(d.root / "cases.txt", [&](std::ostream& o) {
        for (const auto& c : w.cases) o << c.name << "\n";
      }, err))
    return kExitIo;
  out << w.spec.name << ": " << w.cases.size() << " cases in " << d.cases.string() << "\n";
  if (stale > 0) out << "  " << stale << " changed since the last run: their old results were removed\n";
  return kExitOk;
}

bool isDone(const SweepDirs& d, const std::string& name) {
  std::error_code ec;
  return fs::is_directory(d.results / name, ec);
}

// ---------------------------------------------------------------------------------------------
// The local process pool

class SweepProgress {
 public:
  SweepProgress(std::ostream& err, bool show, std::size_t total)
      : err_(err), show_(show), total_(total), start_(std::chrono::steady_clock::now()) {}
  void update(std::size_t done, std::size_t failed) {
    if (!show_) return;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const std::size_t finished = done + failed;
    const double frac = total_ > 0 ? static_cast<double>(finished) / static_cast<double>(total_) : 1.0;
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(std::lround(frac * kWidth));
    std::string line = "\r[" + std::string(filled, '#') + std::string(kWidth - filled, ' ') + "] " +
                       std::to_string(finished) + "/" + std::to_string(total_) + " cases";
    if (failed > 0) line += " (" + std::to_string(failed) + " failed)";
    line += "  " + fmtNum("%.0f", wall) + " s";
    if (finished > 0 && finished < total_) line += "  ETA " + fmtNum("%.0f", wall * (1.0 - frac) / frac) + " s";
    err_ << line << "    " << std::flush;
    drawn_ = true;
  }
  void finish() {
    if (drawn_) err_ << "\n" << std::flush;
  }

 private:
  std::ostream& err_;
  bool show_;
  std::size_t total_;
  std::chrono::steady_clock::time_point start_;
  bool drawn_ = false;
};

/// Start `exe sweep --run-case name --out dir` in a child process (output to /dev/null: the case
/// writes its own run.log). Returns the pid, or -1.
pid_t spawnCase(const std::string& exe, const std::string& name, const std::string& dir) {
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  const int devnull = ::open("/dev/null", O_RDWR);
  if (devnull >= 0) {
    ::dup2(devnull, 0);
    ::dup2(devnull, 1);
    ::dup2(devnull, 2);
  }
  const char* argv[] = {exe.c_str(), "sweep", "--run-case", name.c_str(), "--out", dir.c_str(), nullptr};
  ::execv(exe.c_str(), const_cast<char* const*>(argv));
  ::_exit(127);
}

/// The failure of a child that did not record one itself (killed, or could not start).
void recordFailure(const SweepDirs& d, const std::string& name, const std::string& why) {
  std::error_code ec;
  if (fs::is_directory(d.failed / name, ec)) return;
  fs::create_directories(d.failed / name, ec);
  std::ofstream(d.failed / name / "error.txt") << why << "\n";
}

int runPool(const std::vector<std::string>& pending, const SweepDirs& d, std::size_t jobs, bool progress,
            std::ostream& out, std::ostream& err) {
  std::error_code ec;
  const std::string exe = fs::read_symlink("/proc/self/exe", ec).string();
  if (ec || exe.empty()) {
    err << kProg << ": error: cannot find this program's path (/proc/self/exe) to start the cases\n";
    return kExitIo;
  }
  const std::string dir = fs::absolute(d.root).string();
  SweepProgress bar(err, progress, pending.size());
  std::map<pid_t, std::string> running;
  std::size_t next = 0, done = 0, failed = 0;
  bar.update(0, 0);
  while (next < pending.size() || !running.empty()) {
    while (next < pending.size() && running.size() < jobs) {
      const pid_t pid = spawnCase(exe, pending[next], dir);
      if (pid < 0) {
        recordFailure(d, pending[next], "could not start a process (fork failed)");
        ++failed;
      } else {
        running[pid] = pending[next];
      }
      ++next;
    }
    if (running.empty()) continue;
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      break;
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const std::string name = it->second;
    running.erase(it);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && isDone(d, name)) {
      ++done;
    } else {
      ++failed;
      if (WIFSIGNALED(status))
        recordFailure(d, name, "killed by signal " + std::to_string(WTERMSIG(status)));
      else if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
        recordFailure(d, name, "could not start " + exe);
      else
        recordFailure(d, name, "exit code " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1));
      if (!progress) out << "  " << name << ": FAILED (see " << (d.failed / name / "error.txt").string() << ")\n";
    }
    bar.update(done, failed);
  }
  bar.finish();
  out << "ran " << pending.size() << " cases on " << jobs << " processes: " << done << " done, " << failed
      << " failed\n";
  return kExitOk;
}

// ---------------------------------------------------------------------------------------------
// Emitting job lists for other engines

std::string selfExe() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string(kProg) : p.string();
}

/// "0-3,5,7-9" from sorted indices.
std::string arrayRanges(const std::vector<std::size_t>& idx) {
  std::string s;
  for (std::size_t i = 0; i < idx.size();) {
    std::size_t j = i;
    while (j + 1 < idx.size() && idx[j + 1] == idx[j] + 1) ++j;
    s += (s.empty() ? "" : ",") + std::to_string(idx[i]) + (j > i ? "-" + std::to_string(idx[j]) : "");
    i = j + 1;
  }
  return s;
}

/// The sweep's name as a Slurm job name: letters, digits, '_', '.', '-' (sbatch splits #SBATCH lines at spaces).
std::string slurmJobName(const std::string& name) {
  std::string j;
  for (char c : name.substr(0, 40))
    j += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-') ? c : '_';
  return j.empty() ? std::string("sweep") : j;
}

std::string slurmTime(double seconds) {
  const long minutes = static_cast<long>(std::ceil(seconds / 60.0));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%ld:%02ld:00", minutes / 60, minutes % 60);
  return buf;
}

int emitJobs(const std::string& kind, const Written& w, const SweepDirs& d, std::ostream& out, std::ostream& err) {
  const std::string exe = selfExe();
  const std::string dir = fs::absolute(d.root).lexically_normal().string();
  std::vector<std::size_t> pending;
  for (std::size_t i = 0; i < w.cases.size(); ++i)
    if (!isDone(d, w.cases[i].name)) pending.push_back(i);
  if (kind == "gnu-parallel") {
    const fs::path jobs = d.root / "jobs.txt";
    if (!writeFile(jobs, [&](std::ostream& o) {
          for (std::size_t i : pending)
            o << shellQuote(exe) << " sweep --run-case " << shellQuote(w.cases[i].name) << " --out " << shellQuote(dir)
              << "\n";
        }, err))
      return kExitIo;
    out << "wrote " << jobs.string() << ": " << pending.size() << " of " << w.cases.size()
        << " cases still to run, one command a line. Run them with, e.g.\n"
        << "  parallel --jobs 8 --joblog " << shellQuote(dir + "/parallel.log") << " < " << shellQuote(jobs.string()) << "\n"
        << "  parallel --sshloginfile HOSTS < " << shellQuote(jobs.string())
        << "   # other machines, sharing this folder\n"
        << "then: " << kProg << " sweep --collect " << shellQuote(dir) << "\n";
    return kExitOk;
  }
  // Slurm: one array task per pending case; the time limit from the largest case's estimate.
  double work = 0.0;
  for (std::size_t i : pending) {
    try {
      work = std::max(work, caseWork(d.caseFile(w.cases[i].name)));
    } catch (const std::exception& e) {
      err << kProg << ": error: " << e.what() << "\n";
      return kExitBadInput;
    }
  }
  const double estimate = work * kSecondsPerNodeStep;
  const double limit = std::max(kMinSlurmMinutes * 60.0, kSlurmTimeFactor * estimate);
  const fs::path script = d.root / "sweep.slurm";
  if (!writeFile(script, [&](std::ostream& o) {
        o << "#!/bin/bash\n"
          << "# Slurm job array of the sweep '" << w.spec.name << "' (written by cable_sim sweep --emit slurm).\n"
          << "# One task per case still to run; task i runs line i + 1 of cases.txt. Submit with\n"
          << "#   sbatch " << script.string() << "\n"
          << "# and when the tasks are done: cable_sim sweep --collect " << dir << "\n"
          << "# Time limit: " << fmtNum("%.3g", kSlurmTimeFactor) << " x the estimate of the largest case ("
          << fmtNum("%.0f", estimate) << " s: nodes x time steps x " << fmtNum("%.1e", kSecondsPerNodeStep)
          << " s), at least " << fmtNum("%.0f", kMinSlurmMinutes) << " min.\n"
          << "#SBATCH --job-name=" << slurmJobName(w.spec.name) << "\n"
          << "#SBATCH --array=" << (pending.empty() ? std::string("0") : arrayRanges(pending)) << "\n"
          << "#SBATCH --ntasks=1\n"
          << "#SBATCH --cpus-per-task=1\n"
          << "#SBATCH --mem=1G\n"
          << "#SBATCH --time=" << slurmTime(limit) << "\n"
          << "#SBATCH --output=" << dir << "/slurm/%A_%a.out\n"
          << "set -euo pipefail\n"
          << "DIR=" << shellQuote(dir) << "\n"
          << "CASE=$(sed -n \"$((SLURM_ARRAY_TASK_ID + 1))p\" \"$DIR/cases.txt\")\n"
          << "if [ -z \"$CASE\" ]; then echo \"no case at index $SLURM_ARRAY_TASK_ID in $DIR/cases.txt\" >&2; exit 2; fi\n"
          << "exec " << shellQuote(exe) << " sweep --run-case \"$CASE\" --out \"$DIR\"\n";
      }, err))
    return kExitIo;
  std::error_code ec;
  fs::create_directories(d.root / "slurm", ec);  // sbatch does not create the --output folder
  fs::permissions(script, fs::perms::owner_exec | fs::perms::group_exec, fs::perm_options::add, ec);
  out << "wrote " << script.string() << ": a job array of " << pending.size() << " of " << w.cases.size()
      << " cases still to run, --time=" << slurmTime(limit) << ". Submit with\n"
      << "  sbatch " << shellQuote(script.string()) << "\n"
      << "then: " << kProg << " sweep --collect " << shellQuote(dir) << "\n";
  return kExitOk;
}

}  // namespace

int runSweep(const ParsedArgs& args, std::ostream& out, std::ostream& err) {
  if (args.has("collect")) {
    if (!args.positionals.empty() || args.has("emit") || args.has("run-case"))
      throw UsageError("--collect DIR takes no sweep file, --emit or --run-case");
    const std::string dir = args.values.at("collect");
    if (dir.empty()) throw UsageError("option '--collect' needs a directory, got ''");
    return collectSweep(dir, out, err);
  }
  if (!args.has("out")) throw UsageError("missing --out DIR (the sweep's folder)");
  const std::string dir = args.values.at("out");
  if (dir.empty()) throw UsageError("option '--out' needs a directory, got ''");
  if (args.has("run-case")) {
    if (!args.positionals.empty()) throw UsageError("--run-case NAME --out DIR takes no sweep file");
    return runOneCase(dir, args.values.at("run-case"), out, err);
  }
  if (args.positionals.size() != 1)
    throw UsageError(args.positionals.empty() ? "missing SWEEP.yaml"
                                              : "expected one sweep file, got " + std::to_string(args.positionals.size()) +
                                                    " arguments");
  std::string emit;
  if (args.has("emit")) {
    emit = args.values.at("emit");
    if (emit != "gnu-parallel" && emit != "slurm")
      throw UsageError("option '--emit' needs gnu-parallel or slurm, got '" + emit + "'");
  }
  std::size_t jobs = std::max(1u, std::thread::hardware_concurrency());
  if (args.has("jobs")) jobs = parsePositiveInt("jobs", args.values.at("jobs"));
  const SweepDirs d(dir);
  Written w;
  const int rc = writeCases(args.positionals.front(), d, w, out, err);
  if (rc != kExitOk) return rc;
  if (!emit.empty()) return emitJobs(emit, w, d, out, err);
  std::vector<std::string> pending;
  for (const auto& c : w.cases)
    if (!isDone(d, c.name)) pending.push_back(c.name);
  if (pending.size() < w.cases.size())
    out << "  " << w.cases.size() - pending.size() << " already done (skipped)\n";
  const bool progress = !args.has("no-progress") && ::isatty(STDERR_FILENO) == 1;
  const int prc = runPool(pending, d, jobs, progress, out, err);
  if (prc != kExitOk) return prc;
  return collectSweep(dir, out, err);
}

}  // namespace detail
}  // namespace cli
}  // namespace mooring_dynamics
