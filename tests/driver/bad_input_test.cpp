// spirec on inputs that are valid but extreme (operator chains of thousands
// of terms, a 50 MB line) or plainly wrong (empty sources, directories,
// unreadable files, unwritable outputs, decision files for another shader),
// run as a user would run it.
#include <grp.h>
#include <gtest/gtest.h>
#include <pthread.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "driver/spirec.h"
#include "spirec_run.h"
#include "support/file_io.h"

namespace spire {
namespace {

namespace fs = std::filesystem;
using test::spirec;
using test::SpirecRun;

// A fresh folder per test, removed afterwards (permissions restored first).
class BadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("spire_bad_input_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ignored;
    for (const auto& entry : fs::recursive_directory_iterator(dir_, ignored)) {
      fs::permissions(entry.path(), fs::perms::owner_all, fs::perm_options::add, ignored);
    }
    fs::remove_all(dir_, ignored);
  }

  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return (dir_ / name).string();
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

std::string engineShader(const std::string& components) {
  return "using \"" + (fs::path(SPIRE_SOURCE_DIR) / "pipelines/engine.spire").string() + "\";\n" +
         "shader Sum using EnginePipeline {\n"
         "  @FrameUniform mat4 matMVP;\n"
         "  vec4 projPos = matMVP * vec4(vert_pos, 1.0);\n" +
         components + "}\n";
}

// `first op first op ...` with `terms` terms.
std::string chain(int terms, const std::string& term, const std::string& op) {
  std::string text = term;
  for (int i = 1; i < terms; ++i) text += op + term;
  return text;
}

// A component and a function that both compute a sum of `terms` terms.
std::string sumShader(int terms) {
  return "float twice(float a) { return " + chain(terms, "a", " - ") + " + a * 2.0; }\n" +
         engineShader("  float s = " + chain(terms, "vert_uv.x", " + ") + ";\n" +
                      "  vec4 output = vec4(vert_normal * twice(s), 1.0);\n");
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::string readText(const fs::path& file) { return readWholeFile(file.string()).value_or(""); }

// spirec failed on its input and said `message`.
void expectInputError(const SpirecRun& run, const std::string& message) {
  EXPECT_EQ(run.exitCode, kExitInputError) << run.err.substr(0, 2000);
  EXPECT_NE(run.err.find(message), std::string::npos) << run.err.substr(0, 2000);
}

// Runs `body` on a thread with a stack of `bytes`.
void onStackOf(size_t bytes, const std::function<void()>& body) {
  pthread_attr_t attributes;
  pthread_attr_init(&attributes);
  pthread_attr_setstacksize(&attributes, bytes);
  pthread_t thread;
  auto run = [](void* argument) -> void* {
    (*static_cast<const std::function<void()>*>(argument))();
    return nullptr;
  };
  ASSERT_EQ(pthread_create(&thread, &attributes, run, const_cast<std::function<void()>*>(&body)), 0);
  pthread_join(thread, nullptr);
  pthread_attr_destroy(&attributes);
}

// A flat sum is not nesting: generated shaders write such chains, and they
// compile to kernels (SPIR-V included) with every term kept.
TEST_F(BadInput, LongSumsCompileEndToEnd) {
  for (int terms : {250, 10000}) {
    SCOPED_TRACE(terms);
    const std::string out = path("out" + std::to_string(terms));
    const SpirecRun run = spirec({write("sum.spire", sumShader(terms)), "-o", out, "--dump-placement"});
    ASSERT_EQ(run.exitCode, kExitSuccess) << run.err.substr(0, 2000);
    EXPECT_EQ(run.err, "");
    EXPECT_NE(run.out.find("Sum.s = "), std::string::npos);
    const std::string kernels =
        readText(fs::path(out) / "Sum/Vertex.glsl") + readText(fs::path(out) / "Sum/Fragment.glsl");
    EXPECT_EQ(count(kernels, "vert_uv.x"), static_cast<size_t>(terms));
    EXPECT_EQ(count(kernels, " - a"), static_cast<size_t>(terms - 1));
    EXPECT_TRUE(fs::exists(fs::path(out) / "Sum/Fragment.spv"));
  }
}

// No stage recurses along a chain: 100000 terms compile on a 4 MiB stack,
// where a few dozen bytes of stack per term would already overflow it. That
// includes glslang, which does recurse along a chain, because kernels compute
// long chains in steps.
TEST_F(BadInput, ChainsDoNotDeepenTheStack) {
  const std::string source = write("sum.spire", sumShader(100000));
  SpirecRun run{};
  onStackOf(4u << 20, [&] { run = spirec({source, "-o", path("out"), "--emit=both", "--dump-placement"}); });
  EXPECT_EQ(run.exitCode, kExitSuccess) << run.err.substr(0, 2000);
}

// Real nesting is still limited.
TEST_F(BadInput, DeepParenthesesAreNestingTooDeep) {
  const std::string nested = std::string(300, '(') + "vert_uv.x" + std::string(300, ')');
  const std::string source =
      write("nested.spire", engineShader("  float s = " + nested + ";\n  vec4 output = vec4(s);\n"));
  expectInputError(spirec({source}), "error[E2004]: nesting too deep");
}

// Diagnostics on a megabyte-long line quote a window of it, not all of it.
TEST_F(BadInput, DiagnosticsOnAHugeLineStaySmall) {
  std::string line;
  while (line.size() < (4u << 20)) line += "float f() { return 1.0 + $; } ";
  const SpirecRun run = spirec({write("minified.spire", line)});
  expectInputError(run, "error[E1001]: stray character '$'");
  EXPECT_NE(run.err.find(" 1 | ...urn 1.0 + $; } float f() {"), std::string::npos) << run.err.substr(0, 2000);
  EXPECT_LT(run.err.size(), 20000u);
}

// A source that declares nothing fails at its first line instead of
// compiling to nothing.
TEST_F(BadInput, AnEmptySourceIsAnError) {
  for (const std::string text : {"", "  \n\t\r\n", "// nothing yet\n/* still\n nothing */\n"}) {
    SCOPED_TRACE(text);
    const std::string source = write("empty.spire", text);
    expectInputError(spirec({source, "--choices"}), source + ":1:1: error[E1104]: '" + source +
                                                        "' declares nothing: it is empty or holds only comments");
  }
}

std::string terrain() { return (fs::path(SPIRE_SOURCE_DIR) / "examples/terrain.spire").string(); }

// Permissions do not stop root, so where the tests run as root (CI
// containers do) spirec runs in a child process that has given up root for
// the unprivileged user `nobody`, and reports back through pipes.
constexpr uid_t kNobody = 65534;

std::string drain(int fd) {
  std::string text;
  char buffer[4096];
  for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) > 0;) text.append(buffer, static_cast<size_t>(n));
  ::close(fd);
  return text;
}

void writeAll(int fd, const std::string& text) {
  for (size_t done = 0; done < text.size();) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n <= 0) return;
    done += static_cast<size_t>(n);
  }
}

