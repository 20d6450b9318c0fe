#include "driver/compile_server.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/signalfd.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <map>

#include "driver/exit_codes.h"
#include "driver/server_protocol.h"

namespace spire::server {
namespace {

using Clock = std::chrono::steady_clock;

// A run in progress: its worker and the connection to its client.
struct Worker {
  int connection = -1;
  bool stopped = false;  // sent SIGTERM because its client left or the server stops
};

// The signals the server handles as events rather than by their default
// action.
sigset_t serverSignals() {
  sigset_t set;
  sigemptyset(&set);
  for (int number : {SIGCHLD, SIGTERM, SIGINT, SIGHUP}) sigaddset(&set, number);
  return set;
}

// Takes on the client's process state and runs the request; never returns.
[[noreturn]] void runWorker(ReceivedRequest& received, const ServerHooks& hooks) {
  const sigset_t handled = serverSignals();
  sigprocmask(SIG_UNBLOCK, &handled, nullptr);
  std::signal(SIGPIPE, SIG_DFL);
  for (int fd = 0; fd < 3; ++fd) ::dup2(received.fds[fd], fd);
  ::close_range(3, ~0U, 0);
  Request& request = received.request;
  if (::chdir(request.workingDirectory.c_str()) != 0) {
    std::fprintf(stderr, "spirec: error: cannot enter '%s': %s\n", request.workingDirectory.c_str(),
                 std::strerror(errno));
    std::_Exit(kExitInputError);
  }
  ::clearenv();
  // putenv keeps the strings themselves; they live as long as the process.
  for (std::string& variable : request.environment) ::putenv(variable.data());
  ::umask(request.umask);
  const int status = hooks.run(request.args);
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  std::_Exit(status);
}

// The listening socket, bound after any stale file at its path is removed;
// -1 on failure. The caller holds the lock, so no live server owns the path.
int listenOn(const std::filesystem::path& socketPath) {
  ::unlink(socketPath.c_str());
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return -1;
  const sockaddr_un address = socketAddress(socketPath);
  const mode_t previous = ::umask(0177);
  const bool bound = ::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0;
  ::umask(previous);
  if (!bound || ::listen(fd, SOMAXCONN) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

// The inode of the file at `path`, 0 when there is none.
ino_t inodeOf(const std::filesystem::path& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0 ? info.st_ino : 0;
}

class Server {
 public:
  Server(std::filesystem::path socketPath, const ServerHooks& hooks, std::chrono::seconds idleLimit)
      : socketPath_(std::move(socketPath)), hooks_(hooks), idleLimit_(idleLimit) {}
  ~Server();

  int serve();

 private:
  bool start();
  void accept();
  void reap();
  void stopWorker(pid_t pid);
  void onSignals(bool& stopping);
  std::vector<pollfd> pollSet() const;
  bool shouldStop(Clock::time_point now) const;

  std::filesystem::path socketPath_;
  const ServerHooks& hooks_;
  std::chrono::seconds idleLimit_;
  int lock_ = -1;
  int listener_ = -1;
  int signals_ = -1;
  ino_t socketInode_ = 0;
  std::map<pid_t, Worker> workers_;
  Clock::time_point lastActivity_ = Clock::now();
};

Server::~Server() {
  if (listener_ >= 0) {
    if (inodeOf(socketPath_) == socketInode_) ::unlink(socketPath_.c_str());
    ::close(listener_);
  }
  if (signals_ >= 0) ::close(signals_);
  if (lock_ >= 0) ::close(lock_);
}

// Takes the lock, listens and builds the tables; false when another server
// holds the lock or the socket cannot be made.
bool Server::start() {
  const std::string lockPath = socketPath_.string() + ".lock";
  lock_ = ::open(lockPath.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
  if (lock_ < 0 || ::flock(lock_, LOCK_EX | LOCK_NB) != 0) return false;
  // The lock file names the server, for `kill $(cat SOCKET.lock)`.
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(lock_, 0) != 0 || ::write(lock_, pid.data(), pid.size()) != static_cast<ssize_t>(pid.size())) {
    return false;
  }
  const sigset_t handled = serverSignals();
  sigprocmask(SIG_BLOCK, &handled, nullptr);
  signals_ = ::signalfd(-1, &handled, SFD_CLOEXEC | SFD_NONBLOCK);
  std::signal(SIGPIPE, SIG_IGN);
  listener_ = listenOn(socketPath_);
  socketInode_ = inodeOf(socketPath_);
  if (signals_ < 0 || listener_ < 0) return false;
  // After listening: where no socket can be made (a file system without
  // them), the server gives up before spending the tables' CPU. A client
  // that connects meanwhile waits for them, about as long as it would take
  // to build them itself.
  if (hooks_.warmUp) hooks_.warmUp();
  return true;
}

void Server::accept() {
  const int connection = ::accept4(listener_, nullptr, nullptr, SOCK_CLOEXEC);
  if (connection < 0) return;
  lastActivity_ = Clock::now();
  // A client that connects and then sends nothing must not stall the others.
  const timeval limit{5, 0};
  ::setsockopt(connection, SOL_SOCKET, SO_RCVTIMEO, &limit, sizeof limit);
  auto received = receiveRequest(connection);
  if (!received) {
    ::close(connection);
    return;
  }
  const pid_t pid = ::fork();
  if (pid == 0) runWorker(received.value(), hooks_);
  for (int fd : received->fds) ::close(fd);
  if (pid < 0 || !sendAccepted(connection)) {
    if (pid > 0) ::kill(pid, SIGKILL);
    if (pid > 0) ::waitpid(pid, nullptr, 0);
    ::close(connection);
    return;
  }
  workers_[pid] = Worker{connection};
}

// Sends each finished worker's status to its client.
void Server::reap() {
  int status = 0;
  pid_t pid = 0;
  while ((pid = ::waitpid(-1, &status, WNOHANG)) > 0) {
    const auto worker = workers_.find(pid);
    if (worker == workers_.end()) continue;
    const int exitStatus = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    (void)sendStatus(worker->second.connection, exitStatus);
    ::close(worker->second.connection);
    workers_.erase(worker);
    lastActivity_ = Clock::now();
  }
}

void Server::stopWorker(pid_t pid) {
  Worker& worker = workers_.at(pid);
  if (worker.stopped) return;
  worker.stopped = true;
  ::kill(pid, SIGTERM);
}

void Server::onSignals(bool& stopping) {
  signalfd_siginfo info{};
  while (::read(signals_, &info, sizeof info) == static_cast<ssize_t>(sizeof info)) {
    if (info.ssi_signo == SIGCHLD) continue;
    stopping = true;
  }
  reap();
}

// The listener (unless stopping), the signals, and the connections of
// running workers, whose clients leaving stops them.
std::vector<pollfd> Server::pollSet() const {
  std::vector<pollfd> fds{{listener_, POLLIN, 0}, {signals_, POLLIN, 0}};
  for (const auto& [pid, worker] : workers_) {
    if (!worker.stopped) fds.push_back({worker.connection, POLLIN, 0});
  }
  return fds;
}

bool Server::shouldStop(Clock::time_point now) const {
  if (inodeOf(socketPath_) != socketInode_) return true;
  return workers_.empty() && now - lastActivity_ >= idleLimit_;
}

int Server::serve() {
  if (!start()) return kExitSuccess;
  bool stopping = false;
  while (!(stopping && workers_.empty())) {
    std::vector<pollfd> fds = pollSet();
    if (stopping) fds[0].events = 0;
    if (::poll(fds.data(), fds.size(), 1000) < 0 && errno != EINTR) return kExitInputError;
    if ((fds[1].revents & POLLIN) != 0) onSignals(stopping);
    for (size_t i = 2; i < fds.size(); ++i) {
      if (fds[i].revents == 0) continue;
      for (const auto& [pid, worker] : workers_) {
        if (worker.connection == fds[i].fd) stopWorker(pid);
      }
    }
    if (!stopping && (fds[0].revents & POLLIN) != 0) accept();
    if (!stopping && shouldStop(Clock::now())) stopping = true;
    if (stopping) {
      for (auto& [pid, worker] : workers_) stopWorker(pid);
    }
  }
  return kExitSuccess;
}

}  // namespace

int serveCompiles(const std::filesystem::path& socketPath, const ServerHooks& hooks, std::chrono::seconds idleLimit) {
  // A server started by a client inherits whatever the client's parent left
  // open (a build tool's pipes and jobserver); holding them would keep that
  // parent waiting.
  ::close_range(3, ~0U, 0);
  // Nor keep the first client's working directory busy (an unmount, a
  // removed build folder): every run enters its own.
  if (::chdir("/") != 0) return kExitInputError;
  Server server(std::filesystem::absolute(socketPath), hooks, idleLimit);
  return server.serve();
}

}  // namespace spire::server
