#include "syntax/module_loader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>

#include "syntax_test_util.h"

namespace spire {
namespace {

using Lines = std::vector<std::string>;

// A compilation over an in-memory file system.
struct Loading {
  std::map<std::string, std::string> files;
  std::vector<std::string> reads;  // every path the loader asked for
  SourceManager sources;
  DiagnosticList diags{50};
  ast::Program program;

  ModuleLoader loader(std::vector<std::string> includeDirs = {}) {
    LoadOptions options;
    options.includeDirs = std::move(includeDirs);
    options.readFile = [this](const std::string& path) -> std::optional<std::string> {
      reads.push_back(path);
      const auto found = files.find(path);
      if (found == files.end()) return std::nullopt;
      return found->second;
    };
    return ModuleLoader(sources, diags, std::move(options));
  }

  // The path of each loaded module, in program order.
  Lines modulePaths() const {
    Lines paths;
    for (const auto& module : program.modules) paths.push_back(sources.file(module->file).path);
    return paths;
  }
  Lines diagnostics() const { return test::describe(sources, diags); }
  // The logical name (the name in kernels' #line) of each loaded module.
  Lines logicalNames() const {
    Lines names;
    for (const auto& module : program.modules) names.push_back(sources.file(module->file).logicalName);
    return names;
  }
};

TEST(ModuleLoader, IncludesResolveRelativeToTheIncludingFile) {
  Loading l;
  l.files = {{"main.spire", "using \"lib/a.spire\";\nusing \"c.spire\";"},
             {"lib/a.spire", "using \"b.spire\";\nusing \"../c.spire\";"},
             {"lib/b.spire", "struct B { float x; };"},
             {"c.spire", "struct C { float x; };"}};
  EXPECT_TRUE(l.loader().loadFile("main.spire", l.program));
  EXPECT_EQ(l.diagnostics(), Lines{});
  // Post-order: every file after what it includes; c.spire only once.
  EXPECT_EQ(l.modulePaths(), (Lines{"lib/b.spire", "c.spire", "lib/a.spire", "main.spire"}));
}

TEST(ModuleLoader, IncludeDirectoriesAreSearchedInOrderAfterTheIncluder) {
  Loading l;
  l.files = {{"src/main.spire", "using \"std.spire\";\nusing \"local.spire\";"},
             {"inc1/std.spire", "struct First { float x; };"},
             {"inc2/std.spire", "struct Second { float x; };"},
             {"src/local.spire", ""},
             {"inc1/local.spire", ""}};
  EXPECT_TRUE(l.loader({"inc1", "inc2"}).loadFile("src/main.spire", l.program));
  EXPECT_EQ(l.diagnostics(), Lines{});
  EXPECT_EQ(l.modulePaths(), (Lines{"inc1/std.spire", "src/local.spire", "src/main.spire"}));
}

TEST(ModuleLoader, LogicalNamesAreRelativeToTheInputsFolderOrTheIncludeDirectory) {
  // Inputs and what they include next to themselves: relative to the first
  // input's folder; an include directory's files (and theirs): relative to it.
  Loading l;
  l.files = {{"src/main.spire", "using \"../shared/s.spire\";\nusing \"std.spire\";"},
             {"src/./../src/other.spire", "struct O { float x; };"},
             {"shared/s.spire", ""},
             {"inc/std.spire", "using \"sub/util.spire\";"},
             {"inc/sub/util.spire", ""}};
  auto loader = l.loader({"./x/../inc/"});
  EXPECT_TRUE(loader.loadFile("src/main.spire", l.program));
  EXPECT_TRUE(loader.loadFile("src/./../src/other.spire", l.program));
  EXPECT_EQ(l.diagnostics(), Lines{});
  EXPECT_EQ(l.modulePaths(), (Lines{"shared/s.spire", "inc/sub/util.spire", "inc/std.spire", "src/main.spire",
                                    "src/./../src/other.spire"}));
  EXPECT_EQ(l.logicalNames(), (Lines{"../shared/s.spire", "sub/util.spire", "std.spire", "main.spire", "other.spire"}));
}

TEST(ModuleLoader, EachFileLoadsOnceWhateverThePathSpelling) {
  Loading l;
  l.files = {{"main.spire", "using \"a.spire\";\nusing \"./lib/../a.spire\";\nusing \"lib/x.spire\";"},
             {"a.spire", "struct A { float x; };"},
             {"lib/x.spire", "using \"../a.spire\";"}};
  auto loader = l.loader();
  EXPECT_TRUE(loader.loadFile("main.spire", l.program));
  EXPECT_TRUE(loader.loadFile("./main.spire", l.program));
  EXPECT_EQ(l.diagnostics(), Lines{});
  EXPECT_EQ(l.modulePaths(), (Lines{"a.spire", "lib/x.spire", "main.spire"}));
  EXPECT_EQ(std::count(l.reads.begin(), l.reads.end(), "a.spire"), 1);
}

TEST(ModuleLoader, IncludeCycleIsReportedWhereItCloses) {
  Loading l;
  l.files = {{"a.spire", "using \"b.spire\";"}, {"b.spire", "struct B { float x; };\nusing \"a.spire\";"}};
  EXPECT_TRUE(l.loader().loadFile("a.spire", l.program));
  EXPECT_EQ(l.diagnostics(), Lines{"E1102 2:1 include cycle: a.spire -> b.spire -> a.spire"});
  EXPECT_EQ(l.sources.text(l.diags.all().at(0).range), "using \"a.spire\";");
  EXPECT_EQ(l.modulePaths(), (Lines{"b.spire", "a.spire"}));
}

TEST(ModuleLoader, SelfIncludeIsACycle) {
  Loading l;
  l.files = {{"dir/a.spire", "using \"a.spire\";"}};
  l.loader().loadFile("dir/a.spire", l.program);
  EXPECT_EQ(l.diagnostics(), Lines{"E1102 1:1 include cycle: dir/a.spire -> dir/a.spire"});
}

TEST(ModuleLoader, MissingIncludeNamesWhereItLooked) {
  Loading l;
  l.files = {{"src/main.spire", "shader S using P { }\nusing \"nope.spire\";"}};
  EXPECT_TRUE(l.loader({"inc"}).loadFile("src/main.spire", l.program));
  EXPECT_EQ(l.diagnostics(), (Lines{"E1101 2:7 cannot open included file 'nope.spire'",
                                    "  note - searched 'src/nope.spire', 'inc/nope.spire'"}));
  EXPECT_EQ(l.sources.text(l.diags.all().at(0).range), "\"nope.spire\"");
  EXPECT_EQ(l.modulePaths(), Lines{"src/main.spire"});
}

TEST(ModuleLoader, UnreadableRootFile) {
  Loading l;
  EXPECT_FALSE(l.loader().loadFile("missing.spire", l.program));
  EXPECT_EQ(l.diagnostics(), Lines{"E1101 - cannot open source file 'missing.spire': No such file or directory"});
  EXPECT_TRUE(l.program.modules.empty());
}

// On the real file system, an include that exists but cannot be read is
// named with the reason, besides where the loader looked.
TEST(ModuleLoader, UnreadableIncludeSaysWhy) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "spire_unreadable_include";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "lib.spire");
  std::ofstream(dir / "main.spire") << "using \"lib.spire\";\n";
  SourceManager sources;
  DiagnosticList diags;
  ast::Program program;
  ModuleLoader(sources, diags, {}).loadFile((dir / "main.spire").string(), program);
  EXPECT_EQ(test::describe(sources, diags),
            (Lines{"E1101 1:7 cannot open included file 'lib.spire'",
                   "  note - searched '" + (dir / "lib.spire").string() + "'",
                   "  note - cannot read '" + (dir / "lib.spire").string() + "': Is a directory"}));
  std::filesystem::remove_all(dir);
}

