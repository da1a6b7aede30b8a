// GLSL sources of the renderer (private to the render module), GLSL 3.30 core; the GPU blend's
// are GLSL 4.30 (compute shaders, storage buffers) and use kMeshFragment with its version line
// raised to 4.30.
#pragma once

namespace vdg::render::detail::shaders {

// Shaded surface: the lighting equation of Rademacher 99, section 3.2.4.
extern const char* const kMeshVertex;
extern const char* const kMeshFragment;
// The shaded surface with the reference drawings blended over it (vdg/render/drawing_textures.h).
extern const char* const kDrawingVertex;
extern const char* const kDrawingFragment;
// Thick lines (geometry-shader quads) and round dots (point sprites), pulled towards the eye.
extern const char* const kStrokeVertex;
extern const char* const kLineGeometry;
extern const char* const kLineFragment;
extern const char* const kDotFragment;
// Backdrop image: one triangle covering the viewport, the image stretched over it and blended
// with the paper colour (Renderer::drawBackdrop).
extern const char* const kBackdropVertex;
extern const char* const kBackdropFragment;
// GPU blend: blend, group normals and edges (compute), and the instanced draw's vertex stage.
extern const char* const kBlendCompute;
extern const char* const kNormalsCompute;
extern const char* const kEdgesCompute;
extern const char* const kCreaseStartCompute;
extern const char* const kBlendVertex;

}  // namespace vdg::render::detail::shaders
