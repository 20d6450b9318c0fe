#include "tune/worker_processes.h"

#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <optional>
#include <string_view>
#include <thread>

#include "tune/progress.h"

extern char** environ;

namespace spire::tune {
namespace {

size_t countRows(const std::filesystem::path& path) {
  std::ifstream in(path);
  size_t lines = 0;
  for (std::string line; std::getline(in, line);) lines += line.empty() ? 0 : 1;
  return lines == 0 ? 0 : lines - 1;
}

// This process's environment with LP_NUM_THREADS=1.
std::vector<std::string> workerEnvironment() {
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) {
    if (!std::string_view(*e).starts_with("LP_NUM_THREADS=")) env.emplace_back(*e);
  }
  env.emplace_back("LP_NUM_THREADS=1");
  return env;
}

// nullopt when a worker could not start (those started keep running).
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
    if (posix_spawn(&pid, plan.program.c_str(), nullptr, nullptr, argv.data(), envp.data()) != 0) return std::nullopt;
    pids.push_back(pid);
  }
  return pids;
}

// Waits for every worker, updating the progress from their shards.
bool waitForWorkers(std::vector<pid_t> pids, const WorkerPlan& plan, size_t already, size_t total, std::ostream& err) {
  Progress progress(err, total, already);
  bool ok = true;
  size_t running = pids.size();
  while (running > 0) {
    size_t done = already;
    for (const std::filesystem::path& shard : plan.shards) done += countRows(shard);
    progress.update(std::min(done, total));
    for (pid_t& pid : pids) {
      if (pid == 0) continue;
      int status = 0;
      if (waitpid(pid, &status, WNOHANG) == pid) {
        ok = ok && WIFEXITED(status) && WEXITSTATUS(status) == 0;
        pid = 0;
        --running;
      }
    }
    if (running > 0) std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  progress.update(total);
  return ok;
}

}  // namespace

bool runWorkers(const WorkerPlan& plan, size_t already, size_t total, std::ostream& err) {
  auto pids = spawnWorkers(plan);
  if (!pids) {
    err << "spire-tune: error: cannot start a worker process\n";
    return false;
  }
  return waitForWorkers(std::move(*pids), plan, already, total, err);
}

}  // namespace spire::tune
