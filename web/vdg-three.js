// vdg-three.js: view-dependent models (Rademacher, "View-Dependent Geometry", SIGGRAPH 99) exported
// by `vdg export` / `vdg bake`, alive in three.js. One ES module, no build step, importing only
// 'three'. The weights repeat src/viewdep/view_sphere.cpp and animated_model.cpp exactly, from the
// description the export carries in mesh.extras.vdg (version 2, docs/gltf-export.md):
//  - section 3.2.1: the view from the model centre picks the hull triangle whose cone contains it
//    (cone coordinates lambda = M v with the written inverse M; inside when min >= -kInsideTol);
//  - section 3.2.2: barycentric weights sharpened relative to the largest, (p/pmax)^a / sum;
//  - section 3.3: dummy points give their weight to the base; cosine modes fall off towards the
//    nearest boundary arc or isolated key;
//  - section 4.2: per key view, cardinal cubic-spline coefficients in time from the written
//    second-derivative table (natural, or periodic when looping; held outside the key frames).
// See web/README.md for the API and the multi-camera rule.
import { Matrix4, Vector3 } from 'three';

/**
 * @typedef {object} VdgSphere
 * @property {number[][]} points unit directions: key views first, then dummy base points
 * @property {number} views how many leading points are key views
 * @property {number[][]} triangles hull triangles, indices into points
 * @property {number[][]} inverses per triangle 9 numbers, row-major
 * @property {number[][]} arcs boundary arcs (cosine modes)
 * @property {number[]} isolated keys on no triangle and no arc (cosine modes)
 * @property {number[][]} view_targets per key view, the morph target of each key frame
 */
/**
 * @typedef {object} VdgExtras the parsed mesh.extras.vdg object (version 2)
 * @property {number} version
 * @property {number} sharpness
 * @property {'base'|'cosine'|'cosine2'} uncovered
 * @property {number[]} center
 * @property {{name: string, view: number[], frame: number}[]} keys
 * @property {{frame_count: number, fps: number, loop: boolean, animation?: number, base: 'skin'|'frames'}} [animation]
 * @property {VdgSphere} sphere
 * @property {{frames: number[], second: number[]}[]} [time]
 * @property {{scale: number[], offset: number[]}} [dequantize]
 */
/**
 * @typedef {object} SphereWeights
 * @property {number} triangle hull triangle of the view, -1 when uncovered (cosine modes)
 * @property {number[]} points sphere point of each slot (-1: unused)
 * @property {number[]} weights weight of each slot (0 for unused slots and dummy points)
 * @property {number} base weight of the base model
 */

/** Cone coordinates down to -kInsideTol still count as inside (view_sphere.cpp). */
const kInsideTol = 1e-9;

/**
 * @typedef {object} Prepared
 * @property {VdgExtras} extras
 * @property {Float64Array} points
 * @property {number} views
 * @property {Int32Array} triangles
 * @property {Float64Array} inverses
 * @property {Int32Array} arcs
 * @property {Float64Array} arcFrames per arc: normal, b x normal, normal x a (9 numbers)
 * @property {Int32Array} isolated
 * @property {number} targetCount morph targets of the mesh (keys, then base frames)
 * @property {Float64Array} scratch slot weights etc.
 */

/** @type {WeakMap<object, Prepared>} */
const preparedCache = new WeakMap();

/**
 * The extras turned into flat typed arrays once (cached per extras object).
 * @param {VdgExtras} extras
 * @returns {Prepared}
 */
