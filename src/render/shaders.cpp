#include "shaders.h"

namespace vdg::render::shaders {

const char* const kMeshVertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_view;
uniform mat4 u_proj;
out vec3 v_pos;
out vec3 v_normal;
void main() {
  vec4 p = u_view * vec4(a_position, 1.0);
  v_pos = p.xyz;
  v_normal = mat3(u_view) * a_normal;
  gl_Position = u_proj * p;
}
)";

// C = ka*Cbase + max(0, l1.n)(Cwarm - Cbase*k1)*k2 + max(0, l2.n)(Ccool - Cbase*k3)*k4
// (Rademacher 99, section 3.2.4; the same expression as shade() in shading.cpp).
const char* const kMeshFragment = R"(#version 330 core
in vec3 v_pos;
in vec3 v_normal;
uniform vec3 u_base;
uniform vec3 u_warm;
uniform vec3 u_cool;
uniform vec3 u_light_warm;
uniform vec3 u_light_cool;
uniform float u_ka;
uniform vec4 u_k;
uniform int u_flat;
out vec4 o_color;
void main() {
  vec3 n;
  if (u_flat != 0) {
    n = normalize(cross(dFdx(v_pos), dFdy(v_pos)));
  } else {
    float len = length(v_normal);
    n = len > 1e-20 ? v_normal / len : vec3(0.0, 0.0, 1.0);
    if (!gl_FrontFacing) n = -n;
  }
  float d1 = max(dot(u_light_warm, n), 0.0);
  float d2 = max(dot(u_light_cool, n), 0.0);
  vec3 c = u_ka * u_base + d1 * (u_warm - u_base * u_k.x) * u_k.y + d2 * (u_cool - u_base * u_k.z) * u_k.w;
  o_color = vec4(clamp(c, 0.0, 1.0), 1.0);
}
)";

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

}  // namespace vdg::render::shaders
