#include "tune/worker_processes.h"

#include <signal.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <string_view>
#include <thread>

#include <fmt/format.h>

#include "tune/progress.h"
#include "tune/stop_request.h"

extern char** environ;

namespace spire::tune {
namespace {

size_t countRows(const std::filesystem::path& path) {
  std::ifstream in(path);
  size_t lines = 0;
  for (std::string line; std::getline(in, line);) lines += line.empty() ? 0 : 1;
  return lines == 0 ? 0 : lines - 1;
}

constexpr std::string_view kCoordinatorVariable = "SPIRE_TUNE_COORDINATOR";

// This process's environment with LP_NUM_THREADS=1 and the coordinator's
// process id.
std::vector<std::string> workerEnvironment() {
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) {
    const std::string_view entry(*e);
    if (!entry.starts_with("LP_NUM_THREADS=") && !entry.starts_with(kCoordinatorVariable)) env.emplace_back(entry);
  }
  env.emplace_back("LP_NUM_THREADS=1");
  env.push_back(std::string(kCoordinatorVariable) + "=" + std::to_string(::getpid()));
  return env;
}

// Rows in each shard when the workers start: an interrupted run's, already
// counted.
std::vector<size_t> shardRows(const WorkerPlan& plan) {
  std::vector<size_t> rows;
  for (const std::filesystem::path& shard : plan.shards) rows.push_back(countRows(shard));
  return rows;
}

// nullopt when a worker could not start (after stopping those that did).
std::optional<std::vector<pid_t>> spawnWorkers(const WorkerPlan& plan) {
  std::vector<std::string> env = workerEnvironment();
  std::vector<char*> envp;
  for (std::string& e : env) envp.push_back(e.data());
  envp.push_back(nullptr);
  std::vector<pid_t> pids;
  for (size_t k = 0; k < plan.shards.size(); ++k) {
    std::vector<std::string> workerArgs{"spire-tune"};
    workerArgs.insert(workerArgs.end(), plan.args.begin(), plan.args.end());
    workerArgs.insert(workerArgs.end(), {"--worker", std::to_string(k)});
    std::vector<char*> argv;
    for (std::string& a : workerArgs) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    if (posix_spawn(&pid, plan.program.c_str(), nullptr, nullptr, argv.data(), envp.data()) != 0) {
      // No run with some of its workers: those started stop again.
      for (const pid_t started : pids) ::kill(started, SIGTERM);
      for (const pid_t started : pids) ::waitpid(started, nullptr, 0);
      return std::nullopt;
    }
    pids.push_back(pid);
  }
  return pids;
}

// How a worker that did not exit with 0 ended: a crash prints nothing of its
// own, so the signal is the only trace of it.
std::string describeEnd(int status) {
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    return fmt::format("was killed by signal {} ({})", signal, ::strsignal(signal));
  }
  if (WIFEXITED(status)) return fmt::format("exited with status {}", WEXITSTATUS(status));
  return fmt::format("ended with wait status {}", status);
}

// Waits for every worker, updating the progress from their shards; a stop
// request is passed on to them once.
WorkersEnd waitForWorkers(std::vector<pid_t> pids, const WorkerPlan& plan, size_t already, size_t total,
                          std::ostream& err) {
  Progress progress(err, total, already);
  const std::vector<size_t> before = shardRows(plan);
  std::vector<std::string> failures;
  bool crashesOnly = true;
  bool stopping = false;
  size_t running = pids.size();
  while (running > 0) {
    size_t done = already;
    for (size_t k = 0; k < plan.shards.size(); ++k) {
      const size_t rows = countRows(plan.shards[k]);
      done += rows - std::min(before[k], rows);
    }
    progress.update(std::min(done, total));
    if (StopRequest::requested() && !stopping) {
      stopping = true;
      for (const pid_t pid : pids) {
        if (pid != 0) ::kill(pid, SIGTERM);
      }
    }
    for (size_t k = 0; k < pids.size(); ++k) {
      pid_t& pid = pids[k];
      if (pid == 0) continue;
      int status = 0;
      if (waitpid(pid, &status, WNOHANG) == pid) {
        if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
          crashesOnly = crashesOnly && WIFSIGNALED(status);
          failures.push_back(fmt::format("spire-tune: worker {} {}\n", k, describeEnd(status)));
        }
        pid = 0;
        --running;
      }
    }
    if (running > 0) std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  if (stopping) return WorkersEnd::Interrupted;
  if (!failures.empty()) {
    progress.finish();
    for (const std::string& failure : failures) err << failure;
    return crashesOnly ? WorkersEnd::Crashed : WorkersEnd::Failed;
  }
  progress.update(total);
  return WorkersEnd::Finished;
}

}  // namespace

WorkersEnd runWorkers(const WorkerPlan& plan, size_t already, size_t total, std::ostream& err) {
  auto pids = spawnWorkers(plan);
  if (!pids) {
    err << "spire-tune: error: cannot start a worker process\n";
    return WorkersEnd::Failed;
  }
  return waitForWorkers(std::move(*pids), plan, already, total, err);
}

void followCoordinator() {
  ::prctl(PR_SET_PDEATHSIG, SIGTERM);
  // The coordinator may have gone before the line above ran.
  const char* coordinator = std::getenv(std::string(kCoordinatorVariable).c_str());
  if (coordinator && std::to_string(::getppid()) != coordinator) ::raise(SIGTERM);
}

}  // namespace spire::tune
