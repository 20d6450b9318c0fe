#include "driver/server_protocol.h"

#include <fmt/format.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "reflection/reflection.h"
#include "support/content_hash.h"

namespace spire::server {
namespace {

constexpr char kAccepted = 'A';

// A request on the wire: a 4-byte length, then length-prefixed strings
// (args, working directory, environment) and the umask.
class Writer {
 public:
  void u32(uint32_t value) { bytes_.append(reinterpret_cast<const char*>(&value), sizeof value); }
  void text(const std::string& value) {
    u32(static_cast<uint32_t>(value.size()));
    bytes_ += value;
  }
  void texts(const std::vector<std::string>& values) {
    u32(static_cast<uint32_t>(values.size()));
    for (const std::string& value : values) text(value);
  }
  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}
  bool u32(uint32_t& value) {
    if (bytes_.size() < sizeof value) return false;
    std::memcpy(&value, bytes_.data(), sizeof value);
    bytes_.remove_prefix(sizeof value);
    return true;
  }
  bool text(std::string& value) {
    uint32_t size = 0;
    if (!u32(size) || bytes_.size() < size) return false;
    value.assign(bytes_.substr(0, size));
    bytes_.remove_prefix(size);
    return true;
  }
  bool texts(std::vector<std::string>& values) {
    uint32_t count = 0;
    if (!u32(count) || count > bytes_.size()) return false;
    values.resize(count);
    for (std::string& value : values) {
      if (!text(value)) return false;
    }
    return true;
  }
  bool done() const { return bytes_.empty(); }

 private:
  std::string_view bytes_;
};

Failure systemFailure(std::string_view what) { return Failure{fmt::format("{}: {}", what, std::strerror(errno))}; }

Expected<void, Failure> sendAll(int socket, const char* data, size_t size) {
  while (size > 0) {
    const ssize_t sent = ::send(socket, data, size, MSG_NOSIGNAL);
    if (sent < 0 && errno == EINTR) continue;
    if (sent <= 0) return systemFailure("cannot send on the compile server's socket");
    data += sent;
    size -= static_cast<size_t>(sent);
  }
  return {};
}

bool receiveAll(int socket, char* data, size_t size) {
  while (size > 0) {
    const ssize_t got = ::recv(socket, data, size, 0);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return false;
    data += got;
    size -= static_cast<size_t>(got);
  }
  return true;
}

// A request's 4-byte length with room for the three descriptors that travel
// with it: one sendmsg or recvmsg.
struct LengthMessage {
  explicit LengthMessage(void* length) : io{length, sizeof(uint32_t)} {
    message.msg_iov = &io;
    message.msg_iovlen = 1;
    message.msg_control = control;
    message.msg_controllen = sizeof control;
  }
  LengthMessage(const LengthMessage&) = delete;
  LengthMessage& operator=(const LengthMessage&) = delete;