SpirecRun spirecUnprivileged(const std::vector<std::string>& args) {
  if (::geteuid() != 0) return spirec(args);
  int out[2];
  int err[2];
  if (::pipe(out) != 0 || ::pipe(err) != 0) return {-1, "", "pipe failed"};
  const pid_t child = ::fork();
  if (child == 0) {
    ::close(out[0]);
    ::close(err[0]);
    if (::setgroups(0, nullptr) != 0 || ::setresgid(kNobody, kNobody, kNobody) != 0 ||
        ::setresuid(kNobody, kNobody, kNobody) != 0) {
      writeAll(err[1], "cannot become nobody");
      ::_exit(127);
    }
    const SpirecRun run = spirec(args);
    writeAll(out[1], run.out);
    writeAll(err[1], run.err);
    ::_exit(run.exitCode);  // no exit handlers: they are the parent's
  }
  ::close(out[1]);
  ::close(err[1]);
  SpirecRun run{-1, drain(out[0]), drain(err[0])};
  int status = 0;
  if (child > 0 && ::waitpid(child, &status, 0) == child && WIFEXITED(status)) run.exitCode = WEXITSTATUS(status);
  return run;
}

TEST_F(BadInput, ADirectoryGivenAsAFileSaysSo) {
  const std::string folder = path("shaders.spire");
  fs::create_directories(folder);
  expectInputError(spirec({folder}), "error[E1101]: cannot open source file '" + folder + "': Is a directory");
  expectInputError(spirec({terrain(), "--decisions", folder}),
                   "error[E1101]: cannot open file '" + folder + "': Is a directory");
}

