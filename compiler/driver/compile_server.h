// The compile server: a spirec process that stays after its first run so
// that later runs skip glslang's start-up. glslang (Debian's glslang 12)
// parses its built-in declarations into symbol tables for every stage on the
// first compile in each process, about 28 ms of a default spirec run that
// otherwise takes under 10 ms (docs/integration.md). The server builds them
// once and forks a worker per run; a worker starts with the tables in memory
// and takes on the client's arguments, working directory, environment,
// umask and standard streams, so a run behaves as it would in the client's
// own process, and nothing a run does outlives it.
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace spire::server {

struct ServerHooks {
  // Builds, before the server listens, what every run would otherwise build
  // for itself.
  std::function<void()> warmUp;
  // One run, in a worker that has taken on the client's process state;
  // returns its exit status.
  std::function<int(const std::vector<std::string>& args)> run;
};

// How long a server with no run in progress waits for the next one.
inline constexpr std::chrono::seconds kIdleLimit{300};

// Serves runs on `socketPath` until it has been idle for `idleLimit`, its
// socket is removed or replaced, or it gets SIGTERM, SIGINT or SIGHUP (which
// stop its runs too). Returns at once when another server holds the socket's
// lock (SOCKET.lock, which holds the server's process id). The exit status
// of the server process.
int serveCompiles(const std::filesystem::path& socketPath, const ServerHooks& hooks,
                  std::chrono::seconds idleLimit = kIdleLimit);

}  // namespace spire::server
