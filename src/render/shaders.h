// GLSL sources of the renderer (private to the render module), GLSL 3.30 core.
#pragma once

namespace vdg::render::shaders {

// Shaded surface: the lighting equation of Rademacher 99, section 3.2.4.
extern const char* const kMeshVertex;
extern const char* const kMeshFragment;
// Thick lines (geometry-shader quads) and round dots (point sprites), pulled towards the eye.
extern const char* const kStrokeVertex;
extern const char* const kLineGeometry;
extern const char* const kLineFragment;
extern const char* const kDotFragment;

}  // namespace vdg::render::shaders
