// spirec --batch: each line runs as a separate spirec run would, in one
// process; the batch file's own syntax and misuse.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "driver/batch_file.h"
#include "driver/spirec.h"
#include "spirec_run.h"
#include "support/file_io.h"

namespace spire {
namespace {

namespace fs = std::filesystem;
using test::spirec;
using test::SpirecRun;

// Two sources (lit.spire from the Spire library's engine pipeline, plain.spire
// standalone) in a folder whose name needs quoting in a batch file.
class Batch : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("spire batch " + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "lit.spire") << "using \"pipelines/engine.spire\";\n"
                                         "shader Lit using EnginePipeline {\n"
                                         "  @FrameUniform mat4 matMVP;\n"
                                         "  vec4 projPos = matMVP * vec4(vert_pos, 1.0);\n"
                                         "  float h = vert_uv.x * 0.5;\n"
                                         "  vec4 output = vec4(vert_normal * h, 1.0);\n"
                                         "}\n";
    std::ofstream(dir_ / "plain.spire") << "using \"pipelines/engine.spire\";\n"
                                           "shader Plain using EnginePipeline {\n"
                                           "  @FrameUniform mat4 matMVP;\n"
                                           "  vec4 projPos = matMVP * vec4(vert_pos, 1.0);\n"
                                           "  vec4 output = vec4(vert_uv, 0.0, 1.0);\n"
                                           "}\n";
    // One decision that applies and one with an unknown world (W5001).
    std::ofstream(dir_ / "lit.decisions") << "Lit.h = Vertex\nLit.projPos = Vertx\n";
    std::ofstream(dir_ / "broken.spire") << "shader Broken { float x = y; }\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string quoted(const std::string& name) const { return "\"" + path(name) + "\""; }
  SpirecRun run(const std::vector<std::string>& args) const {
    return spirec(args, SpirecEnvironment{SPIRE_SOURCE_DIR});
  }
  std::string writeBatch(const std::string& text) const {
    std::ofstream(path("jobs.txt")) << text;
    return path("jobs.txt");
  }
  // Every file under out*/ and *.d, by path relative to the folder.
  std::map<std::string, std::string> outputs() const {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(dir_)) {
      const std::string relative = fs::relative(entry.path(), dir_).string();
      const bool output = relative.starts_with("out") || entry.path().extension() == ".d";
      if (entry.is_regular_file() && output) files[relative] = *readWholeFile(entry.path().string());
    }
    return files;
  }
  void removeOutputs() const {
    for (const auto& entry : fs::directory_iterator(dir_)) {
      const std::string name = entry.path().filename().string();
      if (name.starts_with("out") || entry.path().extension() == ".d") fs::remove_all(entry.path());
    }
  }

  fs::path dir_;
};

TEST_F(Batch, JobsMatchSeparateRunsByteForByte) {
  const std::vector<std::vector<std::string>> jobs = {
      {path("lit.spire"), "-o", path("out1"), "--depfile", path("lit.d")},
      {path("lit.spire"), "--decisions", path("lit.decisions"), "-o", path("out2"), "--emit=glsl"},
      {path("plain.spire"), "-o", path("out3"), "--emit", "spirv", "--depfile", path("plain.d"), "--depfile-target",
       "plain.stamp"},
      {path("lit.spire"), path("plain.spire"), "--choices", "--shader", "Plain"},
      // The kernels of job 1 again: SPIR-V from the batch's cache.
      {path("lit.spire"), "-o", path("out4")},
  };
  std::string expectedOut, expectedErr;
  for (size_t i = 0; i < jobs.size(); ++i) {
    const SpirecRun single = run(jobs[i]);
    ASSERT_EQ(single.exitCode, kExitSuccess) << single.err;
    expectedOut += single.out;
    if (!single.err.empty())
      expectedErr += "spirec: job " + std::to_string(i + 1) + " (" + path("jobs.txt") + ":" + std::to_string(i + 3) +
                     "):\n" + single.err;
  }
  const std::map<std::string, std::string> separate = outputs();
  ASSERT_GE(separate.size(), 8u);
  removeOutputs();

  const std::string batch = writeBatch(
      "# every kind of job\n\n" + quoted("lit.spire") + " -o " + quoted("out1") + " --depfile " + quoted("lit.d") +
      "\n" + quoted("lit.spire") + " --decisions " + quoted("lit.decisions") + " -o " + quoted("out2") +
      " --emit=glsl  # W5001\n" + quoted("plain.spire") + " -o " + quoted("out3") + " --emit spirv --depfile " +
      quoted("plain.d") + " --depfile-target plain.stamp\n" + quoted("lit.spire") + " " + quoted("plain.spire") +
      " --choices --shader 'Plain'\n" + quoted("lit.spire") + " -o " + quoted("out4") + "\n");
  // One job at a time, as many as the machine has threads, and more jobs at
  // once than there are.
  for (const std::vector<std::string>& jobFlags : std::vector<std::vector<std::string>>{{"-j", "1"}, {}, {"-j8"}}) {
    std::vector<std::string> args = {"--batch", batch};
    args.insert(args.end(), jobFlags.begin(), jobFlags.end());
    const SpirecRun batched = run(args);
    EXPECT_EQ(batched.exitCode, kExitSuccess) << batched.err;
    EXPECT_EQ(batched.out, expectedOut);
    EXPECT_EQ(batched.err, expectedErr);
    EXPECT_NE(batched.err.find("W5001"), std::string::npos) << batched.err;
    EXPECT_EQ(outputs(), separate);
    removeOutputs();
  }
}

