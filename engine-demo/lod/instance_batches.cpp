#include "lod/instance_batches.h"

#include <glm/geometric.hpp>

#include <algorithm>

namespace spire::lod {

std::array<glm::vec4, 6> frustumPlanes(const glm::mat4& m) {
  const glm::vec4 row0(m[0][0], m[1][0], m[2][0], m[3][0]);
  const glm::vec4 row1(m[0][1], m[1][1], m[2][1], m[3][1]);
  const glm::vec4 row2(m[0][2], m[1][2], m[2][2], m[3][2]);
  const glm::vec4 row3(m[0][3], m[1][3], m[2][3], m[3][3]);
  std::array<glm::vec4, 6> planes = {row3 + row0, row3 - row0, row3 + row1, row3 - row1, row2, row3 - row2};
  for (glm::vec4& p : planes) p /= glm::length(glm::vec3(p));
  return planes;
}

bool sphereVisible(const std::array<glm::vec4, 6>& planes, const glm::vec3& center, float radius) {
  return std::all_of(planes.begin(), planes.end(),
                     [&](const glm::vec4& p) { return glm::dot(glm::vec3(p), center) + p.w >= -radius; });
}

InstanceBatcher::InstanceBatcher(DrawGroups groups, uint32_t blockCount)
    : groups_(std::move(groups)), blockCount_(std::max(blockCount, 1U)) {}

void InstanceBatcher::add(const SceneInstance& instance, uint32_t index, const LodSelector& selector) {
  LevelDraw draws[2];
  uint32_t n = selector.draws(index, draws);
  if (n == 2 && !groups_.canFade(groups_.groupOf[instance.prototype][draws[1].level])) {
    draws[0] = {draws[1].level, 1.0F};
    n = 1;
  }
  for (uint32_t d = 0; d < n; ++d) {
    const uint32_t group = groups_.groupOf[instance.prototype][draws[d].level];
    const uint32_t block = draws[d].fade < 1.0F ? blockCount_ + instance.block : instance.block;
    const uint32_t bucket = block * groups_.groupCount + group;
    entries_.push_back({bucket, groups_.meshOf[instance.prototype], {index, draws[d].fade}});
  }
}

void InstanceBatcher::build(std::span<const SceneInstance> instances, const LodSelector& selector,
                            const glm::mat4& viewProj, FrameBatches& out, std::span<const uint32_t> subset) {
  const std::array<glm::vec4, 6> planes = frustumPlanes(viewProj);
  entries_.clear();
  out.visibleInstances = 0;
  const auto consider = [&](uint32_t i) {
    if (!sphereVisible(planes, instances[i].bounds.center, instances[i].bounds.radius)) return;
    ++out.visibleInstances;
    add(instances[i], i, selector);
  };
  if (subset.empty()) {
    for (uint32_t i = 0; i < instances.size(); ++i) consider(i);
  } else {
    for (uint32_t i : subset) consider(i);
  }
  // A counting sort by (block, group), then by mesh within each: the
  // buckets are few, so this is linear where a comparison sort is not.
  counts_.assign(size_t{2} * blockCount_ * groups_.groupCount + 1, 0);
  for (const Entry& e : entries_) ++counts_[e.bucket + 1];
  for (size_t b = 1; b < counts_.size(); ++b) counts_[b] += counts_[b - 1];
  sorted_.resize(entries_.size());
  std::vector<uint32_t>& next = counts_;
  for (const Entry& e : entries_) sorted_[next[e.bucket]++] = e;
  // next[b] is now the end of bucket b; sort each bucket's meshes.
  uint32_t begin = 0;
  for (uint32_t end : next) {
    if (end - begin > 1) {
      std::stable_sort(sorted_.begin() + begin, sorted_.begin() + end,
                       [](const Entry& a, const Entry& b) { return a.mesh < b.mesh; });
    }
    begin = std::max(begin, end);
  }
  emit(out);
}

void InstanceBatcher::emit(FrameBatches& out) const {
  out.batches.clear();
  out.draws.clear();
  out.records.resize(groups_.groupCount);
  for (auto& records : out.records) records.clear();
  for (size_t i = 0; i < sorted_.size(); ++i) {
    const Entry& e = sorted_[i];
    const uint32_t group = e.bucket % groups_.groupCount;
    const bool newBatch = i == 0 || sorted_[i - 1].bucket != e.bucket;
    if (newBatch) {
      const uint32_t block = e.bucket / groups_.groupCount;
      const bool overlay = block >= blockCount_;
      out.batches.push_back(
          {overlay ? block - blockCount_ : block, group, overlay, static_cast<uint32_t>(out.draws.size()), 0});
    }
    if (newBatch || sorted_[i - 1].mesh != e.mesh) {
      out.draws.push_back({e.mesh, static_cast<uint32_t>(out.records[group].size()), 0});
      ++out.batches.back().drawCount;
    }
    out.records[group].push_back(e.record);
    ++out.draws.back().instanceCount;
  }
}

}  // namespace spire::lod
