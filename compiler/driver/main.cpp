#include <iostream>
#include <string_view>

#include "codegen/spirv_compiler.h"
#include "driver/compile_client.h"
#include "driver/compile_server.h"
#include "driver/library_location.h"
#include "driver/process_memory.h"
#include "driver/spirec.h"

namespace {

spire::SpirecEnvironment processEnvironment() {
  spire::SpirecEnvironment environment;
  if (const auto self = spire::runningExecutable()) {
    if (const auto library = spire::bundledLibraryDir(*self)) environment.libraryDir = library->string();
  }
  return environment;
}

// What the compile server keeps between runs: glslang's built-in tables,
// built by the first compile of a kernel's GLSL version.
void warmUpGlslang() {
  const std::string glsl = std::string(spire::codegen::kGlslVersionLines) + "void main() {}\n";
  (void)spire::codegen::compileGlslToSpirv(spire::codegen::ShaderStage::Fragment, glsl, "warm-up");
}

int serve(const char* socketPath) {
  const spire::SpirecEnvironment environment = processEnvironment();
  spire::server::ServerHooks hooks;
  hooks.warmUp = warmUpGlslang;
  hooks.run = [&](const std::vector<std::string>& args) {
    return spire::runSpirec(args, std::cout, std::cerr, environment);
  };
  return spire::server::serveCompiles(socketPath, hooks);
}

}  // namespace

int main(int argc, char** argv) {
  spire::useHugePageHeap();
  // Hidden: only this executable sets up its heap, so only it can report on
  // it; and the compile server is started by spirec itself.
  if (argc == 2 && std::string_view(argv[1]) == "--heap-report") {
    std::cout << spire::describeHeap() << '\n';
    return 0;
  }
  std::ios::sync_with_stdio(false);
  if (argc == 3 && std::string_view(argv[1]) == spire::server::kServeCompilesFlag) return serve(argv[2]);
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (spire::spirecWantsCompileServer(args)) {
    if (const auto self = spire::runningExecutable()) {
      if (const auto status = spire::server::runOnCompileServer(*self, args)) return *status;
    }
  }
  return spire::runSpirec(args, std::cout, std::cerr, processEnvironment());
}