TEST_F(Batch, ConcurrentJobsWriteAndPrintInFileOrder) {
  // Jobs that write the same shader folder and depfile: the last job's files
  // are what is left, as when they run one after another. The placements go
  // to stdout in job order.
  std::string lines;
  std::string expectedOut;
  for (int i = 0; i < 12; ++i) {
    const bool decided = i % 2 == 1;
    std::vector<std::string> job = {path("lit.spire"),  "-o",         path("out"), "--depfile", path("lit.d"),
                                    "--dump-placement", "--emit=glsl"};
    if (decided) job.insert(job.end(), {"--decisions", path("lit.decisions")});
    const SpirecRun single = run(job);
    ASSERT_EQ(single.exitCode, kExitSuccess) << single.err;
    expectedOut += single.out;
    for (const std::string& arg : job) lines += "\"" + arg + "\" ";
    lines += "\n";
  }
  const std::map<std::string, std::string> last = outputs();  // the last job ran last
  removeOutputs();
  const SpirecRun batched = run({"--batch", writeBatch(lines), "-j", "4"});
  EXPECT_EQ(batched.exitCode, kExitSuccess) << batched.err;
  EXPECT_EQ(batched.out, expectedOut);
  EXPECT_EQ(outputs(), last);
}

TEST_F(Batch, FailingJobDoesNotStopTheOthers) {
  const std::string batch =
      writeBatch(quoted("lit.spire") + " -o " + quoted("out1") + "\n" + quoted("broken.spire") + " -o " +
                 quoted("out2") + "\n" + quoted("plain.spire") + " -o " + quoted("out3") + "\n");
  const SpirecRun batched = run({"--batch", batch});
  EXPECT_EQ(batched.exitCode, kExitInputError);
  EXPECT_TRUE(fs::exists(path("out1/Lit/reflection.json")));
  EXPECT_TRUE(fs::exists(path("out3/Plain/reflection.json")));
  EXPECT_FALSE(fs::exists(path("out2")));
  const std::string header = "spirec: job 2 (" + batch + ":2) failed (exit status 1):\n";
  EXPECT_EQ(batched.err, header + run({path("broken.spire"), "-o", path("out2")}).err);

  // The worst status wins: a usage error (2) over an input error (1).
  const SpirecRun worse = run({"--batch", writeBatch(quoted("broken.spire") + "\n--no-such-flag x.spire\n")});
  EXPECT_EQ(worse.exitCode, kExitUsageError);
  EXPECT_NE(worse.err.find("spirec: job 2 (" + batch + ":2) failed (exit status 2):\n"), std::string::npos)
      << worse.err;
}

TEST_F(Batch, MalformedLineIsAnErrorAtItsColumnAndRunsNothing) {
  const std::string batch = writeBatch(quoted("plain.spire") + " -o " + quoted("out1") + "\n# fine\n" +
                                       quoted("plain.spire") + " -o \"out 2\n");
  const SpirecRun batched = run({"--batch", batch});
  EXPECT_EQ(batched.exitCode, kExitInputError);
  const size_t column = quoted("plain.spire").size() + 5;
  EXPECT_NE(batched.err.find(batch + ":3:" + std::to_string(column) + ": error[E1105]: unterminated double quote"),
            std::string::npos)
      << batched.err;
  EXPECT_NE(batched.err.find("^"), std::string::npos) << batched.err;
  EXPECT_FALSE(fs::exists(path("out1")));
}

