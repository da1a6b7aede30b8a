#include "shaders.h"

#include <string>

namespace vdg::render::detail::shaders {

// One triangle, (-1, -1) (3, -1) (-1, 3) in clip space, covers the whole viewport; no vertex
// attributes. v_uv runs from (0, 0) at the viewport's top-left corner to (1, 1) at its bottom-right
// corner: the texture's rows are uploaded as stored (the picture's top row at t = 0), so the
// picture appears upright in the image readPixels returns (rows top-down).
const char* const kBackdropVertex = R"(#version 330 core
out vec2 v_uv;
void main() {
  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
  v_uv = vec2(p.x + 1.0, 1.0 - p.y) * 0.5;
  gl_Position = vec4(p, 0.0, 1.0);
}
)";

// colour = mix(paper, texel, opacity * texel alpha), opaque.
const char* const kBackdropFragment = R"(#version 330 core
in vec2 v_uv;
uniform sampler2D u_image;
uniform vec3 u_paper;
uniform float u_opacity;
out vec4 o_color;
void main() {
  vec4 texel = texture(u_image, v_uv);
  o_color = vec4(mix(u_paper, texel.rgb, u_opacity * texel.a), 1.0);
}
)";

// The mesh's vertex stage without its main(): the attributes, the outputs, and meshVertex() (the
// eye-space position, normal, uv and colour; returns the clip position), shared by kMeshVertex and
// kDrawingVertex.
const char* const kMeshVertexStage = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
uniform mat4 u_view;
uniform mat4 u_proj;
out vec3 v_pos;
out vec3 v_normal;
out vec2 v_uv;
flat out vec3 v_color;
vec4 meshVertex() {
  vec4 p = u_view * vec4(a_position, 1.0);
  v_pos = p.xyz;
  v_normal = mat3(u_view) * a_normal;
  v_uv = a_uv;
  v_color = vec3(1.0);
  return u_proj * p;
}
)";
// Built at start-up from the shared part (a shader's text is read only when a renderer links it).
const std::string kMeshVertexText = std::string(kMeshVertexStage) + "void main() { gl_Position = meshVertex(); }\n";
const char* const kMeshVertex = kMeshVertexText.c_str();

// C = ka*Cbase + max(0, l1.n)(Cwarm - Cbase*k1)*k2 + max(0, l2.n)(Ccool - Cbase*k3)*k4
// (Rademacher 99, section 3.2.4; the same expression as shade() in shading.cpp). A textured
// surface has Cbase = u_base x texel; with u_instance_base (the GPU blend's faces without a
// material) Cbase is the instance's colour v_color. With u_hue_rule the constants are u_k
// adjusted by the hue of that Cbase, per fragment: hsv() and hueAdjusted() are toHsv() and
// hueAdjustedConstants() of shading.cpp, line for line (the render tests compare them).
// The fragment stage's declarations and shade() (the lighting equation's colour of the fragment),
// shared by kMeshFragment and kDrawingFragment.
const char* const kMeshShade = R"(#version 330 core
in vec3 v_pos;
in vec3 v_normal;
in vec2 v_uv;
flat in vec3 v_color;
uniform vec3 u_base;
uniform vec3 u_warm;
uniform vec3 u_cool;
uniform vec3 u_light_warm;
uniform vec3 u_light_cool;
uniform float u_ka;
uniform vec4 u_k;
uniform int u_flat;
uniform int u_textured;
uniform int u_hue_rule;
uniform int u_instance_base;
uniform sampler2D u_texture;
out vec4 o_color;

vec3 hsv(vec3 c) {
  float mx = max(c.r, max(c.g, c.b));
  float mn = min(c.r, min(c.g, c.b));
  float delta = mx - mn;
  vec3 o = vec3(0.0, mx > 0.0 ? delta / mx : 0.0, mx);
  if (delta <= 0.0) return o;
  float h;
  if (mx == c.r) {
    h = 60.0 * mod((c.g - c.b) / delta, 6.0);
  } else if (mx == c.g) {
    h = 60.0 * ((c.b - c.r) / delta + 2.0);
  } else {
    h = 60.0 * ((c.r - c.g) / delta + 4.0);
  }
  if (h < 0.0) h += 360.0;
  o.x = h;
  return o;
}

