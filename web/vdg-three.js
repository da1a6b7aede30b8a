// vdg-three.js: view-dependent models (Rademacher, "View-Dependent Geometry", SIGGRAPH 99) exported
// by `vdg export` / `vdg bake`, alive in three.js. One ES module, no build step, importing only
// 'three'. The weights repeat src/viewdep/view_sphere.cpp and animated_model.cpp exactly, from the
// description the export carries in mesh.extras.vdg (versions 2 to 4, docs/gltf-export.md):
//  - section 3.2.1: the view from the model centre picks the hull triangle whose cone contains it
//    (cone coordinates lambda = M v with the written inverse M; inside when min >= -kInsideTol);
//  - section 3.2.2: barycentric weights sharpened relative to the largest, (p/pmax)^a / sum;
//    version 3's smooth scheme first turns them into the C1 side-vertex blend (docs/weights.md);
//  - version 4's rbf scheme weighs every key view instead: the written spherical RBF interpolation
//    r_o = b_o + sum_j c_oj g(|v - x_j|^2 / chord2), its C1 positive part, renormalised, sharpened
//    (view_sphere.cpp's rbfWeightsAt; docs/weights.md, "The rbf scheme");
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
 * @property {{chord2: number, coefficients: number[][]}} [rbf] (version 4, rbf scheme) the width as a
 *   squared chord, and (points + 1) rows of (views + 1) coefficients: the constants b_o, then per point
 *   its c_oj (outputs o: the key views, then the base)
 */
