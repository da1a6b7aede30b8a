// The page's look: the warm/cool lighting of Rademacher 99, section 3.2.4 (after Gooch et al. 98),
//   C = ka Cbase + (l1.n)(Cwarm - Cbase k1) k2 + (l2.n)(Ccool - Cbase k3) k4,
// with k1..k4 varied by the hue of Cbase as src/render/shading.cpp does, and outlines drawn as an
// inverted hull (back faces pushed out along the normal by a fixed number of pixels), in the spirit
// of the paper's back-face silhouettes (section 3.2.4, after Raskar 99). Both materials use three's
// morph target and skinning chunks, so they show exactly the shape the runtime's weights make.
import * as THREE from 'three';

// The constants of src/render/shading.h's ShadingParams (paper: ka = 0.9, k1..k4 = 1).
export const SHADING = {
  ka: 0.9,
  warm: [1.0, 0.8, 0.5],
  cool: [0.55, 0.62, 0.85],
  lightWarm: [-0.6, 0.6, 0.5], // camera space, towards the light
  lightCool: [0.75, -0.35, 0.35],
};

const VERTEX_HEAD = /* glsl */ `
#include <common>
#include <batching_pars_vertex>
#include <uv_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
`;

// Everything up to and including three's projection: mvPosition, transformedNormal.
const VERTEX_BODY = /* glsl */ `
  #include <uv_vertex>
  #include <morphinstance_vertex>
  #include <batching_vertex>
  #include <beginnormal_vertex>
  #include <morphnormal_vertex>
  #include <skinbase_vertex>
  #include <skinnormal_vertex>
  #include <defaultnormal_vertex>
  #include <begin_vertex>
  #include <morphtarget_vertex>
  #include <skinning_vertex>
  #include <project_vertex>
`;

// The hue rules' thresholds, those of include/vdg/render/shading.h (kNeutralSaturation, kDarkValue,
// kLitValue): below the first saturation a colour is neutral; the lights fade out between the
// two values.
export const HUE_RULES = { neutralSaturation: 0.2, darkValue: 0.2, litValue: 0.5 };

const f32 = Math.fround;

/**
 * HSV of a colour, as src/render/shading.cpp's toHsv computes it: in 32-bit floats (every step
 * rounded with Math.fround), so that a colour on a rule's boundary falls on the same side as in
 * `vdg render`.
 * @param {number} r @param {number} g @param {number} b
 * @returns {{h: number, s: number, v: number}} hue in degrees [0, 360), saturation and value in [0, 1]
 */
export function toHsv(r, g, b) {
  [r, g, b] = [f32(r), f32(g), f32(b)];
  const mx = Math.max(r, g, b), mn = Math.min(r, g, b);
  const delta = f32(mx - mn);
  const out = { h: 0, s: mx > 0 ? f32(delta / mx) : 0, v: mx };
  if (delta <= 0) return out;
  let h;
  if (mx === r) {
    h = f32(60 * (f32(f32(g - b) / delta) % 6)); // % is C's fmod (the dividend's sign)
  } else if (mx === g) {
    h = f32(60 * f32(f32(f32(b - r) / delta) + 2));
  } else {
    h = f32(60 * f32(f32(f32(r - g) / delta) + 4));
  }
  if (h < 0) h = f32(h + 360);
  out.h = h;
  return out;
}

/**
 * The hue rules (Rademacher 99, section 3.2.4, and vdg's rules for neutral and dark colours; the
 * table in docs/render.md): the caller's k1..k4 adjusted for a base colour, as
 * src/render/shading.cpp's hueAdjustedConstants does, in 32-bit floats.
 *   neutral (saturation < 0.2): k2 = 0 (no warm light: cool whites and greys);
 *   purple (hue in [250, 330)): k4 = 2 k4, k2 = 0.25 k2;
 *   red (hue < 20 or >= 330): k4 = 1.5 k4, k2 = 0.5 k2;
 *   then dark (value < 0.5, any hue): k2 and k4 times t = max(0, (value - 0.2) / 0.3).
 * @param {number[]} k the caller's [k1, k2, k3, k4]
 * @param {number[]} rgb the base colour, each channel in [0, 1]
 * @returns {number[]} [k1, k2, k3, k4]
 */