// k = (k1, k2, k3, k4).
vec4 hueAdjusted(vec4 k, vec3 base) {
  vec3 c = hsv(base);
  vec4 o = k;
  if (c.y < 0.2) {
    o.y = 0.0;
  } else if (c.x >= 250.0 && c.x < 330.0) {
    o.w = 2.0 * k.w;
    o.y = 0.25 * k.y;
  } else if (c.x < 20.0 || c.x >= 330.0) {
    o.w = 1.5 * k.w;
    o.y = 0.5 * k.y;
  }
  if (c.z < 0.5) {
    float t = max(0.0, (c.z - 0.2) / (0.5 - 0.2));
    o.y *= t;
    o.w *= t;
  }
  return o;
}

vec3 shade() {
  vec3 n;
  if (u_flat != 0) {
    n = normalize(cross(dFdx(v_pos), dFdy(v_pos)));
  } else {
    float len = length(v_normal);
    n = len > 1e-20 ? v_normal / len : vec3(0.0, 0.0, 1.0);
    if (!gl_FrontFacing) n = -n;
  }
  vec3 base = u_instance_base != 0 ? v_color : u_base;
  vec4 k = u_k;
  if (u_textured != 0) base *= texture(u_texture, vec2(v_uv.x, 1.0 - v_uv.y)).rgb;
  if (u_hue_rule != 0) k = hueAdjusted(k, base);
  float d1 = max(dot(u_light_warm, n), 0.0);
  float d2 = max(dot(u_light_cool, n), 0.0);
  vec3 c = u_ka * base + d1 * (u_warm - base * k.x) * k.y + d2 * (u_cool - base * k.z) * k.w;
  return clamp(c, 0.0, 1.0);
}
)";

// Built at start-up from the shared part (a shader's text is read only when a renderer links it).
const std::string kMeshFragmentText = std::string(kMeshShade) + R"(
void main() { o_color = vec4(shade(), 1.0); }
)";
const char* const kMeshFragment = kMeshFragmentText.c_str();

// The mesh's vertex stage plus each slot's projective texture coordinates and visibility (s, t, q,
// visible), passed on as they are (interpolated perspective-correct, so (s/q, t/q) per fragment is
// the drawing's projection; vdg/render/drawing_textures.h).
const std::string kDrawingVertexText = std::string(kMeshVertexStage) + R"(
layout(location = 3) in vec4 a_drawing0;
layout(location = 4) in vec4 a_drawing1;
layout(location = 5) in vec4 a_drawing2;
out vec4 v_drawing0;
out vec4 v_drawing1;
out vec4 v_drawing2;
void main() {
  v_drawing0 = a_drawing0;
  v_drawing1 = a_drawing1;
  v_drawing2 = a_drawing2;
  gl_Position = meshVertex();
}
)";
const char* const kDrawingVertex = kDrawingVertexText.c_str();

