// What a spirec process and the compile server (driver/compile_server.h) say
// to each other over a Unix socket. A client sends one Request, with its
// standard input, output and error attached (SCM_RIGHTS), so that the run
// reads and prints exactly where the client would; the server answers with
// one byte once a worker has taken the run, then the run's exit status.
//
// Both sides are the same executable (the socket's name is derived from the
// executable's identity), so the format needs no version of its own.
#pragma once

#include <sys/types.h>
#include <sys/un.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "support/expected.h"

namespace spire::server {

// One spirec run as the client's process would make it.
struct Request {
  std::vector<std::string> args;         // without the program name
  std::string workingDirectory;          // absolute
  std::vector<std::string> environment;  // NAME=VALUE, the client's whole environment
  mode_t umask = 022;
};

// Sends `request` and `fds` (standard input, output, error) on a connected
// socket.
Expected<void, Failure> sendRequest(int socket, const Request& request, const std::array<int, 3>& fds);

// A request received with the client's three descriptors, which the caller
// owns.
struct ReceivedRequest {
  Request request;
  std::array<int, 3> fds{-1, -1, -1};
};

// Reads one request; a Failure when the peer sent something else or closed.
// Requests larger than kMaxRequestBytes are refused.
Expected<ReceivedRequest, Failure> receiveRequest(int socket);
inline constexpr uint32_t kMaxRequestBytes = uint32_t{64} << 20;

// The server's word, one byte, that a worker runs the request; and the
// client's wait for it, false when it did not come within `timeout`.
Expected<void, Failure> sendAccepted(int socket);
bool receiveAccepted(int socket, std::chrono::milliseconds timeout);

// A run's outcome: its exit status, or 128 + the signal that ended it, as a
// shell reports it.
Expected<void, Failure> sendStatus(int socket, int status);
// Waits for sendStatus; nullopt when the server closed first.
std::optional<int> receiveStatus(int socket);

// Where the server of `executable` listens: DIR/spirec-HASH.sock, HASH from
// the executable's path, size, inode and modification time, so that a
// rebuilt or moved spirec never talks to an older one's server. DIR is
// $SPIRE_SERVER_DIR (made absolute), else $XDG_RUNTIME_DIR/spire, else /tmp/spire-UID; it is
// created private (0700) and must be owned by this user and not writable by
// others. nullopt when no such folder can be had or the path is too long for
// a socket address.
std::optional<std::filesystem::path> serverSocketPath(const std::filesystem::path& executable);

// The address of the socket at `path` (which serverSocketPath keeps short
// enough).
sockaddr_un socketAddress(const std::filesystem::path& path);

}  // namespace spire::server