  iovec io;
  alignas(cmsghdr) char control[CMSG_SPACE(sizeof(int) * 3)] = {};
  msghdr message{};
};

// The first 4 bytes (the length) travel with the descriptors, so that the
// receiver gets them from the one recvmsg that reads the length.
Expected<void, Failure> sendWithDescriptors(int socket, const std::string& bytes, const std::array<int, 3>& fds) {
  LengthMessage length(const_cast<char*>(bytes.data()));
  msghdr& message = length.message;
  cmsghdr* header = CMSG_FIRSTHDR(&message);
  header->cmsg_level = SOL_SOCKET;
  header->cmsg_type = SCM_RIGHTS;
  header->cmsg_len = CMSG_LEN(sizeof(int) * 3);
  std::memcpy(CMSG_DATA(header), fds.data(), sizeof(int) * 3);
  ssize_t sent = -1;
  do {
    sent = ::sendmsg(socket, &message, MSG_NOSIGNAL);
  } while (sent < 0 && errno == EINTR);
  if (sent != static_cast<ssize_t>(sizeof(uint32_t)))
    return systemFailure("cannot send on the compile server's socket");
  return sendAll(socket, bytes.data() + sizeof(uint32_t), bytes.size() - sizeof(uint32_t));
}

// Reads the length and the descriptors sent with it.
Expected<uint32_t, Failure> receiveLengthAndDescriptors(int socket, std::array<int, 3>& fds) {
  uint32_t length = 0;
  LengthMessage received(&length);
  msghdr& message = received.message;
  ssize_t got = -1;
  do {
    got = ::recvmsg(socket, &message, MSG_CMSG_CLOEXEC | MSG_WAITALL);
  } while (got < 0 && errno == EINTR);
  for (cmsghdr* header = CMSG_FIRSTHDR(&message); header != nullptr; header = CMSG_NXTHDR(&message, header)) {
    if (header->cmsg_level != SOL_SOCKET || header->cmsg_type != SCM_RIGHTS) continue;
    const size_t count = (header->cmsg_len - CMSG_LEN(0)) / sizeof(int);
    std::vector<int> passed(count);
    std::memcpy(passed.data(), CMSG_DATA(header), count * sizeof(int));
    // Descriptors that are not the three a request carries are the server's
    // to close, or they would stay open in it.
    if (count == 3 && fds[0] < 0) {
      std::copy(passed.begin(), passed.end(), fds.begin());
    } else {
      for (int fd : passed) ::close(fd);
    }
  }
  if (got != static_cast<ssize_t>(sizeof length) || (message.msg_flags & MSG_CTRUNC) != 0 || fds[2] < 0) {
    return Failure{"a request without its length or descriptors"};
  }
  if (length < sizeof length || length > kMaxRequestBytes) return Failure{"a request of a wrong length"};
  return length;
}

void closeAll(std::array<int, 3>& fds) {
  for (int& fd : fds) {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
}

// A private folder of this user's for the sockets; nullopt when `dir` is
// someone else's or open to others.
std::optional<std::filesystem::path> privateFolder(const std::filesystem::path& dir) {
  if (::mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST) return std::nullopt;
  struct stat info {};
  if (::lstat(dir.c_str(), &info) != 0 || !S_ISDIR(info.st_mode) || info.st_uid != ::geteuid() ||
      (info.st_mode & (S_IWGRP | S_IWOTH)) != 0) {
    return std::nullopt;
  }
  return dir;
}

std::optional<std::filesystem::path> socketFolder() {
  // Absolute, so that clients in other working directories find the same
  // socket.
  if (const char* dir = std::getenv("SPIRE_SERVER_DIR"); dir != nullptr && *dir != '\0') {
    std::error_code error;
    const std::filesystem::path absolute = std::filesystem::absolute(dir, error);
    if (error) return std::nullopt;
    return privateFolder(absolute.lexically_normal());
  }
  if (const char* runtime = std::getenv("XDG_RUNTIME_DIR"); runtime != nullptr && *runtime == '/') {
    return privateFolder(std::filesystem::path(runtime) / "spire");
  }
  return privateFolder(fmt::format("/tmp/spire-{}", ::geteuid()));
}

}  // namespace

Expected<void, Failure> sendRequest(int socket, const Request& request, const std::array<int, 3>& fds) {
  Writer body;
  body.texts(request.args);
  body.text(request.workingDirectory);
  body.texts(request.environment);
  body.u32(static_cast<uint32_t>(request.umask));
  Writer framed;
  framed.u32(static_cast<uint32_t>(sizeof(uint32_t) + body.bytes().size()));
  std::string bytes = framed.bytes() + body.bytes();
  if (bytes.size() > kMaxRequestBytes) return Failure{"the request is too large for the compile server"};
  return sendWithDescriptors(socket, bytes, fds);
}

Expected<ReceivedRequest, Failure> receiveRequest(int socket) {
  ReceivedRequest received;
  auto length = receiveLengthAndDescriptors(socket, received.fds);
  if (!length) {
    closeAll(received.fds);
    return length.error();
  }
  std::string body(*length - sizeof(uint32_t), '\0');
  Reader reader(body);
  uint32_t mask = 0;
  Request& request = received.request;
  if (!receiveAll(socket, body.data(), body.size()) || !reader.texts(request.args) ||
      !reader.text(request.workingDirectory) || !reader.texts(request.environment) || !reader.u32(mask) ||
      !reader.done()) {
    closeAll(received.fds);
    return Failure{"a malformed request"};
  }
  request.umask = static_cast<mode_t>(mask & 0777);
  return received;
}

Expected<void, Failure> sendAccepted(int socket) { return sendAll(socket, &kAccepted, 1); }

bool receiveAccepted(int socket, std::chrono::milliseconds timeout) {
  pollfd entry{socket, POLLIN, 0};
  int ready = 0;
  do {
    ready = ::poll(&entry, 1, static_cast<int>(timeout.count()));
  } while (ready < 0 && errno == EINTR);
  char accepted = 0;
  return ready > 0 && receiveAll(socket, &accepted, 1) && accepted == kAccepted;
}

Expected<void, Failure> sendStatus(int socket, int status) {
  const auto value = static_cast<uint32_t>(status);
  return sendAll(socket, reinterpret_cast<const char*>(&value), sizeof value);
}

std::optional<int> receiveStatus(int socket) {
  uint32_t value = 0;
  if (!receiveAll(socket, reinterpret_cast<char*>(&value), sizeof value)) return std::nullopt;
  return static_cast<int>(value);
}

std::optional<std::filesystem::path> serverSocketPath(const std::filesystem::path& executable) {
  struct stat info {};
  if (::stat(executable.c_str(), &info) != 0) return std::nullopt;
  const auto folder = socketFolder();
  if (!folder) return std::nullopt;
  const std::string identity = fmt::format("{}\n{}\n{}\n{}.{}", executable.string(), info.st_size, info.st_ino,
                                           info.st_mtim.tv_sec, info.st_mtim.tv_nsec);
  const std::filesystem::path path = *folder / fmt::format("spirec-{}.sock", spire::contentHash(identity));
  if (path.native().size() >= sizeof(sockaddr_un::sun_path)) return std::nullopt;
  return path;
}

sockaddr_un socketAddress(const std::filesystem::path& path) {
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::strncpy(address.sun_path, path.c_str(), sizeof address.sun_path - 1);
  return address;
}

}  // namespace spire::server
