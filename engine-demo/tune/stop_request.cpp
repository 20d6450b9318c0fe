#include "tune/stop_request.h"

#include <csignal>

namespace spire::tune {
namespace {

volatile std::sig_atomic_t gRequested = 0;
struct sigaction gPreviousInt {};
struct sigaction gPreviousTerm {};

extern "C" void onStopSignal(int /*signal*/) { gRequested = 1; }

}  // namespace

StopRequest::StopRequest() {
  gRequested = 0;
  struct sigaction action {};
  action.sa_handler = onStopSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &gPreviousInt);
  sigaction(SIGTERM, &action, &gPreviousTerm);
}

StopRequest::~StopRequest() {
  sigaction(SIGINT, &gPreviousInt, nullptr);
  sigaction(SIGTERM, &gPreviousTerm, nullptr);
}

bool StopRequest::requested() { return gRequested != 0; }

void StopRequest::set(bool requested) { gRequested = requested ? 1 : 0; }

}  // namespace spire::tune