export function hueAdjusted(k, rgb) {
  const { h, s, v } = toHsv(rgb[0], rgb[1], rgb[2]);
  const out = k.map(f32);
  const neutral = f32(HUE_RULES.neutralSaturation), dark = f32(HUE_RULES.darkValue), lit = f32(HUE_RULES.litValue);
  if (s < neutral) {
    out[1] = 0;
  } else if (h >= 250 && h < 330) {
    out[3] = f32(2 * out[3]);
    out[1] = f32(0.25 * out[1]);
  } else if (h < 20 || h >= 330) {
    out[3] = f32(1.5 * out[3]);
    out[1] = f32(0.5 * out[1]);
  }
  if (v < lit) {
    const t = Math.max(0, f32(f32(v - dark) / f32(lit - dark)));
    out[1] = f32(out[1] * t);
    out[3] = f32(out[3] * t);
  }
  return out;
}

/**
 * The k1..k4 of the hue rules for a base colour and the paper's k1..k4 = 1 (ShadingParams::k).
 * @param {THREE.Color} base
 * @returns {THREE.Vector4}
 */
export function hueConstants(base) {
  return new THREE.Vector4().fromArray(hueAdjusted([1, 1, 1, 1], [base.r, base.g, base.b]));
}

// The same rules in GLSL, for a textured material's Cbase = base colour x texel, a different colour
// at every fragment: src/render/shaders.cpp's hsv() and hueAdjusted(), which vdg render runs per
// texel, line for line.
const HUE_RULES_GLSL = /* glsl */ `
  vec3 vdgHsv(vec3 c) {
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
  vec4 vdgHueAdjusted(vec4 k, vec3 base) {
    vec3 c = vdgHsv(base);
    vec4 o = k;
    if (c.y < ${HUE_RULES.neutralSaturation.toFixed(3)}) {
      o.y = 0.0;
    } else if (c.x >= 250.0 && c.x < 330.0) {
      o.w = 2.0 * k.w;
      o.y = 0.25 * k.y;
    } else if (c.x < 20.0 || c.x >= 330.0) {
      o.w = 1.5 * k.w;
      o.y = 0.5 * k.y;
    }
    if (c.z < ${HUE_RULES.litValue.toFixed(3)}) {
      float t = max(0.0, (c.z - ${HUE_RULES.darkValue.toFixed(3)}) / ${(HUE_RULES.litValue - HUE_RULES.darkValue).toFixed(3)});
      o.y *= t;
      o.w *= t;
    }
    return o;
  }
`;

/**
 * The warm/cool material for one glTF material (its base colour and base colour texture).
 * @param {THREE.Material & {color?: THREE.Color, map?: THREE.Texture|null}} source
 * @returns {THREE.ShaderMaterial}
 */
