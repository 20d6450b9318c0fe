#include "renderer/material.h"

#include <fmt/format.h>

#include <cmath>
#include <set>

#include "renderer/supplied_values.h"
#include "renderer/value_layout.h"
#include "renderer/world_roles.h"

namespace spire::engine {

namespace {

std::string supportedNames() {
  std::string names;
  for (const FrameValueInfo& v : frameValues()) names += fmt::format("{}{}", names.empty() ? "" : ", ", v.component);
  return names;
}

class MaterialResolver {
 public:
  MaterialResolver(const VariantProgram& program, const scene::InstanceDesc& instance, const TextureLookup& textureFor,
                   DiagnosticList& diags)
      : program_(program), instance_(instance), textureFor_(textureFor), diags_(diags) {}

  ResolvedMaterial resolve() {
    const size_t errorsBefore = diags_.errorCount();
    for (const KernelProgram& kernel : program_.kernels) {
      checkKernelWorld(kernel);
      for (const KernelInput& input : kernel.inputs) checkInput(kernel, input);
    }
    ResolvedMaterial resolved;
    resolved.read = std::move(used_);
    if (diags_.errorCount() == errorsBefore) resolved.values = std::move(values_);
    return resolved;
  }

 private:
  SourceRange shaderRange() const { return instance_.kernels ? instance_.kernelsRange : instance_.shaderRange; }

  void checkKernelWorld(const KernelProgram& kernel) {
    const WorldPass* pass = kernel.pass;
    if (!pass || !pass->stage) {
      diags_.reportOnce(DiagCode::E7104, shaderRange(),
                        fmt::format("'{}' has a kernel for world '{}', which this engine does not run: give the "
                                    "world a [Role: \"...\"] attribute naming one of its kernel roles ({})",
                                    program_.shader, kernel.world, roleList(/*kernelsOnly=*/true)));
    } else if (*pass->stage != kernel.stage) {
      diags_.reportOnce(
          DiagCode::E7104, shaderRange(),
          fmt::format("the engine runs world '{}' as a {} kernel, but '{}' compiles it as {}", kernel.world,
                      codegen::stageName(*pass->stage), program_.shader, codegen::stageName(kernel.stage)));
    }
  }

  void checkInput(const KernelProgram& kernel, const KernelInput& input) {
    const WorldPass* pass = kernel.sourcePass(input);
    if (!pass) {
      used_.insert(input.component);  // the binding is fine; the world is the problem
      diags_.reportOnce(DiagCode::E7104, shaderRange(),
                        fmt::format("'{}' imports '{}' from world '{}', which this engine does not know: give the "
                                    "world a [Role: \"...\"] attribute naming one of its roles ({})",
                                    program_.shader, input.component, input.from, roleList()));
      return;
    }
    switch (pass->kind) {
      case WorldRole::MaterialParameters: bindMaterial(input, /*engineValue=*/false); break;
      case WorldRole::FrameParameters: bindMaterial(input, /*engineValue=*/true); break;
      case WorldRole::MeshAttributes: checkMeshAttribute(kernel, input); break;
      case WorldRole::InstanceParameters: checkInstanceValue(input); break;
      default: break;  // produced by a bake of this variant
    }
  }

  void checkMeshAttribute(const KernelProgram& kernel, const KernelInput& input) {
    const MeshAttribute* attribute = findMeshAttribute(input.component);
    if (!attribute) {
      diags_.reportOnce(DiagCode::E7102, shaderRange(),
                        fmt::format("the {} kernel reads mesh attribute '{}', which meshes do not have "
                                    "(they have vert_pos, vert_uv, vert_normal and vert_tangent)",
                                    kernel.world, input.component));
    } else if (!findMeshAttribute(input.component, input.type.name)) {
      diags_.reportOnce(DiagCode::E7103, shaderRange(),
                        fmt::format("mesh attribute '{}' is a {}, but '{}' declares it as {}", input.component,
                                    meshAttributeTypes(input.component), program_.shader, input.type.name));
    }
  }

  // Per-instance values differ between the objects of one draw, so a
  // material cannot bind them: the engine supplies every one.
  void checkInstanceValue(const KernelInput& input) {
    const auto supplied = instanceValue(input.component, InstanceState{});
    if (!supplied) {
      diags_.reportOnce(
          DiagCode::E7102, shaderRange(),
          fmt::format("'{}' reads '{}' ({} from {}), which is not a per-instance engine value; the "
                      "engine supplies {}",
                      program_.shader, input.component, input.type.name, input.from, instanceValueNames()));
    } else if (supplied->type != input.type.name) {
      diags_.reportOnce(DiagCode::E7103, shaderRange(),
                        fmt::format("the engine supplies '{}' as {}, but '{}' declares it as {}", input.component,
                                    supplied->type, program_.shader, input.type.name));
    }
  }