function prepare(extras) {
  const cached = preparedCache.get(extras);
  if (cached) return cached;
  if (!extras || typeof extras !== 'object') throw new TypeError('vdg-three: expected the mesh.extras.vdg object');
  const s = extras.sphere;
  if (!s || !Array.isArray(s.points)) {
    throw new Error(`vdg-three: mesh.extras.vdg has no 'sphere' (version ${extras.version}); re-export with a vdg ` +
      'that writes extras version 2');
  }
  const points = new Float64Array(s.points.flat());
  const triangles = new Int32Array(s.triangles.flat());
  const inverses = new Float64Array(s.inverses.flat());
  const arcs = new Int32Array(s.arcs.flat());
  const arcFrames = new Float64Array(arcs.length / 2 * 9);
  for (let i = 0; i < arcs.length / 2; ++i) {
    const a = arcs[2 * i] * 3, b = arcs[2 * i + 1] * 3;
    // n = (a x b) / |a x b|, then b x n and n x a (view_sphere.cpp's ArcFrame).
    let nx = points[a + 1] * points[b + 2] - points[a + 2] * points[b + 1];
    let ny = points[a + 2] * points[b] - points[a] * points[b + 2];
    let nz = points[a] * points[b + 1] - points[a + 1] * points[b];
    const len = Math.sqrt(nx * nx + ny * ny + nz * nz);
    nx /= len; ny /= len; nz /= len;
    const f = arcFrames.subarray(9 * i, 9 * i + 9);
    f[0] = nx; f[1] = ny; f[2] = nz;
    f[3] = points[b + 1] * nz - points[b + 2] * ny;
    f[4] = points[b + 2] * nx - points[b] * nz;
    f[5] = points[b] * ny - points[b + 1] * nx;
    f[6] = ny * points[a + 2] - nz * points[a + 1];
    f[7] = nz * points[a] - nx * points[a + 2];
    f[8] = nx * points[a + 1] - ny * points[a];
  }
  const frameTargets = extras.animation && extras.animation.base === 'frames' ? extras.animation.frame_count - 1 : 0;
  /** @type {Prepared} */
  const p = {
    extras, points, views: s.views, triangles, inverses, arcs, arcFrames,
    isolated: new Int32Array(s.isolated),
    targetCount: extras.keys.length + frameTargets,
    scratch: new Float64Array(16),
  };
  preparedCache.set(extras, p);
  return p;
}

/**
 * Section 3.2.2's sharpening of s[0..2] in place, relative to the largest (view_sphere.cpp).
 * @param {Float64Array} s
 * @param {number} alpha
 */
function sharpen(s, alpha) {
  const largest = Math.max(s[0], s[1], s[2]);
  if (!(largest > 0)) return;
  for (let k = 0; k < 3; ++k) s[k] = s[k] === largest ? 1 : Math.pow(s[k] / largest, alpha);
  const sum = s[0] + s[1] + s[2];
  for (let k = 0; k < 3; ++k) s[k] /= sum;
}

/**
 * Weights of the unit view (vx, vy, vz) on the sphere's points into `slots` (3 point indices) and
 * `w` (their weights, w[3] = base). Returns the triangle, or -1 when uncovered.
 * @param {Prepared} p
 * @param {number} vx @param {number} vy @param {number} vz
 * @param {number} alpha sharpness
 * @param {Int32Array} slots
 * @param {Float64Array} w
 * @returns {number}
 */
function locate(p, vx, vy, vz, alpha, slots, w) {
  const { inverses, triangles, points } = p;
  const count = triangles.length / 3;
  const base = p.extras.uncovered === 'base';
  let found = -1, bestMin = -1e300, l0 = 0, l1 = 0, l2 = 0;
  for (let t = 0; t < count; ++t) {  // scanTriangles: first inside, else the least outside (base)
    const m = inverses, o = 9 * t;
    const a = m[o] * vx + m[o + 1] * vy + m[o + 2] * vz;
    const b = m[o + 3] * vx + m[o + 4] * vy + m[o + 5] * vz;
    const c = m[o + 6] * vx + m[o + 7] * vy + m[o + 8] * vz;
    const min = Math.min(a, b, c);
    if (min > bestMin && a + b + c > 0) {
      bestMin = min; found = t; l0 = a; l1 = b; l2 = c;
      if (min >= -kInsideTol) break;
    }
  }
  if (found >= 0 && (base || bestMin >= -kInsideTol)) {
    w[0] = Math.max(l0, 0); w[1] = Math.max(l1, 0); w[2] = Math.max(l2, 0);
    if (!(Math.max(w[0], w[1], w[2]) > 0)) { w[0] = w[1] = w[2] = 1; }
    if (alpha !== 1) sharpen(w, alpha);
    const sum = w[0] + w[1] + w[2];
    w[3] = 0;
    for (let k = 0; k < 3; ++k) {
      w[k] /= sum;
      const point = triangles[3 * found + k];
      if (point >= p.views) { w[3] += w[k]; w[k] = 0; slots[k] = -1; } else slots[k] = point;
    }
    return found;
  }
  // Section 3.3, cosine falloff: the nearest isolated key or arc (largest cosine), in scan order.
  let bestCos = -2;
  slots[0] = slots[1] = slots[2] = -1; w[0] = w[1] = w[2] = 0;
  const considerPoint = (/** @type {number} */ k) => {
    const c = vx * points[3 * k] + vy * points[3 * k + 1] + vz * points[3 * k + 2];
    if (c > bestCos) { bestCos = c; slots[0] = k; slots[1] = -1; w[0] = 1; w[1] = 0; }
  };
  for (let i = 0; i < p.isolated.length; ++i) considerPoint(p.isolated[i]);
  for (let i = 0; i < p.arcs.length / 2; ++i) {
    const f = p.arcFrames, o = 9 * i;
    const h = vx * f[o] + vy * f[o + 1] + vz * f[o + 2];
    const c2 = 1 - h * h;
    const la = vx * f[o + 3] + vy * f[o + 4] + vz * f[o + 5];
    const lb = vx * f[o + 6] + vy * f[o + 7] + vz * f[o + 8];
    if (c2 > 1e-24 && la >= 0 && lb >= 0 && la + lb > 0) {
      const c = Math.sqrt(c2);
      if (c > bestCos) {
        bestCos = c; slots[0] = p.arcs[2 * i]; slots[1] = p.arcs[2 * i + 1];
        w[0] = la / (la + lb); w[1] = lb / (la + lb);
      }
      continue;
    }
    considerPoint(p.arcs[2 * i]);
    considerPoint(p.arcs[2 * i + 1]);
  }
  if (slots[0] < 0) { w[3] = 1; return -1; }
  if (alpha !== 1) sharpen(w, alpha);
  let fall = Math.max(0, bestCos);
  if (p.extras.uncovered === 'cosine2') fall *= fall;
  for (let k = 0; k < 3; ++k) { w[k] *= fall; if (w[k] === 0) slots[k] = -1; }
  w[3] = 1 - fall;
  return -1;
}

