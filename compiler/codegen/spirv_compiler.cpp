#include "codegen/spirv_compiler.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <spirv-tools/libspirv.hpp>

#include <climits>

namespace spire::codegen {

namespace {

EShLanguage toGlslang(ShaderStage stage) {
  switch (stage) {
    case ShaderStage::Vertex: return EShLangVertex;
    case ShaderStage::Fragment: return EShLangFragment;
    case ShaderStage::Compute: return EShLangCompute;
  }
  return EShLangVertex;  // unreachable for valid enumerators
}

// glslang needs InitializeProcess() once before any TShader is parsed; later
// parses on any thread are independent (per-thread pools, a global lock around
// the shared built-in symbol tables). FinalizeProcess() is deliberately never
// called: kernels may be compiled until exit, and the tables are reclaimed then.
bool ensureGlslangInitialized() {
  static const bool initialized = glslang::InitializeProcess();
  return initialized;
}

void appendLog(std::string& log, const std::string& text) {
  if (text.empty()) return;
  if (!log.empty() && log.back() != '\n') log += '\n';
  log += text;
}

}  // namespace

SpirvResult compileGlslToSpirv(ShaderStage stage, std::string_view glsl, std::string_view sourceName) {
  SpirvResult result;
  const std::string name(sourceName);
  if (!ensureGlslangInitialized()) {
    result.log = name + ": error: glslang failed to initialize\n";
    return result;
  }
  if (glsl.size() > static_cast<size_t>(INT_MAX)) {
    result.log = name + ": error: GLSL source too large for glslang\n";
    return result;
  }

  const EShLanguage language = toGlslang(stage);
  const char* strings[] = {glsl.data()};
  const int lengths[] = {static_cast<int>(glsl.size())};
  const char* names[] = {name.c_str()};

  // TShader and TProgram own the pools the AST lives in; the program is
  // declared after the shader so that it is destroyed first, as glslang asks.
  glslang::TShader shader(language);
  shader.setStringsWithLengthsAndNames(strings, lengths, names, 1);
  shader.setEnvInput(glslang::EShSourceGlsl, language, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_2);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);

  const auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
  const bool parsed = shader.parse(GetDefaultResources(), /*defaultVersion=*/440,
                                   /*forwardCompatible=*/false, messages);
  appendLog(result.log, shader.getInfoLog());
  if (!parsed) return result;

  glslang::TProgram program;
  program.addShader(&shader);
  const bool linked = program.link(messages);
  appendLog(result.log, program.getInfoLog());
  if (!linked) return result;

  const glslang::TIntermediate* intermediate = program.getIntermediate(language);
  if (intermediate == nullptr) {
    appendLog(result.log,
              name + ": error: glslang produced no intermediate for the " + std::string(stageName(stage)) + " stage\n");
    return result;
  }

  glslang::SpvOptions options;
  options.generateDebugInfo = false;
  options.disableOptimizer = true;
  options.validate = false;  // validateSpirv() is the separate, explicit step
  spv::SpvBuildLogger logger;
  std::vector<unsigned int> spirv;
  glslang::GlslangToSpv(*intermediate, spirv, &logger, &options);
  appendLog(result.log, logger.getAllMessages());

  static_assert(sizeof(unsigned int) == sizeof(uint32_t));
  result.words.assign(spirv.begin(), spirv.end());
  return result;
}

namespace {

// Runs the validator; its messages go to `message`. Friendly names (the
// OpName of each id in messages) cost most of a valid module's validation:
// SPIRV-Tools builds them for every id, with a string stream each, before it
// validates anything.
bool runValidator(const std::vector<uint32_t>& words, bool friendlyNames, std::string& message) {
  spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_2);
  tools.SetMessageConsumer(
      [&message](spv_message_level_t level, const char* /*source*/, const spv_position_t& position, const char* text) {
        const char* severity = "info";
        switch (level) {
          case SPV_MSG_FATAL:
          case SPV_MSG_INTERNAL_ERROR:
          case SPV_MSG_ERROR: severity = "error"; break;
          case SPV_MSG_WARNING: severity = "warning"; break;
          case SPV_MSG_INFO:
          case SPV_MSG_DEBUG: break;
        }
        if (!message.empty()) message += '\n';
        message += severity;
        message += " (word ";
        message += std::to_string(position.index);
        message += "): ";
        message += text == nullptr ? "" : text;
      });
  spvtools::ValidatorOptions options;
  options.SetFriendlyNames(friendlyNames);
  return tools.Validate(words.data(), words.size(), options);
}

}  // namespace

Expected<void, Failure> validateSpirv(const std::vector<uint32_t>& words) {
  if (words.empty()) return Failure{"empty SPIR-V module"};
  std::string message;
  if (runValidator(words, false, message)) return {};
  // Only a module that fails pays for the names, and its message has them.
  std::string named;
  runValidator(words, true, named);
  if (!named.empty()) message = std::move(named);
  if (message.empty()) message = "invalid SPIR-V module";
  return Failure{message};
}

}  // namespace spire::codegen
