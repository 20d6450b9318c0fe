// SIGINT and SIGTERM as a request to stop between variants: a tuning run
// finishes the variant it is measuring, keeps its journal whole and exits
// with kExitInterrupted, so that rerunning the command resumes it. The
// coordinator passes the request on to its workers.
#pragma once

namespace spire::tune {

// Installs the handlers for this scope (the earlier ones come back after).
class StopRequest {
 public:
  StopRequest();
  ~StopRequest();
  StopRequest(const StopRequest&) = delete;
  StopRequest& operator=(const StopRequest&) = delete;

  // Whether a signal arrived since the handlers were installed.
  static bool requested();
  // For tests: as if a signal had arrived (or, with false, none).
  static void set(bool requested);
};

}  // namespace spire::tune