TEST(ModuleLoader, InMemorySourceIncludesRelativeToItsDisplayPath) {
  Loading l;
  l.files = {{"shaders/common.spire", "struct C { float x; };"}};
  l.loader().loadSource("shaders/main.spire", "using \"common.spire\";", l.program);
  EXPECT_EQ(l.diagnostics(), Lines{});
  EXPECT_EQ(l.modulePaths(), (Lines{"shaders/common.spire", "shaders/main.spire"}));
}

TEST(ModuleLoader, BinaryFilesAreRejected) {
  Loading l;
  l.files = {{"main.spire", "using \"blob.spire\";\nusing \"latin1.spire\";"},
             {"blob.spire", std::string("struct\0", 7)},
             {"latin1.spire", "// caf\xE9\n"}};
  EXPECT_TRUE(l.loader().loadFile("main.spire", l.program));
  EXPECT_EQ(l.diagnostics(), (Lines{"E1103 1:7 'blob.spire' is not a source file: it contains a NUL byte",
                                    "E1103 1:7 'latin1.spire' is not valid UTF-8 text"}));
  EXPECT_EQ(l.modulePaths(), Lines{"main.spire"});
}

TEST(ModuleLoader, ExpressionIdsAreUniqueAcrossModules) {
  Loading l;
  l.files = {{"a.spire", "using \"b.spire\";\nshader S using P { float x = 1.0 + 2.0; }"},
             {"b.spire", "shader T using P { float y = 3.0; }"}};
  l.loader().loadFile("a.spire", l.program);
  EXPECT_EQ(l.program.exprCount, 4u);
  const auto& t = ast::cast<ast::ShaderDecl>(*l.program.modules.at(0)->decls.at(0));
  const auto& s = ast::cast<ast::ShaderDecl>(*l.program.modules.at(1)->decls.at(1));
  EXPECT_EQ(t.components.at(0).init->id, 3u);
  EXPECT_EQ(s.components.at(0).init->id, 2u);
}

TEST(ModuleLoader, ReadsTheFileSystemByDefault) {
  const auto dir = std::filesystem::temp_directory_path() / "spire_module_loader_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "lib");
  std::ofstream(dir / "main.spire", std::ios::binary) << "using \"lib/util.spire\";\r\nshader S using P { }\r\n";
  std::ofstream(dir / "lib" / "util.spire", std::ios::binary) << "struct U { float x; };\n";

  SourceManager sources;
  DiagnosticList diags;
  ast::Program program;
  ModuleLoader loader(sources, diags, LoadOptions{});
  const std::string main = (dir / "main.spire").string();
  EXPECT_TRUE(loader.loadFile(main, program));
  EXPECT_FALSE(loader.loadFile((dir / "absent.spire").string(), program));
  EXPECT_FALSE(loader.loadFile(dir.string(), program));
  ASSERT_EQ(program.modules.size(), 2u);
  EXPECT_EQ(sources.file(program.modules[0]->file).path, (dir / "lib" / "util.spire").generic_string());
  EXPECT_EQ(diags.all().size(), 2u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace spire