// blendDrawingColors of drawing_textures.cpp: a_i = w_i v_i alpha_i, colour = (sum a_i rgb_i + w_b
// shade()) / (sum a_i + w_b), or shade() where that sum is <= 1e-6. The texture is sampled outside
// any branch (its mipmap level needs the derivatives of uv).
const std::string kDrawingFragmentText = std::string(kMeshShade) + R"(
in vec4 v_drawing0;
in vec4 v_drawing1;
in vec4 v_drawing2;
uniform sampler2D u_drawing0;
uniform sampler2D u_drawing1;
uniform sampler2D u_drawing2;
uniform vec4 u_drawing_weights;
vec4 drawingLayer(sampler2D image, vec4 d, float w) {
  vec2 uv = d.xy / max(d.z, 1e-20);
  vec4 texel = texture(image, uv);
  float a = d.z > 0.0 ? w * clamp(d.w, 0.0, 1.0) * texel.a : 0.0;
  return vec4(texel.rgb * a, a);
}
void main() {
  vec3 shaded = shade();
  vec4 sum = drawingLayer(u_drawing0, v_drawing0, u_drawing_weights.x) +
             drawingLayer(u_drawing1, v_drawing1, u_drawing_weights.y) +
             drawingLayer(u_drawing2, v_drawing2, u_drawing_weights.z);
  float total = sum.a + u_drawing_weights.w;
  vec3 c = total > 1e-6 ? (sum.rgb + u_drawing_weights.w * shaded) / total : shaded;
  o_color = vec4(c, 1.0);
}
)";
const char* const kDrawingFragment = kDrawingFragmentText.c_str();

// u_pixel_scale: size of one pixel in world units at view depth d is x * d + y.
const char* const kStrokeVertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
uniform mat4 u_view;
uniform mat4 u_proj;
uniform vec2 u_pixel_scale;
uniform float u_pull;
uniform int u_ortho;
uniform float u_point_size;
void main() {
  vec4 p = u_view * vec4(a_position, 1.0);
  float pixel = u_pixel_scale.x * (-p.z) + u_pixel_scale.y;
  vec3 towards_eye = u_ortho != 0 ? vec3(0.0, 0.0, 1.0) : -normalize(p.xyz);
  p.xyz += towards_eye * (u_pull * pixel);
  gl_Position = u_proj * p;
  gl_PointSize = u_point_size;
}
)";

const char* const kLineGeometry = R"(#version 330 core
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;
uniform vec2 u_viewport;
uniform float u_width;
void main() {
  vec4 a = gl_in[0].gl_Position;
  vec4 b = gl_in[1].gl_Position;
  if (a.w <= 0.0 || b.w <= 0.0) return;
  vec2 half_vp = 0.5 * u_viewport;
  vec2 d = (b.xy / b.w - a.xy / a.w) * half_vp;
  float len = length(d);
  d = len > 1e-6 ? d / len : vec2(1.0, 0.0);
  vec2 n = vec2(-d.y, d.x) * (0.5 * u_width) / half_vp;
  gl_Position = vec4(a.xy + n * a.w, a.zw); EmitVertex();
  gl_Position = vec4(a.xy - n * a.w, a.zw); EmitVertex();
  gl_Position = vec4(b.xy + n * b.w, b.zw); EmitVertex();
  gl_Position = vec4(b.xy - n * b.w, b.zw); EmitVertex();
  EndPrimitive();
}
)";

const char* const kLineFragment = R"(#version 330 core
uniform vec3 u_color;
out vec4 o_color;
void main() { o_color = vec4(u_color, 1.0); }
)";

// Round dot with an anti-aliased rim (alpha to coverage).
const char* const kDotFragment = R"(#version 330 core
uniform vec3 u_color;
out vec4 o_color;
void main() {
  float r = length(gl_PointCoord * 2.0 - 1.0);
  if (r > 1.0) discard;
  float rim = max(fwidth(r), 1e-4);
  o_color = vec4(u_color, clamp((1.0 - r) / rim, 0.0, 1.0));
}
)";

// ---------------------------------------------------------------------------------------------
// GPU blend (GLSL 4.30). Buffers are float / int arrays (std430, no vec3 padding); a batch holds
// instances [u_first_instance, u_first_instance + gl_WorkGroupID.y / gl_InstanceID], and its
// blended positions (#V x 3 per instance, world space) and group normals (#G x 3) are indexed by
// the instance's place in the batch.

#define VDG_INSTANCE_BLOCK \
  "struct Instance {\n"    \
  "  mat4 object;\n"       \
  "  ivec4 keys;\n"        \
  "  vec4 weights;\n"      \
  "  vec4 color;\n"        \
  "};\n"                   \
  "layout(std430, binding = 2) readonly buffer Instances { Instance instances[]; };\n"