export function warmCoolMaterial(source) {
  // glTF's baseColorFactor is linear; vdg render shades display (sRGB-encoded) values.
  const base = source.color ? source.color.clone().convertLinearToSRGB() : new THREE.Color(0.8, 0.8, 0.8);
  const map = source.map ?? null;
  if (map) map.colorSpace = THREE.NoColorSpace; // shade the texture's values as vdg render does
  const material = new THREE.ShaderMaterial({
    name: 'vdg warm/cool',
    uniforms: {
      uBase: { value: base },
      uK: { value: hueConstants(base) },
      uKa: { value: SHADING.ka },
      uWarm: { value: new THREE.Color().fromArray(SHADING.warm) },
      uCool: { value: new THREE.Color().fromArray(SHADING.cool) },
      uLightWarm: { value: new THREE.Vector3().fromArray(SHADING.lightWarm).normalize() },
      uLightCool: { value: new THREE.Vector3().fromArray(SHADING.lightCool).normalize() },
      uMap: { value: map },
      uHasMap: { value: map !== null },
    },
    vertexShader: `${VERTEX_HEAD}
      varying vec3 vNormalView;
      varying vec2 vTexCoord;
      void main() {
        ${VERTEX_BODY}
        vNormalView = normalize(transformedNormal);
        vTexCoord = uv;
      }`,
    fragmentShader: /* glsl */ `
      uniform vec3 uBase, uWarm, uCool, uLightWarm, uLightCool;
      uniform vec4 uK;
      uniform float uKa;
      uniform sampler2D uMap;
      uniform bool uHasMap;
      varying vec3 vNormalView;
      varying vec2 vTexCoord;
      ${HUE_RULES_GLSL}
      void main() {
        vec3 base = uBase;
        vec4 k = uK;
        if (uHasMap) {
          base *= texture2D(uMap, vTexCoord).rgb;
          k = vdgHueAdjusted(vec4(1.0), base); // per texel, as vdg render does
        }
        vec3 n = normalize(vNormalView);
        if (!gl_FrontFacing) n = -n;
        float d1 = max(dot(uLightWarm, n), 0.0), d2 = max(dot(uLightCool, n), 0.0);
        vec3 c = uKa * base + d1 * (uWarm - base * k.x) * k.y + d2 * (uCool - base * k.z) * k.w;
        gl_FragColor = vec4(clamp(c, 0.0, 1.0), 1.0);
      }`,
    side: THREE.FrontSide,
  });
  return material;
}

/**
 * The outline material: back faces pushed out by `pixels` (half the stroke) along the view-space
 * normal, so the outline keeps its width in pixels at any distance. `uPixel` (the view height of one
 * pixel at distance 1) is set each frame by setOutlinePixel.
 * @param {number} pixels
 * @returns {THREE.ShaderMaterial}
 */
export function outlineMaterial(pixels) {
  return new THREE.ShaderMaterial({
    name: 'vdg outline',
    uniforms: { uPixels: { value: pixels }, uPixel: { value: 0.002 } },
    vertexShader: `${VERTEX_HEAD}
      uniform float uPixels, uPixel;
      void main() {
        ${VERTEX_BODY}
        vec3 n = normalize(transformedNormal);
        #ifdef FLIP_SIDED
          n = -n; // three flips the normals of a back-side material; the hull grows outwards
        #endif
        mvPosition.xyz += n * uPixels * uPixel * max(-mvPosition.z, 0.0);
        gl_Position = projectionMatrix * mvPosition;
      }`,
    fragmentShader: /* glsl */ `void main() { gl_FragColor = vec4(0.08, 0.08, 0.1, 1.0); }`,
    side: THREE.BackSide,
  });
}

/**
 * Sets the outline materials' pixel size for a perspective camera rendering `height` pixels.
 * @param {THREE.ShaderMaterial[]} materials
 * @param {THREE.PerspectiveCamera} camera
 * @param {number} height
 */
export function setOutlinePixel(materials, camera, height) {
  const pixel = (2 * Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2)) / Math.max(1, height);
  for (const m of materials) m.uniforms.uPixel.value = pixel;
}

/**
 * Gives every mesh under `root` the warm/cool material and an outline: the geometry is drawn twice
 * (two groups over all of it), so both passes use the same morph weights the runtime sets.
 * @param {THREE.Object3D} root
 * @param {number} pixels outline half width in pixels
 * @returns {THREE.ShaderMaterial[]} the outline materials (for setOutlinePixel)
 */
export function styleModel(root, pixels) {
  /** @type {THREE.ShaderMaterial[]} */
  const outlines = [];
  root.traverse((object) => {
    const mesh = /** @type {THREE.Mesh} */ (object);
    if (!mesh.isMesh) return;
    const geometry = mesh.geometry;
    const count = geometry.index ? geometry.index.count : geometry.attributes.position.count;
    const source = Array.isArray(mesh.material) ? mesh.material[0] : mesh.material;
    const outline = outlineMaterial(pixels);
    outlines.push(outline);
    geometry.clearGroups();
    geometry.addGroup(0, count, 0);
    geometry.addGroup(0, count, 1);
    mesh.material = [warmCoolMaterial(/** @type {any} */ (source)), outline];
    mesh.frustumCulled = false; // morphs move vertices beyond the base's bounds
  });
  return outlines;
}
