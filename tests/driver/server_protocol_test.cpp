// The compile server's wire format (driver/server_protocol.h): a request
// arrives whole, with its three descriptors, and anything else a peer sends
// is refused without reading past it or leaving descriptors open.
#include "driver/server_protocol.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstring>
#include <string>

namespace spire::server {
namespace {

// A connected pair of Unix stream sockets, closed at the end of the test.
class SocketPair {
 public:
  SocketPair() { EXPECT_EQ(::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, fds_), 0); }
  ~SocketPair() {
    for (int fd : fds_) {
      if (fd >= 0) ::close(fd);
    }
  }
  SocketPair(const SocketPair&) = delete;
  SocketPair& operator=(const SocketPair&) = delete;

  int client() const { return fds_[0]; }
  int server() const { return fds_[1]; }
  void closeClient() {
    ::close(fds_[0]);
    fds_[0] = -1;
  }

 private:
  int fds_[2] = {-1, -1};
};

// The number of descriptors this process has open.
int openDescriptors() {
  int count = 0;
  for (int fd = 0; fd < 1024; ++fd) count += ::fcntl(fd, F_GETFD) != -1 ? 1 : 0;
  return count;
}

std::string readAll(int fd) {
  std::string text(64, '\0');
  const ssize_t got = ::read(fd, text.data(), text.size());
  text.resize(got > 0 ? static_cast<size_t>(got) : 0);
  return text;
}

TEST(ServerProtocolTest, ARequestArrivesWholeWithItsDescriptors) {
  SocketPair sockets;
  int pipeFds[2];
  ASSERT_EQ(::pipe(pipeFds), 0);
  Request sent;
  sent.args = {"a b.spire", "", "-o", "out\ndir", std::string(20000, 'x')};
  sent.workingDirectory = "/tmp/some where";
  sent.environment = {"A=1", "EMPTY=", "MULTI=line\nline"};
  sent.umask = 027;
  ASSERT_TRUE(sendRequest(sockets.client(), sent, {pipeFds[0], pipeFds[1], pipeFds[1]}));
  auto received = receiveRequest(sockets.server());
  ASSERT_TRUE(received) << received.error().message;
  EXPECT_EQ(received->request.args, sent.args);
  EXPECT_EQ(received->request.workingDirectory, sent.workingDirectory);
  EXPECT_EQ(received->request.environment, sent.environment);
  EXPECT_EQ(received->request.umask, sent.umask);
  // The received descriptors are the same pipe: what goes in one end comes
  // out of the other.
  ASSERT_EQ(::write(received->fds[1], "hi", 2), 2);
  EXPECT_EQ(readAll(pipeFds[0]), "hi");
  for (int fd : received->fds) ::close(fd);
  ::close(pipeFds[0]);
  ::close(pipeFds[1]);
}

TEST(ServerProtocolTest, TheStatusAndTheAcceptanceComeBack) {
  SocketPair sockets;
  ASSERT_TRUE(sendAccepted(sockets.server()));
  EXPECT_TRUE(receiveAccepted(sockets.client(), std::chrono::milliseconds(1000)));
  EXPECT_FALSE(receiveAccepted(sockets.client(), std::chrono::milliseconds(10))) << "nothing more was sent";
  ASSERT_TRUE(sendStatus(sockets.server(), 143));
  EXPECT_EQ(receiveStatus(sockets.client()), 143);
  ::shutdown(sockets.server(), SHUT_WR);
  EXPECT_EQ(receiveStatus(sockets.client()), std::nullopt) << "a closed server gives no status";
}

// Raw bytes with, optionally, descriptors, as a faulty or hostile peer might
// send them.
void sendRaw(int socket, const std::string& bytes, int descriptorCount) {
  std::vector<int> fds(static_cast<size_t>(descriptorCount), STDERR_FILENO);
  iovec io{const_cast<char*>(bytes.data()), bytes.size()};
  std::vector<char> control(CMSG_SPACE(sizeof(int) * fds.size()));
  msghdr message{};
  message.msg_iov = &io;
  message.msg_iovlen = 1;
  if (!fds.empty()) {
    message.msg_control = control.data();
    message.msg_controllen = control.size();
    cmsghdr* header = CMSG_FIRSTHDR(&message);
    header->cmsg_level = SOL_SOCKET;
    header->cmsg_type = SCM_RIGHTS;
    header->cmsg_len = CMSG_LEN(sizeof(int) * fds.size());
    std::memcpy(CMSG_DATA(header), fds.data(), sizeof(int) * fds.size());
  }
  ASSERT_EQ(::sendmsg(socket, &message, 0), static_cast<ssize_t>(bytes.size()));
}

std::string u32(uint32_t value) { return std::string(reinterpret_cast<const char*>(&value), sizeof value); }

TEST(ServerProtocolTest, MalformedRequestsAreRefusedAndLeaveNoDescriptorOpen) {
  const int before = openDescriptors();
  struct Case {
    const char* what;
    std::string bytes;
    int descriptors;
    bool closeAfter;
  };
  const Case cases[] = {
      {"no descriptors", u32(8) + u32(0), 0, true},
      {"two descriptors", u32(8) + u32(0), 2, true},
      {"a length below its own size", u32(2), 3, true},
      {"a length past the limit", u32(kMaxRequestBytes + 1), 3, true},
      {"a body shorter than its length", u32(64) + u32(0), 3, true},
      {"a count larger than the body", u32(12) + u32(0xffffffffU) + u32(0), 3, true},
      {"a string longer than the body", u32(16) + u32(1) + u32(1000) + u32(0), 3, true},
      {"bytes after the request", u32(32) + u32(0) + u32(0) + u32(0) + u32(0) + u32(0) + u32(0) + u32(0), 3, true},
      {"nothing at all", "", 0, true},
  };
  for (const Case& c : cases) {
    SocketPair sockets;
    if (!c.bytes.empty()) sendRaw(sockets.client(), c.bytes, c.descriptors);
    if (c.closeAfter) sockets.closeClient();
    const auto received = receiveRequest(sockets.server());
    EXPECT_FALSE(received) << c.what;
  }
  EXPECT_EQ(openDescriptors(), before) << "a refused request left descriptors open";
}

}  // namespace
}  // namespace spire::server