/**
 * The unit view of `view` (any finite non-zero length); throws for a zero or non-finite one.
 * @param {ArrayLike<number>|{x: number, y: number, z: number}} view
 * @param {Float64Array} out
 */
function unitView(view, out) {
  const v = /** @type {any} */ (view);
  let x = v.x !== undefined ? v.x : v[0], y = v.y !== undefined ? v.y : v[1], z = v.z !== undefined ? v.z : v[2];
  const big = Math.max(Math.abs(x), Math.abs(y), Math.abs(z));
  if (!(big > 0) || !Number.isFinite(big)) throw new RangeError('vdg-three: the view must be finite and non-zero');
  x /= big; y /= big; z /= big;  // no overflow or underflow for 1e-300 or 1e300 long views
  const len = Math.sqrt(x * x + y * y + z * z);
  out[0] = x / len; out[1] = y / len; out[2] = z / len;
}

/**
 * @param {VdgExtras} extras
 * @param {number|null|undefined} sharpness
 */
function resolveSharpness(extras, sharpness) {
  const a = sharpness == null ? extras.sharpness : sharpness;
  if (!(a > 0) || !Number.isFinite(a)) throw new RangeError('vdg-three: the sharpness must be finite and > 0');
  return a;
}

const tmpSlots = new Int32Array(3);
const tmpWeights = new Float64Array(4);
const tmpView = new Float64Array(3);

/**
 * The view's weights on the viewing sphere (for a sphere widget): its triangle, the three slots'
 * sphere points (key views; -1 for unused slots and dummy points) and weights, and the base's.
 * @param {VdgExtras} extras parsed mesh.extras.vdg
 * @param {ArrayLike<number>|{x: number, y: number, z: number}} view model-space direction towards the eye
 * @param {{sharpness?: number|null}} [options]
 * @returns {SphereWeights}
 */
export function vdgSphereWeights(extras, view, { sharpness = null } = {}) {
  const p = prepare(extras);
  unitView(view, tmpView);
  const triangle = locate(p, tmpView[0], tmpView[1], tmpView[2], resolveSharpness(extras, sharpness), tmpSlots,
    tmpWeights);
  return {
    triangle,
    points: Array.from(tmpSlots),
    weights: [tmpWeights[0], tmpWeights[1], tmpWeights[2]],
    base: tmpWeights[3],
  };
}

/**
 * Cardinal time coefficients of key view i at `frame` into out[0..m-1] (animated_model.cpp's
 * coefficients(), section 4.2).
 * @param {VdgExtras} extras
 * @param {number} i key view
 * @param {number} frame any finite frame, fractional ok
 * @param {Float64Array} out
 */
