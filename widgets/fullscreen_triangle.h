#pragma once
// The vertex shader both panorama views draw with: one triangle covering the viewport, passing each
// fragment its normalised device coordinates (x, y in [-1, 1]) as `ndc`; attribute 0 is `corner`.
namespace plenopath::widgets {

inline constexpr const char* kFullscreenTriangleVertexShader = R"(#version 150
in vec2 corner;
out vec2 ndc;
void main() {
  ndc = corner;
  gl_Position = vec4(corner, 0.0, 1.0);
}
)";

}  // namespace plenopath::widgets
