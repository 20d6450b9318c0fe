// Runs a fuzz target (the LLVMFuzzerTestOneInput it is linked with; see
// CMakeLists.txt beside this file) once over every file given on the command
// line, descending into directories. This is how CI replays the seed corpora
// (and any crash reproducer added to them) without libFuzzer: the CTests
// FuzzCorpusRegression, FuzzDecisionsCorpusRegression and
// FuzzVariantCorpusRegression, under ASan/UBSan in the asan preset.
//
//   spire_fuzz_replay tests/fuzz/corpus [more files or dirs...]
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace fs = std::filesystem;

namespace {

bool collect(const fs::path& path, std::vector<fs::path>& out) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(path, ec)) {
      if (entry.is_regular_file(ec)) out.push_back(entry.path());
    }
    return !ec;
  }
  if (fs::is_regular_file(path, ec)) {
    out.push_back(path);
    return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s <corpus dir or file>...\n", argv[0]);
    return 2;
  }
  const std::string name = fs::path(argv[0]).filename().string();
  std::vector<fs::path> inputs;
  for (int i = 1; i < argc; ++i) {
    if (!collect(argv[i], inputs)) {
      std::fprintf(stderr, "%s: cannot read %s\n", name.c_str(), argv[i]);
      return 2;
    }
  }
  std::sort(inputs.begin(), inputs.end());
  if (inputs.empty()) {
    std::fprintf(stderr, "%s: no inputs found\n", name.c_str());
    return 2;
  }

  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  double slowestMs = 0;
  std::string slowest;
  for (const fs::path& path : inputs) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "%s: cannot open %s\n", name.c_str(), path.c_str());
      return 2;
    }
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // Named first so that a sanitizer report below it points at the input.
    std::fprintf(stderr, "replay %s (%zu bytes)\n", path.c_str(), bytes.size());
    const auto t0 = Clock::now();
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    if (ms > slowestMs) {
      slowestMs = ms;
      slowest = path.filename().string();
    }
  }
  const double totalMs = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  std::printf("%s: %zu inputs, 0 crashes, %.1f ms (slowest %s: %.1f ms)\n", name.c_str(), inputs.size(), totalMs,
              slowest.c_str(), slowestMs);
  return 0;
}