export function vdgTimeCoefficients(extras, i, frame, out) {
  const table = /** @type {{frames: number[], second: number[]}[]} */ (extras.time)[i];
  const t = table.frames, m = t.length;
  out.fill(0, 0, m);
  if (m === 1) { out[0] = 1; return; }
  const anim = /** @type {NonNullable<VdgExtras['animation']>} */ (extras.animation);
  const period = anim.frame_count;
  let x = frame, j = 0;
  if (anim.loop) {
    let u = (frame - t[0]) % period;
    if (u < 0) u += period;
    if (u >= period) u = 0;
    x = t[0] + u;
    while (j + 1 < m && x >= t[j + 1]) ++j;
  } else {
    if (x <= t[0]) { out[0] = 1; return; }
    if (x >= t[m - 1]) { out[m - 1] = 1; return; }
    while (j + 1 < m && t[j + 1] <= x) ++j;
  }
  const next = (j + 1) % m;
  const t1 = j + 1 < m ? t[j + 1] : t[0] + period;
  const h = t1 - t[j];
  const a = (t1 - x) / h, b = 1 - a;
  const ca = (a * a * a - a) * h * h / 6, cb = (b * b * b - b) * h * h / 6;
  out[j] += a;
  out[next] += b;
  const s = table.second;
  for (let k = 0; k < m; ++k) out[k] += ca * s[j * m + k] + cb * s[next * m + k];
}

const tmpCoef = new Float64Array(64);

/**
 * Morph weights of a view into `out` (length: the mesh's targets), allocation-free.
 * @param {Prepared} p
 * @param {number} vx @param {number} vy @param {number} vz unit view
 * @param {number} alpha
 * @param {number} frame
 * @param {Float64Array|number[]} out
 * @param {Int32Array} slots
 * @param {Float64Array} w
 */
function weightsInto(p, vx, vy, vz, alpha, frame, out, slots, w) {
  const extras = p.extras;
  for (let i = 0; i < p.targetCount; ++i) out[i] = 0;
  locate(p, vx, vy, vz, alpha, slots, w);
  const viewTargets = extras.sphere.view_targets;
  for (let k = 0; k < 3; ++k) {
    const i = slots[k];
    if (i < 0 || w[k] === 0) continue;
    const targets = viewTargets[i];
    if (!extras.time) {
      for (let j = 0; j < targets.length; ++j) out[targets[j]] += w[k];
      continue;
    }
    const coef = targets.length <= tmpCoef.length ? tmpCoef : new Float64Array(targets.length);
    vdgTimeCoefficients(extras, i, frame, coef);
    for (let j = 0; j < targets.length; ++j) out[targets[j]] += w[k] * coef[j];
  }
  const anim = extras.animation;
  if (anim && anim.base === 'frames' && anim.frame_count > 1) {
    // The base frames as the glTF "base" clip plays them: weight 1 on frame k's target at frame k,
    // linear in between (frame 0 is POSITION); wrapped when looping, held at the ends otherwise.
    const n = anim.frame_count, first = extras.keys.length - 1;
    let x = anim.loop ? ((frame % n) + n) % n : Math.min(Math.max(frame, 0), n - 1);
    if (!(x < n)) x = 0;
    const k0 = Math.floor(x), u = x - k0, k1 = k0 + 1 === n ? (anim.loop ? 0 : n - 1) : k0 + 1;
    if (k0 > 0) out[first + k0] += 1 - u;
    if (k1 > 0 && u > 0) out[first + k1] += u;
  }
}

/**
 * Morph weights of a view, in the mesh's target order (keys, then a "frames" base's frames).
 * @param {VdgExtras} extras parsed mesh.extras.vdg (version 2)
 * @param {ArrayLike<number>|{x: number, y: number, z: number}} view model-space direction towards the eye, any length
 * @param {{frame?: number, sharpness?: number|null}} [options] frame: animated models (fractional ok)
 * @returns {Float64Array}
 */
export function vdgWeights(extras, view, { frame = 0, sharpness = null } = {}) {
  const p = prepare(extras);
  if (!Number.isFinite(frame)) throw new RangeError('vdg-three: the frame must be finite');
  unitView(view, tmpView);
  const out = new Float64Array(p.targetCount);
  weightsInto(p, tmpView[0], tmpView[1], tmpView[2], resolveSharpness(extras, sharpness), frame, out, tmpSlots,
    tmpWeights);
  return out;
}
