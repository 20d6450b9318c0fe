// The compile server (driver/compile_server.h) through the built spirec, as
// a build runs it: a run it serves writes, prints and exits exactly as one in
// the client's own process; a worker does not outlive its client; a server
// does not outlive its socket; and a socket folder that is not private is
// never used.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include "scene/temp_dir.h"
#include "support/file_io.h"

namespace {

namespace fs = std::filesystem;
using spire::scene::testing::TempDir;

const std::string kSpirec = SPIRE_SPIREC_EXE;
const std::string kCouch = std::string(SPIRE_SOURCE_DIR) + "/examples/couch.spire";

std::string readText(const fs::path& path) { return spire::readWholeFile(path.string()).value_or(""); }

// Every file under `dir` with its bytes, by relative path.
std::map<std::string, std::string> filesUnder(const fs::path& dir) {
  std::map<std::string, std::string> files;
  if (!fs::exists(dir)) return files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (entry.is_regular_file()) files[fs::relative(entry.path(), dir).string()] = readText(entry.path());
  }
  return files;
}

bool eventually(const std::function<bool()>& condition, std::chrono::seconds limit = std::chrono::seconds(20)) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (std::chrono::steady_clock::now() < end) {
    if (condition()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return condition();
}

bool alive(pid_t pid) { return pid > 0 && ::kill(pid, 0) == 0; }

// The processes whose parent is `pid`.
std::string childrenOf(pid_t pid) {
  return readText(fs::path("/proc") / std::to_string(pid) / "task" / std::to_string(pid) / "children");
}

class CompileServerTest : public ::testing::Test {
 protected:
  // What a spirec run left: its exit status, stdout, stderr and output files.
  struct Run {
    int status = -1;
    std::string out, err;
    std::map<std::string, std::string> files;
  };

  // A socket's path must fit a socket address (108 bytes): not under the
  // test's folder, whose name is long.
  fs::path serverDir() const { return serverDir_; }

  // Runs `spirec ARGS` in `work` (created), writing into work/out; with the
  // server unless `inProcess`.
  Run spirec(const std::string& args, const std::string& work, bool inProcess) const {
    const fs::path dir = temp_.path() / work;
    fs::create_directories(dir);
    const std::string command = "cd '" + dir.string() + "' && SPIRE_SERVER_DIR='" + serverDir().string() + "' " +
                                (inProcess ? "SPIRE_SERVER=off " : "") + "'" + kSpirec + "' " + args +
                                " >stdout.txt 2>stderr.txt";
    Run run;
    const int result = std::system(command.c_str());
    run.status = WIFEXITED(result) ? WEXITSTATUS(result) : -1;
    run.out = readText(dir / "stdout.txt");
    run.err = readText(dir / "stderr.txt");
    run.files = filesUnder(dir / "out");
    return run;
  }

  // The running server's process id, from its lock file; 0 when none.
  pid_t serverPid() const {
    if (!fs::exists(serverDir())) return 0;
    for (const auto& entry : fs::directory_iterator(serverDir())) {
      if (entry.path().extension() != ".lock") continue;
      const pid_t pid = std::atoi(readText(entry.path()).c_str());
      const fs::path socket = entry.path().parent_path() / entry.path().stem();
      if (alive(pid) && fs::exists(socket)) return pid;
    }
    return 0;
  }

  // Starts the server the way a first run does, and waits until it listens.
  pid_t startServer() const {
    EXPECT_EQ(spirec("'" + kCouch + "' -o out", "first", false).status, 0);
    pid_t pid = 0;
    EXPECT_TRUE(eventually([&] { return (pid = serverPid()) != 0; })) << "no server started in " << serverDir();
    return pid;
  }

  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "spire-server-test-XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    serverDir_ = pattern;
  }

  void TearDown() override {
    if (const pid_t pid = serverPid()) ::kill(pid, SIGTERM);
    std::error_code ignored;
    fs::remove_all(serverDir_, ignored);
  }

  TempDir temp_;
  fs::path serverDir_;
};

TEST_F(CompileServerTest, ServedRunsMatchRunsInTheClientsProcess) {
  const pid_t server = startServer();
  ASSERT_NE(server, 0);
  {
    std::ofstream broken(temp_.path() / "broken.spire");
    broken << "shader Broken {\n  float x = ;\n}\n";
  }
  const std::string broken = (temp_.path() / "broken.spire").string();
  // Relative paths resolve in the client's working directory; a depfile,
  // diagnostics with carets and a failing status come back as they are.
  for (const std::string& args :
       {"'" + kCouch + "' -o out --depfile out/couch.d", "'" + kCouch + "' -o out --emit spirv --dump-placement",
        "'" + broken + "' -o out", "'" + kCouch + "' -o out --shader Nothing"}) {
    const Run served = spirec(args, "served", false);
    const Run local = spirec(args, "local", true);
    EXPECT_EQ(served.status, local.status) << args;
    EXPECT_EQ(served.out, local.out) << args;
    EXPECT_EQ(served.err, local.err) << args;
    EXPECT_EQ(served.files, local.files) << args;
    fs::remove_all(temp_.path() / "served");
    fs::remove_all(temp_.path() / "local");
  }
  EXPECT_EQ(serverPid(), server) << "the server stopped or was replaced";
}