/**
 * @typedef {object} VdgExtras the parsed mesh.extras.vdg object (version 2, 3 or 4)
 * @property {number} version
 * @property {number} sharpness
 * @property {'base'|'cosine'|'cosine2'} uncovered
 * @property {{scheme: 'linear'|'smooth'|'rbf', kernel?: 'gaussian'|'inverse-multiquadric'|'wendland',
 *   width?: number}} [weights] (version 3; 4 for rbf) the weight scheme; absent: linear
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
/** The rbf kernels by their extras name, in Prepared.rbfKernel's numbering. */
const kRbfKernels = ['gaussian', 'inverse-multiquadric', 'wendland'];
/** ViewSphere::kRbfPositiveSoftness: the rbf positive part is C1 on (0, e). */
const kRbfPositiveSoftness = 0.05;
/** ViewSphere::kMultiplySharpnessMax: integer sharpness up to this is repeated multiplication. */
const kMultiplySharpnessMax = 8;

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
 * @property {boolean} smooth the smooth weight scheme (extras version 3 'weights'), else linear
 * @property {boolean} rbf the rbf weight scheme (extras version 4): the fields below are set
 * @property {number} rbfKernel 0 gaussian, 1 inverse multiquadric, 2 wendland
 * @property {number} rbfChord2 the width as a squared chord
 * @property {Float64Array} rbfRows the constants, then per point its coefficients (views + 1 each)
 * @property {Float64Array} rbfPhi per point, the kernel at the view (scratch)
 * @property {Float64Array} rbfOut per key view then the base, the weights (scratch)
 * @property {Float64Array} nearest the nearest covered point of the last uncovered locate() (scratch)
 * @property {number} targetCount morph targets of the mesh (keys, then base frames)
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
  const scheme = extras.weights ? extras.weights.scheme : 'linear';
  if (scheme !== 'linear' && scheme !== 'smooth' && scheme !== 'rbf') {
    throw new Error(`vdg-three: weight scheme '${scheme}' is not supported here (linear, smooth and rbf are)`);
  }
  const smooth = scheme === 'smooth', rbf = scheme === 'rbf';
  const rbfKernel = rbf ? kRbfKernels.indexOf(extras.weights.kernel) : -1;
  if (rbf && (rbfKernel < 0 || !s.rbf || !Array.isArray(s.rbf.coefficients) || !(s.rbf.chord2 > 0) ||
      s.rbf.coefficients.length !== s.points.length + 1 ||
      !s.rbf.coefficients.every((/** @type {number[]} */ row) => Array.isArray(row) && row.length === s.views + 1))) {
    throw new Error("vdg-three: an rbf model needs mesh.extras.vdg 'weights'.'kernel' and 'sphere'.'rbf' " +
      '(extras version 4); re-export it with this vdg');
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
    extras, points, views: s.views, triangles, inverses, arcs, arcFrames, smooth, rbf, rbfKernel,
    rbfChord2: rbf ? s.rbf.chord2 : 1,
    rbfRows: new Float64Array(rbf ? s.rbf.coefficients.flat() : []),
    rbfPhi: new Float64Array(rbf ? s.points.length : 0),
    rbfOut: new Float64Array(rbf ? s.views + 1 : 0),
    nearest: new Float64Array(3),
    isolated: new Int32Array(s.isolated),
    targetCount: extras.keys.length + frameTargets,
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
 * The smooth scheme's edge step F(t) = 3t^2 - 2t^3 on [0, 1], clamped (view_sphere.cpp).
 * @param {number} t
 */
function smoothEdgeStep(t) {
  t = Math.min(Math.max(t, 0), 1);
  return t * t * (3 - 2 * t);
}

/**
 * Where the view lies between points a and b (offsets into `points`): the chord lengths' ratio
 * |v - a| / (|v - a| + |v - b|) (view_sphere.cpp's edgeParameter).
 * @param {Float64Array} points @param {number} a @param {number} b
 * @param {number} vx @param {number} vy @param {number} vz
 */
function edgeParameter(points, a, b, vx, vy, vz) {
  const toA = Math.sqrt(Math.max(0, 2 - 2 * (vx * points[a] + vy * points[a + 1] + vz * points[a + 2])));
  const toB = Math.sqrt(Math.max(0, 2 - 2 * (vx * points[b] + vy * points[b + 1] + vz * points[b + 2])));
  return toA / (toA + toB);
}

/** smoothTriangle's edge blends (scratch). */
const tmpBeta = new Float64Array(3);

/**
 * The smooth scheme's weights of triangle t's corners (docs/weights.md; view_sphere.h, "Weight
 * schemes"), in place: w[0..2] holds the triangle's barycentric weights (>= 0) on entry.
 * @param {Prepared} p @param {number} t
 * @param {number} vx @param {number} vy @param {number} vz
 * @param {Float64Array} w
 */
function smoothTriangle(p, t, vx, vy, vz, w) {
  const total = w[0] + w[1] + w[2];
  const b0 = w[0] / total, b1 = w[1] / total, b2 = w[2] / total;
  const p0 = b1 * b2, p1 = b2 * b0, p2 = b0 * b1;
  const beta = tmpBeta;  // preallocated: no allocation per frame
  beta[0] = p0 * p0; beta[1] = p1 * p1; beta[2] = p2 * p2;
  const sum = beta[0] + beta[1] + beta[2];
  if (!(sum > 1e-280)) {  // at a corner: its one-hot weights (kMinSmoothBlend)
    const largest = b0 >= b1 && b0 >= b2 ? 0 : (b1 >= b2 ? 1 : 2);
    for (let k = 0; k < 3; ++k) w[k] = k === largest ? 1 : 0;
    return;
  }
  w[0] = w[1] = w[2] = 0;
  for (let k = 0; k < 3; ++k) {
    const i = (k + 1) % 3, j = (k + 2) % 3;
    const f = smoothEdgeStep(edgeParameter(p.points, 3 * p.triangles[3 * t + i], 3 * p.triangles[3 * t + j],
      vx, vy, vz));
    const weight = beta[k] / sum;
    w[i] += weight * (1 - f);
    w[j] += weight * f;
  }
}

/**
 * Weights of the unit view (vx, vy, vz) on the sphere's points into `slots` (3 point indices) and
 * `w` (their weights, w[3] = base). Returns the triangle, or -1 when uncovered.
 * @param {Prepared} p
 * @param {number} vx @param {number} vy @param {number} vz
 * @param {number} alpha sharpness
 * @param {Int32Array} slots
 * @param {Float64Array} w
 * @param {number} [hint] a triangle to test first (-1: none)
 * @returns {number}
 */
function locate(p, vx, vy, vz, alpha, slots, w, hint = -1) {
  const { inverses, triangles, points } = p;
  const count = triangles.length / 3;
  const base = p.extras.uncovered === 'base';
  let found = -1, bestMin = -1e300, l0 = 0, l1 = 0, l2 = 0;
  if (hint >= 0 && hint < count) {  // a coherent camera: the last triangle first (locateByScan)
    const m = inverses, o = 9 * hint;
    const a = m[o] * vx + m[o + 1] * vy + m[o + 2] * vz;
    const b = m[o + 3] * vx + m[o + 4] * vy + m[o + 5] * vz;
    const c = m[o + 6] * vx + m[o + 7] * vy + m[o + 8] * vz;
    if (Math.min(a, b, c) >= -kInsideTol) { found = hint; bestMin = Math.min(a, b, c); l0 = a; l1 = b; l2 = c; }
  }
  const hinted = found >= 0;
  for (let t = 0; !hinted && t < count; ++t) {  // scanTriangles: first inside, else the least outside
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
    if (!(Math.max(w[0], w[1], w[2]) > 0)) { w[0] = w[1] = w[2] = 1; } else if (p.smooth) {
      smoothTriangle(p, found, vx, vy, vz, w);
    }
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
    if (c > bestCos) {
      bestCos = c; slots[0] = k; slots[1] = -1; w[0] = 1; w[1] = 0;
      p.nearest[0] = points[3 * k]; p.nearest[1] = points[3 * k + 1]; p.nearest[2] = points[3 * k + 2];
    }
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
        {  // the arc's point nearest to the view, normalize(la a + lb b) (view_sphere.cpp's falloff)
          const a = 3 * p.arcs[2 * i], b = 3 * p.arcs[2 * i + 1], q = p.nearest;
          q[0] = la * points[a] + lb * points[b]; q[1] = la * points[a + 1] + lb * points[b + 1];
          q[2] = la * points[a + 2] + lb * points[b + 2];
          const len = Math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
          q[0] /= len; q[1] /= len; q[2] /= len;
        }
        if (p.smooth) {  // the smooth edge weights at the arc's point nearest to the view
          const a = 3 * p.arcs[2 * i], b = 3 * p.arcs[2 * i + 1];
          let qx = la * points[a] + lb * points[b], qy = la * points[a + 1] + lb * points[b + 1];
          let qz = la * points[a + 2] + lb * points[b + 2];
          const len = Math.sqrt(qx * qx + qy * qy + qz * qz);
          qx /= len; qy /= len; qz /= len;
          const f = smoothEdgeStep(edgeParameter(points, a, b, qx, qy, qz));
          w[0] = 1 - f; w[1] = f;
        } else {
          w[0] = la / (la + lb); w[1] = lb / (la + lb);
        }
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
 * The rbf kernel g of the scaled squared chord q (view_sphere.cpp's rbfKernelOfChord2).
 * @param {number} kernel Prepared.rbfKernel @param {number} q
 */
function rbfKernelOfChord2(kernel, q) {
  if (kernel === 1) return 1 / Math.sqrt(1 + q);
  if (kernel === 2) {
    const r = Math.sqrt(q);
    if (r >= 1) return 0;
    const u = 1 - r;
    return u * u * u * u * (4 * r + 1);
  }
  return Math.exp(-q);
}

/**
 * The rbf scheme's C1 positive part P (view_sphere.cpp's rbfPositivePart).
 * @param {number} r
 */
function rbfPositivePart(r) {
  const e = kRbfPositiveSoftness;
  if (r >= e) return r;
  if (r <= 0) return 0;
  return r * r * (2 * e - r) / (e * e);
}

/**
 * Section 3.2.2's sharpening of x[0..n-1] in place, relative to the largest, exactly as
 * view_sphere.cpp's sharpenRelative (squares, integer powers by multiplication, else Math.pow).
 * @param {Float64Array} x @param {number} n @param {number} alpha
 */
function sharpenRelative(x, n, alpha) {
  let largest = x[0];
  for (let i = 1; i < n; ++i) if (x[i] > largest) largest = x[i];
  const inverse = 1 / largest;
  if (alpha === 2) {
    for (let i = 0; i < n; ++i) x[i] = (x[i] * inverse) * (x[i] * inverse);
  } else if (alpha <= kMultiplySharpnessMax && alpha === Math.floor(alpha)) {
    for (let i = 0; i < n; ++i) {
      const r = x[i] * inverse;
      let v = r;
      for (let k = 1; k < alpha; ++k) v *= r;
      x[i] = v;
    }
  } else {
    for (let i = 0; i < n; ++i) x[i] = x[i] === largest ? 1 : Math.pow(x[i] * inverse, alpha);
  }
}

/**
 * The rbf weights at the unit direction (x, y, z) into p.rbfOut (key views, then the base): the
 * interpolation r_o = b_o + sum_j c_oj g(q_j), centre by centre; the positive part; normalised and
 * sharpened; the key views get `scale` times their weight, the base the rest (view_sphere.cpp's
 * rbfWeightsAt, in its order of operations).
 * @param {Prepared} p @param {number} x @param {number} y @param {number} z
 * @param {number} alpha @param {number} scale
 */
function rbfWeightsAt(p, x, y, z, alpha, scale) {
  const { points, rbfRows: rows, rbfPhi: phi, rbfOut: w } = p;
  const m = points.length / 3, outputs = p.views + 1;
  for (let j = 0; j < m; ++j) {
    const dx = x - points[3 * j], dy = y - points[3 * j + 1], dz = z - points[3 * j + 2];
    phi[j] = rbfKernelOfChord2(p.rbfKernel, (dx * dx + dy * dy + dz * dz) / p.rbfChord2);
  }
  for (let o = 0; o < outputs; ++o) w[o] = rows[o];
  for (let j = 0; j < m; ++j) {
    if (phi[j] === 0) continue;
    const row = (j + 1) * outputs;
    for (let o = 0; o < outputs; ++o) w[o] += rows[row + o] * phi[j];
  }
  let sum = 0;
  for (let o = 0; o < outputs; ++o) { w[o] = rbfPositivePart(w[o]); sum += w[o]; }
  if (alpha !== 1) {
    for (let o = 0; o < outputs; ++o) w[o] /= sum;
    sharpenRelative(w, outputs, alpha);
    sum = 0;
    for (let o = 0; o < outputs; ++o) sum += w[o];
  }
  const factor = scale / sum;
  for (let o = 0; o + 1 < outputs; ++o) w[o] *= factor;
  w[outputs - 1] = w[outputs - 1] * factor + (1 - scale);
}

/**
 * The rbf weights of the unit view into p.rbfOut (view_sphere.cpp's denseWeights): at the view in
 * base mode and for a covered view; for an uncovered one (cosine modes) at the nearest covered
 * point p, times the falloff f = max(0, v.p) (squared for cosine2), the base getting 1 - f. Then
 * `slots` / `w` get the three heaviest key views (ties to the lower index) and, as the base, the
 * rest (vdg's heaviestKeys). Returns the hull triangle (the hint), -1 when uncovered.
 * @param {Prepared} p
 * @param {number} vx @param {number} vy @param {number} vz
 * @param {number} alpha
 * @param {Int32Array} slots
 * @param {Float64Array} w
 * @param {number} [hint]
 * @returns {number}
 */
function rbfLocate(p, vx, vy, vz, alpha, slots, w, hint = -1) {
  const triangle = locate(p, vx, vy, vz, 1, slots, w, hint);
  if (p.extras.uncovered === 'base' || triangle >= 0) {
    rbfWeightsAt(p, vx, vy, vz, alpha, 1);
  } else {
    const q = p.nearest;
    const reached = slots[0] >= 0 || slots[1] >= 0 || slots[2] >= 0;
    let f = reached ? Math.max(0, vx * q[0] + vy * q[1] + vz * q[2]) : 0;
    if (p.extras.uncovered === 'cosine2') f *= f;
    rbfWeightsAt(p, q[0], q[1], q[2], alpha, f);
  }
  const out = p.rbfOut, views = p.views;
  slots[0] = slots[1] = slots[2] = -1;
  w[0] = w[1] = w[2] = 0;
  for (let i = 0; i < views; ++i) {  // insertion into the three heaviest, stable for ties
    let k = 3;
    while (k > 0 && (slots[k - 1] < 0 || out[i] > w[k - 1])) --k;
    for (let m = 2; m > k; --m) { slots[m] = slots[m - 1]; w[m] = w[m - 1]; }
    if (k < 3) { slots[k] = i; w[k] = out[i]; }
  }
  let rest = out[views];
  for (let i = 0; i < views; ++i) if (i !== slots[0] && i !== slots[1] && i !== slots[2]) rest += out[i];
  w[3] = rest;
  return triangle;
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
  const triangle = (p.rbf ? rbfLocate : locate)(p, tmpView[0], tmpView[1], tmpView[2],
    resolveSharpness(extras, sharpness), tmpSlots, tmpWeights);
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

/** Coefficients of one view's key frames (vdg allows 256 key frames per view: kMaxKeyFramesPerView). */
const tmpCoef = new Float64Array(256);

/**
 * Morph weights of a view into `out` (length: the mesh's targets), allocation-free.
 * @param {Prepared} p
 * @param {number} vx @param {number} vy @param {number} vz unit view
 * @param {number} alpha
 * @param {number} frame
 * @param {Float64Array|number[]} out
 * @param {Int32Array} slots
 * @param {Float64Array} w
 * @param {number} [hint]
 * @returns {number} the triangle (-1: uncovered)
 */
function weightsInto(p, vx, vy, vz, alpha, frame, out, slots, w, hint = -1) {
  const extras = p.extras;
  for (let i = 0; i < p.targetCount; ++i) out[i] = 0;
  const triangle = (p.rbf ? rbfLocate : locate)(p, vx, vy, vz, alpha, slots, w, hint);
  const viewTargets = extras.sphere.view_targets;
  // Three slots, or with the rbf scheme every key view (its weights in p.rbfOut).
  const count = p.rbf ? p.views : 3;
  for (let k = 0; k < count; ++k) {
    const i = p.rbf ? k : slots[k];
    const weight = p.rbf ? p.rbfOut[k] : w[k];
    if (i < 0 || weight === 0) continue;
    const targets = viewTargets[i];
    if (!extras.time) {
      for (let j = 0; j < targets.length; ++j) out[targets[j]] += weight;
      continue;
    }
    const coef = targets.length <= tmpCoef.length ? tmpCoef : new Float64Array(targets.length);
    vdgTimeCoefficients(extras, i, frame, coef);
    for (let j = 0; j < targets.length; ++j) out[targets[j]] += weight * coef[j];
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
  return triangle;
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

// ---- three.js controller ----------------------------------------------------------------------

/**
 * @typedef {object} VdgModel one view-dependent model under the root
 * @property {import('three').Mesh[]} meshes its Meshes (one per glTF primitive, sharing one target list)
 * @property {VdgExtras} extras
 */

const _inverse = new Matrix4();
const _eye = new Vector3();
const _dir = new Vector3();

/**
 * True for a pass that is not a view of the scene: a depth or distance material (shadow maps, depth
 * pre-passes), or a camera marked `camera.userData.vdgAuxiliary = true` (reflections, probes).
 * @param {any} camera @param {any} material
 */
function auxiliaryPass(camera, material) {
  return !!(material && (material.isMeshDepthMaterial || material.isMeshDistanceMaterial)) ||
    !!(camera && camera.userData && camera.userData.vdgAuxiliary);
}

/**
 * The model-space view of `camera` seen from an object whose world matrix is `world` (then
 * `instance`, for an instanced mesh): the eye (perspective) or the camera's backward axis
 * (orthographic) mapped through the inverse, then through extras.dequantize, minus the centre
 * (points only). Writes `out`; false when the eye sits on the centre.
 * @param {any} camera @param {import('three').Matrix4} world @param {VdgExtras} extras
 * @param {Float64Array} out
 */
function cameraView(camera, world, extras, out) {
  _inverse.copy(world).invert();
  const e = camera.matrixWorld.elements;
  const ortho = !!camera.isOrthographicCamera;
  const q = extras.dequantize;
  if (ortho) {
    _dir.set(e[8], e[9], e[10]).transformDirection(_inverse);  // towards the eye: the camera's +Z
    out[0] = _dir.x * (q ? q.scale[0] : 1);
    out[1] = _dir.y * (q ? q.scale[1] : 1);
    out[2] = _dir.z * (q ? q.scale[2] : 1);
  } else {
    _eye.set(e[12], e[13], e[14]).applyMatrix4(_inverse);
    const c = extras.center;
    out[0] = (q ? q.offset[0] + q.scale[0] * _eye.x : _eye.x) - c[0];
    out[1] = (q ? q.offset[1] + q.scale[1] * _eye.y : _eye.y) - c[1];
    out[2] = (q ? q.offset[2] + q.scale[2] * _eye.z : _eye.z) - c[2];
  }
  const big = Math.max(Math.abs(out[0]), Math.abs(out[1]), Math.abs(out[2]));
  if (!(big > 0) || !Number.isFinite(big)) return false;
  const len = Math.hypot(out[0] / big, out[1] / big, out[2] / big) * big;
  out[0] /= len; out[1] /= len; out[2] /= len;
  return true;
}

/**
 * The animation frame of a controller: `frame`, or `time` seconds times fps (wrapped when looping).
 * @param {VdgExtras} extras @param {number} frame @param {number|null} time
 */
function controllerFrame(extras, frame, time) {
  const anim = extras.animation;
  if (!anim) return 0;
  if (time == null) return frame;
  const f = time * anim.fps;
  return anim.loop ? ((f % anim.frame_count) + anim.frame_count) % anim.frame_count : f;
}

/**
 * Makes every view-dependent mesh under `root` (a GLTFLoader scene from `vdg export`) follow the
 * camera that renders it. The rule (web/README.md): each render of a mesh sets its
 * morphTargetInfluences from THE CAMERA THAT IS RENDERING it (onBeforeRender), so two views of one
 * scene each see the model drawn for them; auxiliary passes (shadow maps through onBeforeShadow,
 * depth or distance materials, cameras with userData.vdgAuxiliary) use `mainCamera` (when null,
 * the camera the renderer was called with), so a shadow matches what the main view shows.
 * @param {import('three').Object3D} root
 * @param {{mainCamera?: import('three').Camera|null, sharpness?: number|null, frame?: number}} [options]
 */
export function attachVdg(root, { mainCamera = null, sharpness = null, frame = 0 } = {}) {
  /**
   * Per model: its last view's morph weights and sphere weights (kept without allocating per frame).
   * @type {Map<VdgExtras, VdgModel & {weights: Float64Array, hint: number, drawn: boolean, triangle: number,
   *   slots: Int32Array, slotWeights: Float64Array}>}
   */
  const byExtras = new Map();
  root.traverse((object) => {
    const mesh = /** @type {any} */ (object);
    const extras = mesh.isMesh && mesh.userData && mesh.userData.vdg;
    if (!extras || !mesh.morphTargetInfluences) return;
    prepare(extras);  // throws for a version 1 export, naming the problem
    let model = byExtras.get(extras);
    if (!model) {
      model = {
        meshes: [], extras, weights: new Float64Array(prepare(extras).targetCount), hint: -1,
        drawn: false, triangle: -1, slots: new Int32Array(3), slotWeights: new Float64Array(4),
      };
      byExtras.set(extras, model);
    }
    model.meshes.push(mesh);
  });
  const view = new Float64Array(3);
  const slots = new Int32Array(3);
  const w = new Float64Array(4);
  /** @type {{mesh: any, before: any, shadow: any}[]} */
  const hooked = [];

  const controller = {
    /** @type {number|null} null: each model's own sharpness */
    sharpness,
    /** animated models: the frame (fractional ok); used when `time` is null */
    frame,
    /** @type {number|null} animated models: seconds; frame = time * fps (wrapped when looping) */
    time: null,
    /** @type {import('three').Camera|null} */
    mainCamera,
    /** @type {VdgModel[]} */
    models: Array.from(byExtras.values()).map(({ meshes, extras }) => ({ meshes, extras })),
    /**
     * The morph weights last set for a model by a view of the scene (not an auxiliary pass).
     * @param {VdgModel} model
     */
    lastWeights(model) { return /** @type {any} */ (byExtras.get(model.extras)).weights; },
    /**
     * Its sphere weights (vdgSphereWeights' form), or null before the first render.
     * @param {VdgModel} model
     */
    lastSphereWeights(model) {
      const m = /** @type {any} */ (byExtras.get(model.extras));
      if (!m.drawn) return null;
      const w = m.slotWeights;
      return { triangle: m.triangle, points: Array.from(m.slots), weights: [w[0], w[1], w[2]], base: w[3] };
    },
    /** Restores the meshes' hooks and zero weights (the base). */
    dispose() {
      for (const { mesh, before, shadow } of hooked) {
        mesh.onBeforeRender = before;
        mesh.onBeforeShadow = shadow;
        mesh.morphTargetInfluences.fill(0);
      }
      hooked.length = 0;
    },
  };

  /**
   * Sets the influences of `mesh` (of `model`) for `camera`.
   * @param {any} model @param {any} mesh @param {any} camera @param {boolean} record
   */
  function update(model, mesh, camera, record) {
    if (!camera || !cameraView(camera, mesh.matrixWorld, model.extras, view)) return;
    const p = prepare(model.extras);
    const alpha = resolveSharpness(model.extras, controller.sharpness);
    const f = controllerFrame(model.extras, controller.frame, controller.time);
    const out = record ? model.weights : _scratchWeights(p.targetCount);
    model.hint = weightsInto(p, view[0], view[1], view[2], alpha, f, out, slots, w, model.hint);
    const influences = mesh.morphTargetInfluences;
    for (let i = 0; i < influences.length && i < out.length; ++i) influences[i] = out[i];
    if (record) {
      model.drawn = true;
      model.triangle = model.hint;
      model.slots.set(slots);
      model.slotWeights.set(w);
    }
  }

  for (const model of byExtras.values()) {
    for (const mesh of model.meshes) {
      const m = /** @type {any} */ (mesh);
      hooked.push({ mesh: m, before: m.onBeforeRender, shadow: m.onBeforeShadow });
      const before = m.onBeforeRender, shadow = m.onBeforeShadow;
      m.onBeforeRender = function (renderer, scene, camera, geometry, material, group) {
        const aux = auxiliaryPass(camera, material);
        update(model, m, aux ? controller.mainCamera || camera : camera, !aux);
        before.call(this, renderer, scene, camera, geometry, material, group);
      };
      m.onBeforeShadow = function (renderer, object, camera, shadowCamera, geometry, depthMaterial, group) {
        update(model, m, controller.mainCamera || camera, false);
        shadow.call(this, renderer, object, camera, shadowCamera, geometry, depthMaterial, group);
      };
    }
  }
  return controller;
}

/** @type {Float64Array} */
let scratchWeights = new Float64Array(0);
/** @param {number} n */
function _scratchWeights(n) {
  if (scratchWeights.length < n) scratchWeights = new Float64Array(n);
  return scratchWeights;
}

/**
 * Crowds: many instances of one model in a three.js InstancedMesh (its geometry the model's, with
 * its morph attributes), each weighted for its own view: the rendering camera seen from that
 * instance (mesh.matrixWorld then its instance matrix), written into the per-instance morph
 * weights (instancedMesh.morphTexture, as setMorphAt lays it out) before every render. The same
 * camera rule as attachVdg. Per frame: one 4x4 inverse and one triangle search per instance (the
 * instance's last triangle is tried first, so a smooth camera costs one cone test).
 * @param {import('three').InstancedMesh} instancedMesh
 * @param {VdgExtras} extras the model's mesh.extras.vdg
 * @param {{mainCamera?: import('three').Camera|null, sharpness?: number|null, frame?: number}} [options]
 */
export function attachVdgInstanced(instancedMesh, extras, { mainCamera = null, sharpness = null, frame = 0 } = {}) {
  const p = prepare(extras);
  const mesh = /** @type {any} */ (instancedMesh);
  const targets = p.targetCount;
  const width = targets + 1;
  // The morph texture, created by three's own setMorphAt (then written directly).
  mesh.setMorphAt(0, { morphTargetInfluences: new Array(targets).fill(0) });
  const hints = new Int32Array(mesh.count).fill(-1);
  const view = new Float64Array(3);
  const slots = new Int32Array(3);
  const w = new Float64Array(4);
  const weights = new Float64Array(targets);
  const instance = new Matrix4();
  const world = new Matrix4();
  const relative = !!mesh.geometry.morphTargetsRelative;
  const before = mesh.onBeforeRender, shadow = mesh.onBeforeShadow;
  const controller = {
    sharpness,
    frame,
    /** @type {number|null} */
    time: null,
    mainCamera,
    /** @type {Float64Array|null} per-instance frames (animated models), overriding frame / time */
    frames: null,
    /** Restores the hooks. */
    dispose() { mesh.onBeforeRender = before; mesh.onBeforeShadow = shadow; },
    /**
     * Writes every instance's weights for `camera` (called before each render; callable directly).
     * @param {import('three').Camera} camera
     */
    update(camera) {
      const data = mesh.morphTexture.source.data.data;
      const alpha = resolveSharpness(extras, controller.sharpness);
      const shared = controllerFrame(extras, controller.frame, controller.time);
      for (let i = 0; i < mesh.count; ++i) {
        mesh.getMatrixAt(i, instance);
        world.multiplyMatrices(mesh.matrixWorld, instance);
        if (!cameraView(camera, world, extras, view)) continue;
        const f = controller.frames ? controller.frames[i] : shared;
        hints[i] = weightsInto(p, view[0], view[1], view[2], alpha, f, weights, slots, w, hints[i]);
        let sum = 0;
        const row = i * width;
        for (let t = 0; t < targets; ++t) { data[row + 1 + t] = weights[t]; sum += weights[t]; }
        data[row] = relative ? 1 : 1 - sum;
      }
      mesh.morphTexture.needsUpdate = true;
    },
  };
  mesh.onBeforeRender = function (renderer, scene, camera, geometry, material, group) {
    controller.update(auxiliaryPass(camera, material) ? controller.mainCamera || camera : camera);
    before.call(this, renderer, scene, camera, geometry, material, group);
  };
  mesh.onBeforeShadow = function (renderer, object, camera, shadowCamera, geometry, depthMaterial, group) {
    controller.update(controller.mainCamera || camera);
    shadow.call(this, renderer, object, camera, shadowCamera, geometry, depthMaterial, group);
  };
  return controller;
}
