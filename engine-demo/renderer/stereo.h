// Stereo frames (paper section 7.3): Vertex and Fragment run once per eye,
// and object-space work can run once per frame for both. Each eye renders
// into the frame's ordinary target, so screen-space work (gl_FragCoord, the
// multi-rate pass) sees an ordinary frame; the two eyes' images are then put
// side by side, the left eye on the left.
#pragma once

#include <array>

#include "renderer/render_target.h"
#include "scene/scene_file.h"

namespace spire::engine {

// The left and right eyes of `view`: moved by half `separation` each way
// along the camera's right vector (view direction x up), both targets moved
// likewise, so the eyes look parallel.
std::array<scene::CameraView, 2> eyeViews(const scene::CameraView& view, const glm::vec3& up, float separation);

// Two images of one size side by side, `left` on the left: color and coverage.
measure::FloatImage sideBySide(const measure::FloatImage& left, const measure::FloatImage& right);
std::vector<uint8_t> sideBySide(const std::vector<uint8_t>& left, const std::vector<uint8_t>& right, uint32_t width);

}  // namespace spire::engine