  void bindMaterial(const KernelInput& input, bool engineValue) {
    const scene::MaterialBinding* binding = findBinding(input.component);
    if (binding) {
      used_.insert(input.component);
      if (!values_.contains(input.component)) resolveBinding(input, *binding);
      return;
    }
    if (!engineValue) {
      diags_.reportOnce(DiagCode::E7102, instance_.materialRange,
                        fmt::format("input '{}' ({} from {}) of '{}' is not bound; add it to the instance's "
                                    "\"material\"",
                                    input.component, input.type.name, input.from, program_.shader));
      return;
    }
    const auto supplied = frameValue(input.component, FrameState{}, glm::mat4(1.0F));
    if (!supplied) {
      diags_.reportOnce(DiagCode::E7102, instance_.materialRange,
                        fmt::format("input '{}' ({} from {}) of '{}' is not bound and is not a per-frame engine value "
                                    "({}); bind it in the instance's \"material\"",
                                    input.component, input.type.name, input.from, program_.shader, supportedNames()));
    } else if (supplied->type != input.type.name) {
      diags_.reportOnce(DiagCode::E7103, shaderRange(),
                        fmt::format("the engine supplies '{}' as {}, but '{}' declares it as {}", input.component,
                                    supplied->type, program_.shader, input.type.name));
    }
  }

  const scene::MaterialBinding* findBinding(const std::string& component) const {
    for (const scene::MaterialBinding& binding : instance_.material) {
      if (binding.component == component) return &binding;
    }
    return nullptr;
  }

  // `binding` names a value the engine supplies every frame: it must be one,
  // of the input's type, read from a uniform block (which the engine
  // rewrites before each frame).
  void resolveEngineValue(const KernelInput& input, const scene::MaterialBinding& binding) {
    const std::string& name = *binding.engineValue;
    const auto supplied = frameValue(name, FrameState{}, glm::mat4(1.0F));
    if (!supplied) {
      diags_.report(DiagCode::E7103, binding.valueRange,
                    fmt::format("'{}' is bound to the engine value '{}', which the engine does not supply; it "
                                "supplies {}",
                                input.component, name, supportedNames()));
    } else if (supplied->type != input.type.name) {
      diags_.report(DiagCode::E7103, binding.valueRange,
                    fmt::format("'{}' is a {}, but the engine value '{}' is a {}", input.component, input.type.name,
                                name, supplied->type));
    } else if (input.kind != InputKind::UniformMember) {
      diags_.report(DiagCode::E7103, binding.valueRange,
                    fmt::format("'{}' is not read from a uniform block; an engine value can be bound only to a "
                                "uniform (import it with uniformImport)",
                                input.component));
    } else {
      values_[input.component] = MaterialValue{{}, nullptr, "engine:" + name, name};
    }
  }

  void resolveBinding(const KernelInput& input, const scene::MaterialBinding& binding) {
    if (binding.engineValue) return resolveEngineValue(input, binding);
    if (input.type.kind == ValueType::Kind::Sampler) {
      if (!binding.texture) {
        diags_.report(
            DiagCode::E7103, binding.valueRange,
            fmt::format("'{}' is a {}: bind it to a texture name, not numbers", input.component, input.type.name));
        return;
      }
      if (const GpuTexture* texture = textureFor_(*binding.texture, binding.valueRange)) {
        values_[input.component] = MaterialValue{{}, texture, "texture:" + *binding.texture, {}};
      }
      return;
    }
    const ValueType* type = input.type.isNumeric() ? &input.type : nullptr;
    if (!type) {
      diags_.report(
          DiagCode::E7103, binding.valueRange,
          fmt::format("'{}' has type {}, which a scene file cannot supply", input.component, input.type.name));
      return;
    }
    if (binding.texture) {
      diags_.report(DiagCode::E7103, binding.valueRange,
                    fmt::format("'{}' is a {}: bind it to {} number{}, not a texture", input.component, input.type.name,
                                type->componentCount(), type->componentCount() == 1 ? "" : "s"));
      return;
    }
    if (binding.numbers.size() != type->componentCount()) {
      diags_.report(
          DiagCode::E7103, binding.valueRange,
          fmt::format("'{}' is a {} and needs {} number{}, but the value has {}", input.component, input.type.name,
                      type->componentCount(), type->componentCount() == 1 ? "" : "s", binding.numbers.size()));
      return;
    }
    if (type->scalar != ValueType::Scalar::Float) {
      for (double n : binding.numbers) {
        if (n != std::floor(n) || (type->scalar == ValueType::Scalar::Uint && n < 0)) {
          diags_.report(DiagCode::E7103, binding.valueRange,
                        fmt::format("'{}' is a {}: {} is not a valid component", input.component, input.type.name, n));
          return;
        }
      }
    }
    std::string identity = "numbers:";
    for (double n : binding.numbers) identity += fmt::format("{},", n);
    values_[input.component] = MaterialValue{binding.numbers, nullptr, std::move(identity), {}};
  }

  const VariantProgram& program_;
  const scene::InstanceDesc& instance_;
  const TextureLookup& textureFor_;
  DiagnosticList& diags_;
  MaterialValues values_;
  std::set<std::string, std::less<>> used_;
};

}  // namespace

ResolvedMaterial resolveMaterial(const VariantProgram& program, const scene::InstanceDesc& instance,
                                 const TextureLookup& textureFor, DiagnosticList& diags) {
  return MaterialResolver(program, instance, textureFor, diags).resolve();
}

void reportUnreadBindings(const scene::InstanceDesc& instance, const std::set<std::string, std::less<>>& read,
                          DiagnosticList& diags) {
  for (const scene::MaterialBinding& binding : instance.material) {
    if (read.contains(binding.component)) continue;
    diags.reportOnce(DiagCode::W7101, binding.keyRange,
                     fmt::format("'{}' is not an input of any variant of '{}' rendered; the value is ignored",
                                 binding.component, instance.shader));
  }
}

}  // namespace spire::engine