TEST_F(CompileServerTest, AWorkerRunsTheClientsRunAndStopsWhenTheClientDoes) {
  const pid_t server = startServer();
  ASSERT_NE(server, 0);
  // A batch read from a FIFO holds the run until the test writes it, so the
  // worker can be seen.
  const fs::path fifo = temp_.path() / "jobs";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string command = "cd '" + temp_.path().string() + "' && SPIRE_SERVER_DIR='" + serverDir().string() +
                              "' exec '" + kSpirec + "' --batch jobs >/dev/null 2>&1";
  const pid_t client = ::fork();
  ASSERT_GE(client, 0);
  if (client == 0) {
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  EXPECT_TRUE(eventually([&] { return !childrenOf(server).empty(); })) << "no worker took the run";
  ::kill(client, SIGKILL);
  ::waitpid(client, nullptr, 0);
  EXPECT_TRUE(eventually([&] { return childrenOf(server).empty(); })) << "the worker outlived its client";
  EXPECT_EQ(serverPid(), server);
}

TEST_F(CompileServerTest, TheServerStopsWhenItsSocketIsRemovedOrOnSigterm) {
  pid_t server = startServer();
  ASSERT_NE(server, 0);
  fs::remove_all(serverDir());
  EXPECT_TRUE(eventually([&] { return !alive(server); })) << "the server outlived its socket";

  server = startServer();
  ASSERT_NE(server, 0);
  ::kill(server, SIGTERM);
  EXPECT_TRUE(eventually([&] { return !alive(server); }));
  EXPECT_EQ(serverPid(), 0);
  EXPECT_TRUE(filesUnder(serverDir()).size() <= 1) << "the socket was left behind";
}

TEST_F(CompileServerTest, AStaleSocketIsReplacedByANewServer) {
  const pid_t first = startServer();
  ASSERT_NE(first, 0);
  ::kill(first, SIGKILL);
  EXPECT_TRUE(eventually([&] { return !alive(first); }));
  const Run run = spirec("'" + kCouch + "' -o out", "after", false);
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_FALSE(run.files.empty());
  pid_t second = 0;
  EXPECT_TRUE(eventually([&] { return (second = serverPid()) != 0; }));
  EXPECT_NE(second, first);
}

TEST_F(CompileServerTest, ARelativeServerFolderNamesOneFolderFromAnyWorkingDirectory) {
  const pid_t server = startServer();
  ASSERT_NE(server, 0);
  const fs::path relative = fs::relative(serverDir(), temp_.path());
  const std::string command = "cd '" + temp_.path().string() + "' && SPIRE_SERVER_DIR='" + relative.string() + "' '" +
                              kSpirec + "' '" + kCouch + "' -o out >/dev/null 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_EQ(serverPid(), server) << "a second server";
  const auto entries = fs::directory_iterator(temp_.path() / relative);
  EXPECT_EQ(std::distance(fs::begin(entries), fs::end(entries)), 2) << "the socket and its lock, nothing more";
  EXPECT_EQ(fs::read_symlink(fs::path("/proc") / std::to_string(server) / "cwd"), fs::path("/"))
      << "the server keeps a working directory busy";
}

// A run stays in its own process when the user says so (--no-server,
// SPIRE_SERVER=off), and when a tracer or a preloaded library would see or
// change only that process.
TEST_F(CompileServerTest, RunsThatMustStayInTheirProcessStartNoServer) {
  const fs::path dir = temp_.path() / "here";
  fs::create_directories(dir);
  // In a sanitizer build, LeakSanitizer cannot run under ptrace and
  // AddressSanitizer's runtime must otherwise come first among preloads.
  const std::string server =
      "SPIRE_SERVER_DIR='" + serverDir().string() + "' ASAN_OPTIONS=detect_leaks=0:verify_asan_link_order=0 ";
  const std::string spirec = "'" + kSpirec + "' '" + kCouch + "' -o '" + (dir / "out").string() + "'";
  for (const std::string& command :
       {server + spirec + " --no-server", server + "SPIRE_SERVER=off " + spirec,
        server + "LD_PRELOAD=libm.so.6 " + spirec, server + "strace -f -o /dev/null " + spirec}) {
    EXPECT_EQ(std::system((command + " >/dev/null 2>&1").c_str()), 0)
        << command << " (strace comes with scripts/install-deps.sh)";
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    EXPECT_EQ(serverPid(), 0) << "a server was started by " << command;
    EXPECT_TRUE(fs::is_empty(serverDir())) << command;
  }
  // The same run as it is starts one, so the checks above can fail.
  EXPECT_NE(startServer(), 0);
}

TEST_F(CompileServerTest, AFolderOthersCanWriteIsNeverUsed) {
  ASSERT_EQ(::chmod(serverDir().c_str(), 0777), 0);
  const Run run = spirec("'" + kCouch + "' -o out", "open", false);
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_FALSE(run.files.empty());
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_TRUE(filesUnder(serverDir()).empty()) << "a socket was made in a folder open to others";
}

}  // namespace
