#include "shaders.h"

namespace vdg::render::shaders {

const char* const kMeshVertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
uniform mat4 u_view;
uniform mat4 u_proj;
out vec3 v_pos;
out vec3 v_normal;
out vec2 v_uv;
void main() {
  vec4 p = u_view * vec4(a_position, 1.0);
  v_pos = p.xyz;
  v_normal = mat3(u_view) * a_normal;
  v_uv = a_uv;
  gl_Position = u_proj * p;
}
)";

// C = ka*Cbase + max(0, l1.n)(Cwarm - Cbase*k1)*k2 + max(0, l2.n)(Ccool - Cbase*k3)*k4
// (Rademacher 99, section 3.2.4; the same expression as shade() in shading.cpp). A textured
// surface has Cbase = u_base x texel, and with u_hue_rule the constants are u_k adjusted by the
// hue of that Cbase, per fragment: hsv() and hueAdjusted() are toHsv() and
// hueAdjustedConstants() of shading.cpp, line for line (the render tests compare them).
const char* const kMeshFragment = R"(#version 330 core
in vec3 v_pos;
in vec3 v_normal;
in vec2 v_uv;
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
    if (c.z > 0.6) o.y = 0.0;
    return o;
  }
  if (c.x >= 250.0 && c.x < 330.0) {
    o.w = 2.0 * k.w;
  } else if (c.x < 20.0 || c.x >= 330.0) {
    o.w = 1.5 * k.w;
    o.y = 0.5 * k.y;
  }
  return o;
}

void main() {
  vec3 n;
  if (u_flat != 0) {
    n = normalize(cross(dFdx(v_pos), dFdy(v_pos)));
  } else {
    float len = length(v_normal);
    n = len > 1e-20 ? v_normal / len : vec3(0.0, 0.0, 1.0);
    if (!gl_FrontFacing) n = -n;
  }
  vec3 base = u_base;
  vec4 k = u_k;
  if (u_textured != 0) {
    base *= texture(u_texture, vec2(v_uv.x, 1.0 - v_uv.y)).rgb;
    if (u_hue_rule != 0) k = hueAdjusted(k, base);
  }
  float d1 = max(dot(u_light_warm, n), 0.0);
  float d2 = max(dot(u_light_cool, n), 0.0);
  vec3 c = u_ka * base + d1 * (u_warm - base * k.x) * k.y + d2 * (u_cool - base * k.z) * k.w;
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