TEST_F(BadInput, AnUnreadableFileSaysWhy) {
  const std::string source = write("secret.spire", "struct S { float x; };\n");
  fs::permissions(source, fs::perms::none);
  expectInputError(spirecUnprivileged({source}), "cannot open source file '" + source + "': Permission denied");
}

// Each write error carries the reason of the call that failed, not what a
// later cleanup left in errno ("Success").
TEST_F(BadInput, WriteErrorsSayWhy) {
  fs::create_directories(dir_ / "taken");
  expectInputError(spirec({terrain(), "--choices", path("taken")}),
                   "cannot write '" + path("taken") + "': Is a directory");
  expectInputError(spirec({terrain(), "--choices", path("missing/terrain.choices")}), "': No such file or directory");
  write("file", "");
  expectInputError(spirec({terrain(), "-o", path("file/out"), "--emit=glsl"}),
                   "error[E6003]: cannot create directory '" + path("file/out") + "': Not a directory");
}

TEST_F(BadInput, WritingIntoAReadOnlyFolderSaysWhy) {
  fs::create_directories(dir_ / "readonly");
  // Readable by everyone (the unprivileged child included), writable by no one.
  fs::permissions(dir_ / "readonly", fs::perms::owner_read | fs::perms::owner_exec | fs::perms::others_read |
                                         fs::perms::others_exec | fs::perms::group_read | fs::perms::group_exec);
  expectInputError(spirecUnprivileged({terrain(), "--choices", path("readonly/terrain.choices")}),
                   "': Permission denied");
  expectInputError(spirecUnprivileged({terrain(), "-o", path("readonly"), "--emit=glsl"}), "Permission denied");
}

// An empty output folder, decision file or shader name is a usage error,
// not "no output", "no decisions" or "every shader".
TEST_F(BadInput, EmptyOptionValuesAreUsageErrors) {
  for (const std::string option : {"-o", "--output", "--decisions", "--shader"}) {
    SCOPED_TRACE(option);
    const SpirecRun run = spirec({terrain(), option, ""});
    EXPECT_EQ(run.exitCode, kExitUsageError);
    EXPECT_NE(run.err.find("spirec: error: "), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("must not be empty"), std::string::npos) << run.err;
    EXPECT_EQ(run.out, "");
  }
  EXPECT_EQ(spirec({terrain(), "--output="}).exitCode, kExitUsageError);
}

// A decision file with one decision that applies and one that names an
// unknown world (W5001).
constexpr const char* kOneBadDecision = "Terrain.albedo = PrebakeTex\nTerrain.normal = Vertx\n";