// Pass 1: p = object * (base + sum_i w_i delta_i) (Rademacher 99, section 3.2.3).
const char* const kBlendCompute =
    "#version 430 core\n"
    "layout(local_size_x = 64) in;\n" VDG_INSTANCE_BLOCK R"(
layout(std430, binding = 0) readonly buffer Base { float base[]; };
layout(std430, binding = 1) readonly buffer Deltas { float deltas[]; };
layout(std430, binding = 3) writeonly buffer Positions { float positions[]; };
uniform int u_vertex_count;
uniform int u_first_instance;
uniform int u_item_offset;
void main() {
  int v = u_item_offset + int(gl_GlobalInvocationID.x);
  if (v >= u_vertex_count) return;
  int local = int(gl_WorkGroupID.y);
  Instance ins = instances[u_first_instance + local];
  vec3 p = vec3(base[3 * v], base[3 * v + 1], base[3 * v + 2]);
  for (int s = 0; s < 3; ++s) {
    int k = ins.keys[s];
    float w = ins.weights[s];
    if (k < 0 || w == 0.0) continue;
    int d = 3 * (k * u_vertex_count + v);
    p += w * vec3(deltas[d], deltas[d + 1], deltas[d + 2]);
  }
  vec3 q = (ins.object * vec4(p, 1.0)).xyz;
  int o = 3 * (local * u_vertex_count + v);
  positions[o] = q.x;
  positions[o + 1] = q.y;
  positions[o + 2] = q.z;
}
)";

// Pass 2: the normal of each smoothing group, computeGroupNormals's rule as a gather: the
// unnormalised cross products of the faces listed for the group (once per corner in it), summed
// and normalised ((0, 0, 0) for a zero sum).
const char* const kNormalsCompute = R"(#version 430 core
layout(local_size_x = 64) in;
layout(std430, binding = 3) readonly buffer Positions { float positions[]; };
layout(std430, binding = 4) readonly buffer Triangles { int triangles[]; };
layout(std430, binding = 5) readonly buffer GroupStart { int group_start[]; };
layout(std430, binding = 6) readonly buffer GroupFaces { int group_faces[]; };
layout(std430, binding = 7) writeonly buffer Normals { float normals[]; };
uniform int u_vertex_count;
uniform int u_group_count;
uniform int u_item_offset;
vec3 at(int first, int v) { int i = 3 * (first + v); return vec3(positions[i], positions[i + 1], positions[i + 2]); }
void main() {
  int g = u_item_offset + int(gl_GlobalInvocationID.x);
  if (g >= u_group_count) return;
  int local = int(gl_WorkGroupID.y);
  int first = local * u_vertex_count;
  vec3 n = vec3(0.0);
  for (int j = group_start[g]; j < group_start[g + 1]; ++j) {
    int f = 3 * group_faces[j];
    vec3 a = at(first, triangles[f]);
    n += cross(at(first, triangles[f + 1]) - a, at(first, triangles[f + 2]) - a);
  }
  float len = length(n);
  if (len > 0.0) n /= len;
  int o = 3 * (local * u_group_count + g);
  normals[o] = n.x;
  normals[o + 1] = n.y;
  normals[o + 2] = n.z;
}
)";

