#include "driver/spirec_batch.h"

#include <fmt/format.h>

#include <algorithm>
#include <ostream>
#include <sstream>

#include "driver/batch_file.h"
#include "driver/spirv_cache.h"
#include "support/diagnostic_renderer.h"
#include "support/file_io.h"

namespace spire {
namespace {

constexpr std::string_view kBatch = "--batch";

bool namesBatch(const std::string& arg) { return arg == kBatch || arg.starts_with("--batch="); }

}  // namespace

std::optional<std::string> batchFileArgument(const std::vector<std::string>& args) {
  if (args.size() == 2 && args[0] == kBatch) return args[1];
  if (args.size() == 1 && args[0].starts_with("--batch=")) return args[0].substr(kBatch.size() + 1);
  return std::nullopt;
}

bool batchMisuse(const std::vector<std::string>& args) {
  return !batchFileArgument(args) && std::ranges::any_of(args, namesBatch);
}

int runSpirecBatch(const std::string& path, SpirecJobRunner runJob, std::ostream& out, std::ostream& err,
                   const SpirecEnvironment& environment) {
  auto text = readFileBytes(path);
  if (!text) {
    err << fmt::format("spirec: error: cannot read batch file '{}': {}\n", path, text.error().message());
    return kExitInputError;
  }
  SourceManager sources;
  DiagnosticList diags;
  const FileId file = sources.addFile(path, std::move(text).value());
  const std::vector<BatchJob> jobs = parseBatchFile(sources, file, diags);
  if (diags.hasErrors()) {
    err << renderDiagnostics(sources, diags, DiagnosticFormat::Text);
    return kExitInputError;
  }
  // Variants of one shader in different jobs often share kernels.
  SpirvCache cache;
  SpirecEnvironment jobEnvironment = environment;
  jobEnvironment.spirvCache = &cache;
  int worst = kExitSuccess;
  for (size_t i = 0; i < jobs.size(); ++i) {
    const BatchJob& job = jobs[i];
    std::ostringstream jobErr;
    int status = kExitUsageError;
    if (std::ranges::any_of(job.args, namesBatch)) {
      jobErr << "spirec: error: --batch cannot be used inside a batch file\n";
    } else {
      status = runJob(job.args, out, jobErr, jobEnvironment);
    }
    const std::string diagnostics = std::move(jobErr).str();
    if (status != kExitSuccess || !diagnostics.empty()) {
      // Flushing `out` first keeps a job's stdout before the next job's
      // diagnostics when both streams go to one terminal.
      out.flush();
      const std::string failed = status == kExitSuccess ? "" : fmt::format(" failed (exit status {})", status);
      err << fmt::format("spirec: job {} ({}:{}){}:\n{}", i + 1, path, job.line, failed, diagnostics);
    }
    worst = std::max(worst, status);
  }
  return worst;
}

}  // namespace spire