// With --warnings-as-errors (or -Werror) a warning fails the run: it is
// reported as an error that says why, and nothing is written.
TEST_F(BadInput, WarningsAsErrors) {
  const std::string decisions = write("terrain.decisions", kOneBadDecision);
  const SpirecRun lenient = spirec({terrain(), "--decisions", decisions, "-o", path("out"), "--emit=glsl"});
  EXPECT_EQ(lenient.exitCode, kExitSuccess) << lenient.err;
  EXPECT_NE(lenient.err.find("warning[W5001]: unknown world 'Vertx'"), std::string::npos) << lenient.err;
  fs::remove_all(path("out"));
  const std::vector<std::vector<std::string>> flags = {{"--warnings-as-errors"}, {"-Werror"}, {"-W", "error"}};
  for (const std::vector<std::string>& flag : flags) {
    SCOPED_TRACE(flag.front());
    std::vector<std::string> args = {terrain(), "--decisions", decisions, "-o", path("out"), "--dump-placement"};
    args.insert(args.end(), flag.begin(), flag.end());
    const SpirecRun strict = spirec(args);
    expectInputError(strict, decisions + ":2:18: error[W5001]: unknown world 'Vertx'");
    EXPECT_NE(strict.err.find("note: treated as an error (--warnings-as-errors)\n1 error generated.\n"),
              std::string::npos)
        << strict.err;
    EXPECT_EQ(strict.out, "");
    EXPECT_FALSE(fs::exists(path("out")));
  }
  const SpirecRun json = spirec({terrain(), "--decisions", decisions, "-Werror", "--diagnostics-format=json"});
  EXPECT_EQ(json.exitCode, kExitInputError);
  EXPECT_NE(json.err.find("\"severity\": \"error\",\n      \"code\": \"W5001\""), std::string::npos) << json.err;
  EXPECT_NE(json.err.find("\"errorCount\": 1,\n  \"warningCount\": 0"), std::string::npos) << json.err;
  EXPECT_EQ(spirec({terrain(), "-Wall"}).exitCode, kExitUsageError);
  // Without warnings the flag changes nothing.
  EXPECT_EQ(spirec({terrain(), "--choices", "-Werror"}).exitCode, kExitSuccess);
}

// A decision file none of whose decisions takes effect is an error: written
// for another shader, or with every decision skipped.
TEST_F(BadInput, ADecisionFileThatDecidesNothingIsAnError) {
  const std::string couch = (fs::path(SPIRE_SOURCE_DIR) / "examples/couch.spire").string();
  const std::string forTerrain =
      (fs::path(SPIRE_SOURCE_DIR) / "examples/decisions/terrain_baked_albedo.decisions").string();
  const SpirecRun other = spirec({couch, "--decisions", forTerrain, "-o", path("out"), "--emit=glsl"});
  expectInputError(other,
                   "error[E5002]: no decision in this file applies to shader 'Couch': its decisions are for 'Terrain'");
  EXPECT_NE(other.err.find("warning[W5001]: unknown shader 'Terrain'"), std::string::npos) << other.err;
  EXPECT_FALSE(fs::exists(path("out")));
  const std::string skipped =
      write("skipped.decisions", "// stale\nTerrain.albedoo = Vertex\nTerrain.normal = Vertx\n");
  const SpirecRun stale = spirec({terrain(), "--decisions", skipped});
  expectInputError(stale, skipped +
                              ":2:1: error[E5002]: no decision in this file applies to shader 'Terrain': "
                              "every decision for it is skipped");
  // No decisions at all ask for the default variant.
  const std::string none = write("none.decisions", "// defaults everywhere\n\n");
  EXPECT_EQ(spirec({terrain(), "--decisions", none, "--dump-placement"}).exitCode, kExitSuccess);
  // A file applied to several shaders needs to apply to one of them only.
  const std::string lod = (fs::path(SPIRE_SOURCE_DIR) / "examples/lod_library.spire").string();
  const std::string forLq = write("lq.decisions", "BaseMaterialLQ.nDotL = Vertex\n");
  const SpirecRun library = spirec({lod, "--decisions", forLq, "--dump-placement"});
  EXPECT_EQ(library.exitCode, kExitSuccess) << library.err;
  EXPECT_EQ(library.err, "");
  expectInputError(spirec({lod, "--decisions", forLq, "--shader", "TerrainLOD<BaseMaterialHQ>"}),
                   "error[E5002]: no decision in this file applies to shader 'TerrainLOD<BaseMaterialHQ>': "
                   "its decisions are for 'BaseMaterialLQ'");
}

}  // namespace
}  // namespace spire