// Pass 3: silhouette, border and crease edges (faceFacing, silhouetteEdges and creaseEdges of
// silhouette.cpp, per instance). Each found edge appends its two vertices' places in the batch's
// position buffer to its list; the list's count is the `count` of its indirect draw command
// (commands[0..4]: silhouettes and borders, growing up from index 0; commands[5..9]: creases,
// growing down from index u_capacity; an edge is in one list at most, so u_capacity = 2 x edges
// x instances holds both). kCreaseStartCompute then sets the crease command's first index.
const char* const kEdgesCompute = R"(#version 430 core
layout(local_size_x = 64) in;
layout(std430, binding = 3) readonly buffer Positions { float positions[]; };
layout(std430, binding = 4) readonly buffer Triangles { int triangles[]; };
layout(std430, binding = 8) readonly buffer Edges { ivec4 edges[]; };
layout(std430, binding = 9) buffer Commands { uint commands[]; };
layout(std430, binding = 10) writeonly buffer Strokes { uint strokes[]; };
uniform int u_vertex_count;
uniform int u_edge_count;
uniform vec3 u_eye;
uniform int u_silhouettes;
uniform int u_borders;
uniform int u_creases;
uniform float u_cos_crease;
uniform uint u_capacity;
uniform int u_item_offset;
vec3 at(int first, int v) { int i = 3 * (first + v); return vec3(positions[i], positions[i + 1], positions[i + 2]); }
// (v1 - v0) x (v2 - v0) of face f, and whether it faces the eye.
vec3 faceCross(int first, int f, out bool front) {
  vec3 a = at(first, triangles[3 * f]);
  vec3 n = cross(at(first, triangles[3 * f + 1]) - a, at(first, triangles[3 * f + 2]) - a);
  front = dot(n, u_eye - a) > 0.0;
  return n;
}
void main() {
  int e = u_item_offset + int(gl_GlobalInvocationID.x);
  if (e >= u_edge_count) return;
  int first = int(gl_WorkGroupID.y) * u_vertex_count;
  ivec4 edge = edges[e];
  bool front0, front1;
  vec3 n0 = faceCross(first, edge.z, front0);
  uint slot;
  if (edge.w < 0) {
    if (u_silhouettes == 0 || u_borders == 0) return;
    slot = atomicAdd(commands[0], 2u);
  } else {
    vec3 n1 = faceCross(first, edge.w, front1);
    if (front0 != front1) {
      if (u_silhouettes == 0) return;
      slot = atomicAdd(commands[0], 2u);
    } else {
      float scale = length(n0) * length(n1);
      if (u_creases == 0 || !front0 || !(scale > 0.0) || dot(n0, n1) >= u_cos_crease * scale) return;
      slot = u_capacity - 2u - atomicAdd(commands[5], 2u);
    }
  }
  strokes[slot] = uint(first + edge.x);
  strokes[slot + 1u] = uint(first + edge.y);
}
)";

const char* const kCreaseStartCompute = R"(#version 430 core
layout(local_size_x = 1) in;
layout(std430, binding = 9) buffer Commands { uint commands[]; };
uniform uint u_capacity;
void main() { commands[7] = u_capacity - commands[5]; }
)";

// The instanced draw of a batch: render vertex (vertex, group) of instance gl_InstanceID.
const char* const kBlendVertex = R"(#version 430 core
layout(location = 0) in ivec2 a_ref;
layout(location = 2) in vec2 a_uv;
)" VDG_INSTANCE_BLOCK R"(
layout(std430, binding = 3) readonly buffer Positions { float positions[]; };
layout(std430, binding = 7) readonly buffer Normals { float normals[]; };
uniform mat4 u_view;
uniform mat4 u_proj;
uniform int u_vertex_count;
uniform int u_group_count;
uniform int u_first_instance;
out vec3 v_pos;
out vec3 v_normal;
out vec2 v_uv;
flat out vec3 v_color;
void main() {
  int i = 3 * (gl_InstanceID * u_vertex_count + a_ref.x);
  int n = 3 * (gl_InstanceID * u_group_count + a_ref.y);
  vec4 p = u_view * vec4(positions[i], positions[i + 1], positions[i + 2], 1.0);
  v_pos = p.xyz;
  v_normal = mat3(u_view) * vec3(normals[n], normals[n + 1], normals[n + 2]);
  v_uv = a_uv;
  v_color = instances[u_first_instance + gl_InstanceID].color.rgb;
  gl_Position = u_proj * p;
}
)";

#undef VDG_INSTANCE_BLOCK

}  // namespace vdg::render::detail::shaders
