#include "driver/compile_client.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string_view>

#include "driver/exit_codes.h"
#include "driver/server_protocol.h"

extern char** environ;

namespace spire::server {
namespace {

// How long a client waits for a worker to take its run before compiling it
// itself: a server forks one in about a millisecond, so only a stuck or
// stopped server takes this long.
constexpr std::chrono::milliseconds kAcceptTimeout{10000};

// A socket connected to the server at `path`; -1 with errno when none
// listens there.
int connectTo(const std::filesystem::path& path) {
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return -1;
  const sockaddr_un address = socketAddress(path);
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    const int error = errno;
    ::close(fd);
    errno = error;
    return -1;
  }
  return fd;
}

// Starts `executable --serve-compiles path` in a session of its own, with
// /dev/null for its standard streams, and does not wait for it: a second
// server for the same socket gives way to the first (its lock).
void startServer(const std::filesystem::path& executable, const std::filesystem::path& path) {
  posix_spawnattr_t attributes;
  posix_spawn_file_actions_t actions;
  posix_spawnattr_init(&attributes);
  posix_spawn_file_actions_init(&actions);
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  for (int number : {SIGINT, SIGTERM, SIGHUP, SIGPIPE, SIGCHLD}) sigaddset(&defaults, number);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSID | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  for (int fd = 0; fd < 3; ++fd) posix_spawn_file_actions_addopen(&actions, fd, "/dev/null", O_RDWR, 0);
  std::string program = executable.string(), flag = kServeCompilesFlag, socket = path.string();
  char* argv[] = {program.data(), flag.data(), socket.data(), nullptr};
  pid_t pid = 0;
  (void)posix_spawn(&pid, program.c_str(), &actions, &attributes, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
}

// This process's state that a run depends on; nullopt when the working
// directory cannot be named.
std::optional<Request> requestFor(const std::vector<std::string>& args) {
  Request request;
  request.args = args;
  std::error_code error;
  request.workingDirectory = std::filesystem::current_path(error).string();
  if (error) return std::nullopt;
  for (char** variable = environ; variable != nullptr && *variable != nullptr; ++variable) {
    request.environment.emplace_back(*variable);
  }
  request.umask = ::umask(0);
  ::umask(request.umask);
  return request;
}

// Sends the run and waits for its outcome once a worker took it.
std::optional<int> runOn(int fd, const std::vector<std::string>& args) {
  const auto request = requestFor(args);
  if (!request || !sendRequest(fd, *request, {STDIN_FILENO, STDOUT_FILENO, STDERR_FILENO})) return std::nullopt;
  if (!receiveAccepted(fd, kAcceptTimeout)) return std::nullopt;
  if (const auto status = receiveStatus(fd)) return status;
  // The worker may have printed part of its output already: running again
  // here could print it twice.
  std::cerr << "spirec: error: the compile server stopped during the run; run again, or with SPIRE_SERVER=off\n";
  return kExitInputError;
}

// Whether the run must stay in this process: when the user says so
// (SPIRE_SERVER=off, 0, no or false); when it is traced (a debugger,
// strace), since the tracer would see nothing of a run on the server; when
// libraries are preloaded (valgrind, heaptrack, another allocator), since a
// worker forked from the server would run without them.
bool mustRunHere() {
  if (const char* setting = std::getenv("SPIRE_SERVER")) {
    const std::string_view value(setting);
    if (value == "off" || value == "0" || value == "no" || value == "false") return true;
  }
  if (const char* preload = std::getenv("LD_PRELOAD"); preload != nullptr && *preload != '\0') return true;
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.starts_with("TracerPid:")) return std::strtol(line.c_str() + 10, nullptr, 10) != 0;
  }
  return false;
}

}  // namespace

std::optional<int> runOnCompileServer(const std::filesystem::path& executable, const std::vector<std::string>& args) {
  if (mustRunHere()) return std::nullopt;
  const auto path = serverSocketPath(executable);
  if (!path) return std::nullopt;
  const int fd = connectTo(*path);
  if (fd < 0) {
    if (errno == ENOENT || errno == ECONNREFUSED) startServer(executable, *path);
    return std::nullopt;
  }
  const auto status = runOn(fd, args);
  ::close(fd);
  return status;
}

}  // namespace spire::server