TEST_F(Batch, BatchWithOtherArgumentsIsAUsageError) {
  const std::string batch = writeBatch(quoted("plain.spire") + "\n");
  const std::vector<std::pair<std::vector<std::string>, std::string>> misuses = {
      {{"--batch", batch, "-q"}, "-q"},
      {{path("plain.spire"), "--batch=" + batch}, path("plain.spire")},
      {{"--batch"}, "--batch"},
      {{"--batch", batch, "-j", "0"}, "-j"},
      {{"--batch", batch, "-j", "2x"}, "-j"},
      {{"--batch", batch, "-j"}, "-j"},
      {{"--batch", batch, "-j", "1", "-j", "2"}, "-j"},
  };
  for (const auto& [args, named] : misuses) {
    const SpirecRun misuse = run(args);
    EXPECT_EQ(misuse.exitCode, kExitUsageError) << misuse.err;
    EXPECT_EQ(misuse.err.rfind("spirec: error: ", 0), 0u) << misuse.err;
    EXPECT_NE(misuse.err.find(named), std::string::npos) << misuse.err;
    EXPECT_NE(misuse.err.find("--help"), std::string::npos) << misuse.err;
  }
  EXPECT_EQ(run({"--batch=" + batch}).exitCode, kExitSuccess);
  const SpirecRun nested = run({"--batch", writeBatch("--batch " + quoted("jobs.txt") + "\n")});
  EXPECT_EQ(nested.exitCode, kExitUsageError);
  EXPECT_NE(nested.err.find("--batch cannot be used inside a batch file"), std::string::npos) << nested.err;
}

// -j N in each spelling the tools accept, before or after --batch.
TEST_F(Batch, JobCountsInEachSpelling) {
  const std::string batch = writeBatch(quoted("plain.spire") + " -o " + quoted("out") + "\n");
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{{"--batch=" + batch, "-j", "3"},
                                                                                    {"-j3", "--batch", batch},
                                                                                    {"--batch", batch, "--jobs", "12"},
                                                                                    {"--jobs=2", "--batch", batch}}) {
    removeOutputs();
    const SpirecRun batched = run(args);
    EXPECT_EQ(batched.exitCode, kExitSuccess) << ::testing::PrintToString(args) << batched.err;
    EXPECT_TRUE(fs::exists(path("out/Plain/reflection.json"))) << ::testing::PrintToString(args);
  }
}

TEST_F(Batch, MissingBatchFileIsAClearError) {
  const SpirecRun missing = run({"--batch", path("none.txt")});
  EXPECT_EQ(missing.exitCode, kExitInputError);
  EXPECT_EQ(missing.err.rfind("spirec: error: cannot read batch file '" + path("none.txt") + "': ", 0), 0u)
      << missing.err;
}

TEST_F(Batch, HelpDocumentsBatchMode) {
  const SpirecRun help = run({"--help"});
  EXPECT_NE(help.out.find("--batch FILE"), std::string::npos) << help.out;
}

TEST(BatchFile, QuotingAndComments) {
  SourceManager sources;
  DiagnosticList diags;
  const FileId file = sources.addFile(
      "b.txt", "  # only a comment\r\na \"b c\" 'd\\e' f\\ g \"h\\\"i\\\\j\\k\" -o\"x y\" l#m # n\n\n\\#o\r\n");
  const std::vector<BatchJob> jobs = parseBatchFile(sources, file, diags);
  EXPECT_FALSE(diags.hasErrors());
  ASSERT_EQ(jobs.size(), 2u);
  EXPECT_EQ(jobs[0].line, 2u);
  EXPECT_EQ(jobs[0].args, (std::vector<std::string>{"a", "b c", "d\\e", "f g", "h\"i\\j\\k", "-ox y", "l#m"}));
  EXPECT_EQ(jobs[1].line, 4u);
  EXPECT_EQ(jobs[1].args, (std::vector<std::string>{"#o"}));
}

TEST(BatchFile, MalformedLinesReportEach) {
  SourceManager sources;
  DiagnosticList diags;
  const FileId file = sources.addFile("b.txt", "a 'b\nc\nd \\\n");
  EXPECT_TRUE(parseBatchFile(sources, file, diags).size() == 1u);
  ASSERT_EQ(diags.all().size(), 2u);
  EXPECT_EQ(sources.begin(diags.all()[0].range).column, 3u);
  EXPECT_EQ(sources.begin(diags.all()[1].range).line, 3u);
}

}  // namespace
}  // namespace spire
