#include "driver/spirec_batch.h"

#include <fmt/format.h>

#include <algorithm>
#include <ostream>
#include <sstream>
#include <thread>

#include "driver/batch_file.h"
#include "driver/ordered_jobs.h"
#include "driver/spirv_cache.h"
#include "driver/tool_arguments.h"
#include "support/diagnostic_renderer.h"
#include "support/file_io.h"

namespace spire {
namespace {

constexpr std::string_view kBatch = "--batch";

bool namesBatch(const std::string& arg) { return arg == kBatch || arg.starts_with("--batch="); }

// What `spirec --batch` is asked to do.
struct BatchRequest {
  std::string file;
  unsigned jobs = 0;  // runs compiled at once; 0: one per hardware thread
};

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

// Runs the batch file's jobs as BatchRequest says; runSpirecBatch's work
// once its arguments are parsed.
int runBatchFile(const BatchRequest& request, SpirecJobPreparer prepare, std::ostream& out, std::ostream& err,
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

}  // namespace

bool namesBatchMode(const std::vector<std::string>& args) { return std::ranges::any_of(args, namesBatch); }

int runSpirecBatch(const std::vector<std::string>& args, SpirecJobPreparer prepare, std::ostream& out,
                   std::ostream& err, const SpirecEnvironment& environment) {
  CLI::App app{"spirec --batch: many spirec runs in one process (docs/integration.md)", "spirec"};
  BatchRequest request;
  app.add_option("--batch", request.file, "Run each line of FILE as a separate spirec run")
      ->required()
      ->type_name("FILE");
  app.add_option("-j,--jobs", request.jobs, "Runs compiled at once (default: one per hardware thread)")
      ->check(CLI::Range(1U, 4096U))
      ->type_name("N");
  // spirecWantsCompileServer finds the flag in the arguments before a batch
  // runs; here the batch runs in this process already.
  bool noServer = false;
  app.add_flag("--no-server", noServer, "Run the batch in this process, not on the compile server");
  if (const auto status = parseToolArguments(app, args, out, err)) return *status;
  return runBatchFile(request, prepare, out, err, environment);
}

}  // namespace spire
