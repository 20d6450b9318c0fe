// Compiles shaders/lit.spire in process through the installed library's one
// compile entry point: the installed headers are complete and
// Spire::compiler links.
#include <iostream>

#include "driver/compiler.h"
#include "support/diagnostic_renderer.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: compile_lit SOURCE SPIRE_LIBRARY_DIR\n";
    return 2;
  }
  spire::FrontEndOptions options;
  options.includeDirs.push_back(argv[2]);
  spire::ShaderLibrary library(std::move(options));
  library.addFile(argv[1]);
  if (!library.compile()) {
    std::cerr << spire::renderDiagnostics(library.sources(), library.diagnostics(), spire::DiagnosticFormat::Text);
    return 1;
  }
  spire::Decisions decisions;
  decisions.placement["shade"] = "Vertex";
  const spire::CompileResult compiled = spire::compileVariant(library, "Lit", decisions);
  if (!compiled) {
    std::cerr << compiled.error().message << "\n";
    return 1;
  }
  std::cout << "Lit: " << compiled.value()->kernels.size() << " kernels\n";
  return 0;
}
