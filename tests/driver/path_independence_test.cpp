// Kernels, reflection and hashes do not depend on where spirec runs or how
// the input path is spelled (docs/reflection.md, "#line directives"):
// spirec runs from different working directories, with relative, absolute
// and roundabout spellings, on the checkout and on a copy of it elsewhere,
// and every output file must be byte-identical.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "driver/spirec.h"

namespace spire {
namespace {

namespace fs = std::filesystem;

// Restores the working directory, which other tests of this binary set too.
class WorkingDirectory {
 public:
  explicit WorkingDirectory(const fs::path& dir) : saved_(fs::current_path()) { fs::current_path(dir); }
  ~WorkingDirectory() { fs::current_path(saved_); }
  WorkingDirectory(const WorkingDirectory&) = delete;
  WorkingDirectory& operator=(const WorkingDirectory&) = delete;

 private:
  fs::path saved_;
};

struct SpirecOutput {
  int exitCode = 0;
  std::string err;
  std::map<std::string, std::string> files;  // path under -o -> contents
};

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// Runs spirec in `cwd` with `args` plus `-o OUT` and reads back everything
// it wrote.
SpirecOutput spirecIn(const fs::path& cwd, std::vector<std::string> args, const fs::path& out) {
  fs::remove_all(out);
  SpirecOutput run;
  {
    WorkingDirectory here(cwd);
    args.insert(args.end(), {"-o", out.string()});
    std::ostringstream stdoutText, stderrText;
    run.exitCode = runSpirec(args, stdoutText, stderrText);
    run.err = stderrText.str();
  }
  for (const auto& entry : fs::recursive_directory_iterator(out)) {
    if (entry.is_regular_file()) {
      run.files[fs::relative(entry.path(), out).generic_string()] = readFile(entry.path());
    }
  }
  fs::remove_all(out);
  return run;
}

void expectSameFiles(const SpirecOutput& a, const SpirecOutput& b) {
  ASSERT_EQ(a.exitCode, kExitSuccess) << a.err;
  ASSERT_EQ(b.exitCode, kExitSuccess) << b.err;
  std::vector<std::string> namesA, namesB;
  for (const auto& [name, text] : a.files) namesA.push_back(name);
  for (const auto& [name, text] : b.files) namesB.push_back(name);
  ASSERT_EQ(namesA, namesB);
  for (const auto& [name, text] : a.files) EXPECT_TRUE(text == b.files.at(name)) << name << " differs";
}

const fs::path kSource = SPIRE_SOURCE_DIR;
// Per test and process: ctest runs these tests in parallel.
fs::path tempDir() {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return fs::temp_directory_path() /
         fmt::format("spire_path_independence_{}_{}", info ? info->name() : "none", ::getpid());
}

TEST(PathIndependence, KernelsAndReflectionDoNotDependOnTheWorkingDirectoryOrSpelling) {
  const std::string decisions = "examples/decisions/terrain_baked_albedo.decisions";
  const SpirecOutput relative =
      spirecIn(kSource, {"examples/terrain.spire", "--decisions", decisions}, tempDir() / "a");
  ASSERT_FALSE(relative.files.empty());
  // From the examples folder, with an absolute path that takes a detour.
  const std::string roundabout = (kSource / "stdlib" / ".." / "examples" / "." / "terrain.spire").string();
  const SpirecOutput absolute =
      spirecIn(kSource / "examples", {roundabout, "--decisions", (kSource / decisions).string()}, tempDir() / "b");
  expectSameFiles(relative, absolute);
  // The kernels name the sources relative to the input's folder.
  const std::string& fragment = relative.files.at("Terrain/Fragment.glsl");
  EXPECT_NE(fragment.find("#line "), std::string::npos);
  EXPECT_NE(fragment.find("\"terrain.spire\""), std::string::npos) << fragment;
  EXPECT_NE(fragment.find("\"../stdlib/lighting.spire\""), std::string::npos) << fragment;
  EXPECT_EQ(fragment.find(kSource.string()), std::string::npos) << fragment;
  fs::remove_all(tempDir());
}

TEST(PathIndependence, ACopyOfTheSourcesElsewhereGivesTheSameKernels) {
  // A second checkout at another depth, as on another build machine.
  const fs::path copy = tempDir() / "deeper" / "checkout";
  fs::remove_all(tempDir() / "deeper");
  for (const char* dir : {"examples", "pipelines", "stdlib"}) {
    fs::create_directories(copy / dir);
    fs::copy(kSource / dir, copy / dir, fs::copy_options::recursive);
  }
  const SpirecOutput original = spirecIn(kSource, {"examples/lod_library.spire"}, tempDir() / "a");
  const SpirecOutput copied = spirecIn(copy / "stdlib", {"../examples/lod_library.spire"}, tempDir() / "b");
  expectSameFiles(original, copied);
  fs::remove_all(tempDir() / "deeper");
  fs::remove_all(tempDir());
}

TEST(PathIndependence, IncludeDirectoriesNameTheirFilesRelativeToThemselves) {
  const fs::path project = tempDir() / "project";
  fs::remove_all(project);
  fs::create_directories(project / "shaders");
  std::ofstream(project / "shaders" / "lit.spire") << "using \"engine.spire\";\n"
                                                      "shader Lit using EnginePipeline {\n"
                                                      "  @FrameUniform mat4 matMVP;\n"
                                                      "  vec4 projPos = matMVP * vec4(vert_pos, 1.0);\n"
                                                      "  vec4 output = vec4(vert_normal, 1.0);\n"
                                                      "}\n";
  const SpirecOutput inProject =
      spirecIn(project, {"shaders/lit.spire", "-I", (kSource / "pipelines").string()}, tempDir() / "a");
  const std::string pipelinesFromShaders = fs::relative(kSource / "pipelines", project / "shaders").string();
  const SpirecOutput inShaders =
      spirecIn(project / "shaders", {"./lit.spire", "-I", pipelinesFromShaders + "/"}, tempDir() / "b");
  expectSameFiles(inProject, inShaders);
  fs::remove_all(project);
  fs::remove_all(tempDir());
}

TEST(PathIndependence, DiagnosticsKeepThePathAsTyped) {
  const fs::path project = tempDir() / "broken";
  fs::remove_all(project);
  fs::create_directories(project / "sub");
  std::ofstream(project / "sub" / "bad.spire") << "shader S using NoSuchPipeline {}\n";
  {
    WorkingDirectory here(project);
    std::ostringstream out, err;
    EXPECT_EQ(runSpirec({"sub/../sub/bad.spire"}, out, err), kExitInputError);
    EXPECT_EQ(err.str().rfind("sub/../sub/bad.spire:1:", 0), 0u) << err.str();
  }
  fs::remove_all(project);
  fs::remove_all(tempDir());
}

}  // namespace
}  // namespace spire
