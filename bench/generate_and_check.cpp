// bench/generate-and-check: the generator's property (tests/gen) at scale.
// Runs seeds from --first-seed upward on --threads threads until the seeds
// taken in order hold at least --variants variants, so the result depends
// only on the arguments, never on thread timing. Prints the refusals by
// diagnostic code, every failure class with its count and the seed of an
// example, the order-dependent routes and unshared locked kernels
// (campaign.h), and last the line
//   N variants, I internal errors, K invalid kernels, M interface mismatches
// --failures DIR writes each class's example (program, decisions, details).
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

#include "gen/campaign.h"

namespace {

using spire::testgen::CampaignStats;

struct Options {
  uint64_t variants = 100000;
  uint32_t firstSeed = 1000000;  // away from the ctest test's seeds
  int decisionMaps = 6;
  int threads = 2;
  std::string failuresDir;
};

// Seeds finished out of order, merged in seed order up to the first seed at
// which the target is reached.
class SeedLedger {
 public:
  SeedLedger(uint32_t first, uint64_t target) : next_(first), prefixEnd_(first), target_(target) {}

  bool claim(uint32_t& seed) {
    std::lock_guard lock(mutex_);
    if (reached_) return false;
    seed = next_++;
    return true;
  }

  void finish(uint32_t seed, CampaignStats stats) {
    std::lock_guard lock(mutex_);
    done_.emplace(seed, std::move(stats));
    for (auto it = done_.find(prefixEnd_); !reached_ && it != done_.end(); it = done_.find(++prefixEnd_)) {
      total_.merge(it->second);
      reached_ = total_.variants >= target_;
      if (total_.variants / 10000 != (total_.variants - it->second.variants) / 10000) {
        std::cerr << fmt::format("... {}\n", total_.summaryLine());
      }
    }
  }

  const CampaignStats& total() const { return total_; }

 private:
  std::mutex mutex_;
  std::map<uint32_t, CampaignStats> done_;
  uint32_t next_, prefixEnd_;
  uint64_t target_;
  bool reached_ = false;
  CampaignStats total_;
};

void writeFailures(const CampaignStats& stats, const std::string& dir) {
  std::filesystem::create_directories(dir);
  for (size_t i = 0; i < stats.failures.size(); ++i) {
    std::ofstream(fmt::format("{}/failure-{:02}-seed-{}.txt", dir, i, stats.failures[i].seed))
        << stats.failures[i].format();
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Generates random Spire programs and variants and checks the compiler's property on each"};
  Options o;
  app.add_option("--variants", o.variants, "Stop once the seeds run hold this many variants");
  app.add_option("--first-seed", o.firstSeed, "The first seed");
  app.add_option("--maps", o.decisionMaps, "Random decision maps per program (besides the default variant)");
  app.add_option("--threads", o.threads, "Worker threads");
  app.add_option("--failures", o.failuresDir, "Write an example of each failure class here");
  CLI11_PARSE(app, argc, argv);

  SeedLedger ledger(o.firstSeed, o.variants);
  std::vector<std::thread> workers;
  for (int t = 0; t < std::max(o.threads, 1); ++t) {
    workers.emplace_back([&] {
      for (uint32_t seed = 0; ledger.claim(seed);) ledger.finish(seed, spire::testgen::runSeed(seed, o.decisionMaps));
    });
  }
  for (std::thread& w : workers) w.join();

  const CampaignStats& stats = ledger.total();
  if (!o.failuresDir.empty()) writeFailures(stats, o.failuresDir);
  std::cout << fmt::format("{} programs (seeds {}..{}), {} variants accepted\n", stats.programs, o.firstSeed,
                           o.firstSeed + stats.programs - 1, stats.count(spire::testgen::Verdict::Accepted));
  std::cout << stats.refusalTable();
  for (const auto& [c, n] : stats.failureClasses) std::cout << fmt::format("failure class ({}x): {}\n", n, c);
  for (const auto& f : stats.failures) {
    std::cout << fmt::format("example: seed {} -> {}\n", f.seed, spire::testgen::failureClass(f.report));
  }
  std::cout << stats.routesAndLocksLine() << "\n" << stats.summaryLine() << std::endl;
  return 0;
}
