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

/**
 * The k1..k4 of the paper's hue rule for a base colour (src/render/shading.cpp, hueAdjustedConstants).
 * @param {THREE.Color} base
 * @returns {THREE.Vector4}
 */
export function hueConstants(base) {
  const hsl = { h: 0, s: 0, l: 0 };
  const max = Math.max(base.r, base.g, base.b), min = Math.min(base.r, base.g, base.b);
  const saturation = max > 0 ? (max - min) / max : 0;
  base.getHSL(hsl, THREE.LinearSRGBColorSpace);
  const hue = hsl.h * 360;
  const k = new THREE.Vector4(1, 1, 1, 1);
  if (saturation < 0.2) {
    if (max > 0.6) k.y = 0; // soft, cool whites: warm light off
  } else if (hue >= 250 && hue < 330) {
    k.w = 2; // purples: intensified cool light
  } else if (hue < 20 || hue >= 330) {
    k.w = 1.5; // reds: more cool, less warm
    k.y = 0.5;
  }
  return k;
}

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
      void main() {
        vec3 base = uBase;
        if (uHasMap) base *= texture2D(uMap, vTexCoord).rgb;
        vec3 n = normalize(vNormalView);
        if (!gl_FrontFacing) n = -n;
        float d1 = max(dot(uLightWarm, n), 0.0), d2 = max(dot(uLightCool, n), 0.0);
        vec3 c = uKa * base + d1 * (uWarm - base * uK.x) * uK.y + d2 * (uCool - base * uK.z) * uK.w;
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
