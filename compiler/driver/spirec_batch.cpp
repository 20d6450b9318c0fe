#include "driver/spirec_batch.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <ostream>
#include <sstream>
#include <thread>

#include "driver/batch_file.h"
#include "driver/ordered_jobs.h"
#include "driver/spirv_cache.h"
#include "support/diagnostic_renderer.h"
#include "support/file_io.h"

namespace spire {
namespace {

constexpr std::string_view kBatch = "--batch";

bool namesBatch(const std::string& arg) { return arg == kBatch || arg.starts_with("--batch="); }

// N of `-j N`: a whole number of at least 1, nothing else.
std::optional<unsigned> jobCount(std::string_view text) {
  unsigned value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value == 0) return std::nullopt;
  return value;
}

// Takes one option of batch mode from args[i] (and args[i + 1] when its value
// is separate) into `file` or `jobs`; false when args[i] is not one, repeats
// one or has a bad value.
bool takeBatchOption(const std::vector<std::string>& args, size_t& i, std::optional<std::string>& file,
                     std::optional<unsigned>& jobs) {
  const std::string& arg = args[i];
  const bool hasNext = i + 1 < args.size();
  if (arg == kBatch && hasNext && !file) {
    file = args[++i];
  } else if (arg.starts_with("--batch=") && !file) {
    file = arg.substr(kBatch.size() + 1);
  } else if ((arg == "-j" || arg == "--jobs") && hasNext && !jobs) {
    jobs = jobCount(args[++i]);
    return jobs.has_value();
  } else if (arg.starts_with("--jobs=") && !jobs) {
    jobs = jobCount(std::string_view(arg).substr(7));
    return jobs.has_value();
  } else if (arg.starts_with("-j") && arg.size() > 2 && !jobs) {
    jobs = jobCount(std::string_view(arg).substr(2));
    return jobs.has_value();
  } else {
    return false;
  }
  return true;
}

// Runs one job and returns how it finishes: its status, output and
// diagnostics under the job's header line.
JobFinish prepareJob(const BatchJob& job, size_t index, const std::string& path, SpirecJobPreparer prepare,
                     const SpirecEnvironment& environment, std::ostream& out, std::ostream& err, int& worst) {
  SpirecFinish finish;
  if (std::ranges::any_of(job.args, namesBatch)) {
    finish = [](std::ostream&, std::ostream& jobErr) {
      jobErr << "spirec: error: --batch cannot be used inside a batch file\n";
      return int{kExitUsageError};
    };
  } else {
    finish = prepare(job.args, environment);
  }
  return [=, &out, &err, &worst, finish = std::move(finish)] {
    std::ostringstream jobErr;
    const int status = finish(out, jobErr);
    const std::string diagnostics = std::move(jobErr).str();
    if (status != kExitSuccess || !diagnostics.empty()) {
      // Flushing `out` first keeps a job's stdout before the next job's
      // diagnostics when both streams go to one terminal.
      out.flush();
      const std::string failed = status == kExitSuccess ? "" : fmt::format(" failed (exit status {})", status);
      err << fmt::format("spirec: job {} ({}:{}){}:\n{}", index + 1, path, job.line, failed, diagnostics);
    }
    worst = std::max(worst, status);
  };
}

}  // namespace

std::optional<BatchRequest> batchRequest(const std::vector<std::string>& args) {
  std::optional<std::string> file;
  std::optional<unsigned> jobs;
  for (size_t i = 0; i < args.size(); ++i) {
    if (!takeBatchOption(args, i, file, jobs)) return std::nullopt;
  }
  if (!file) return std::nullopt;
  return BatchRequest{*file, jobs.value_or(0)};
}

bool batchMisuse(const std::vector<std::string>& args) {
  return !batchRequest(args) && std::ranges::any_of(args, namesBatch);
}

int runSpirecBatch(const BatchRequest& request, SpirecJobPreparer prepare, std::ostream& out, std::ostream& err,
                   const SpirecEnvironment& environment) {
  auto text = readFileBytes(request.file);
  if (!text) {
    err << fmt::format("spirec: error: cannot read batch file '{}': {}\n", request.file, text.error().message());
    return kExitInputError;
  }
  SourceManager sources;
  DiagnosticList diags;
  const FileId file = sources.addFile(request.file, std::move(text).value());
  const std::vector<BatchJob> jobs = parseBatchFile(sources, file, diags);
  if (diags.hasErrors()) {
    err << renderDiagnostics(sources, diags, DiagnosticFormat::Text);
    return kExitInputError;
  }
  // Variants of one shader in different jobs often share kernels.
  SpirvCache cache;
  SpirecEnvironment jobEnvironment = environment;
  jobEnvironment.spirvCache = &cache;
  const unsigned threads = request.jobs != 0 ? request.jobs : std::max(1U, std::thread::hardware_concurrency());
  int worst = kExitSuccess;
  runOrderedJobs(jobs.size(), threads, [&](size_t i) {
    return prepareJob(jobs[i], i, request.file, prepare, jobEnvironment, out, err, worst);
  });
  return worst;
}

}  // namespace spire
