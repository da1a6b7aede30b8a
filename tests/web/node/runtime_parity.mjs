// web/vdg-three.js against vdg itself (docs/gltf-export.md, extras v2 to v4): vdgWeights / vdgSphereWeights
// equal `vdg weights --views` within kWeightTol at 10,000 random views and at every key view of every
// shipped example (and of two in the smooth weight scheme, and of spot-rbf in the rbf scheme at four
// sharpnesses), and at 2,000 views of small degenerate key sets in every uncovered mode and every
// weight scheme (rbf with each of its three kernels), and of
// animated OBJ-sequence bases (natural and periodic splines); the
// morphed positions (POSITION + sum w * targets, read from the .glb) equal `vdg eval` within kPosTol.
// Usage: node runtime_parity.mjs VDG_BINARY SOURCE_DIR WEB_DIR WORK_DIR
// Exit 0 pass, 1 fail, 77 skip (three.js not installed, unless VDG_REQUIRE_WEB=1).
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { readAccessor, readGlb } from './glb.mjs';

const kWeightTol = 1e-6;  // the CLI prints float weights with 7 digits
const kPosTol = 1e-5;  // float positions, float weights
const kRandomViews = 10000;
const kDegenerateViews = 2000;

const [vdg, sourceDir, webDir, workDir] = process.argv.slice(2);
if (!existsSync(join(webDir, 'node_modules', 'three'))) {
  console.log('SKIP: web/node_modules/three is missing (scripts/install-deps)');
  process.exit(process.env.VDG_REQUIRE_WEB === '1' ? 1 : 77);
}
const { vdgWeights, vdgSphereWeights } = await import(pathToFileURL(join(webDir, 'vdg-three.js')).href);
rmSync(workDir, { recursive: true, force: true });
mkdirSync(workDir, { recursive: true });

let failures = 0;
/** @param {boolean} ok @param {string} what */
function check(ok, what) {
  if (!ok) {
    failures++;
    if (failures <= 20) console.log(`FAIL: ${what}`);
  }
}

/** @param {string[]} args */
function run(args) {
  return execFileSync(vdg, args, { encoding: 'utf8', maxBuffer: 1 << 28 });
}

// A seeded generator (mulberry32): the same views on every run.
function random(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

/** @param {number} n @param {number} seed @returns {number[][]} uniform directions */
function randomViews(n, seed) {
  const r = random(seed), out = [];
  while (out.length < n) {
    const v = [2 * r() - 1, 2 * r() - 1, 2 * r() - 1];
    const l = Math.hypot(...v);
    if (l > 1e-3 && l <= 1) out.push(v.map((x) => x / l));
  }
  return out;
}

/**
 * Exports `manifest` to a .glb in the work folder; returns the mesh's extras and the glb.
 * @param {string} manifest @param {string} name
 */
function exportModel(manifest, name) {
  const glbPath = join(workDir, `${name}.glb`);
  run(['export', manifest, '-q', '-o', glbPath]);
  const glb = readGlb(glbPath);
  return { glb, extras: glb.json.meshes[0].extras, glbPath };
}

/**
 * Compares the runtime's weights with `vdg weights --views` at `views`.
 * @param {string} model manifest @param {any} extras mesh extras @param {number[][]} views
 * @param {string} label @param {number|null} sharpness
 */
function compareWeights(model, extras, views, label, sharpness = null) {
  const vdgExtras = extras.vdg, names = extras.targetNames;
  const viewsFile = join(workDir, 'views.json');
  writeFileSync(viewsFile, JSON.stringify(views));
  const args = ['weights', model, '--views', viewsFile];
  if (sharpness !== null) args.push('--sharpness', String(sharpness));
  const expected = JSON.parse(run(args));
  check(expected.length === views.length, `${label}: ${expected.length} results for ${views.length} views`);
  const animated = !!vdgExtras.animation;
  // Animated: a sphere point's key names, to find the CLI's entry of each view.
  const pointOf = new Map();
  vdgExtras.sphere.view_targets.forEach((targets, i) => pointOf.set(names[targets[0]], i));
  let worst = 0;
  for (let n = 0; n < views.length; ++n) {
    const e = expected[n];
    const sw = vdgSphereWeights(vdgExtras, views[n], { sharpness });
    if (animated) {
      worst = Math.max(worst, Math.abs(sw.base - e.base));
      const mine = new Map();
      sw.points.forEach((p, k) => { if (p >= 0) mine.set(p, (mine.get(p) || 0) + sw.weights[k]); });
      for (const v of e.views) {
        const p = pointOf.get(v.keys[0]);
        worst = Math.max(worst, Math.abs((mine.get(p) || 0) - v.weight));
        mine.delete(p);
      }
      for (const w of mine.values()) worst = Math.max(worst, w);
      // The morph weights of a view's key frames sum to its weight (cardinal coefficients).
      const frame = (n * 7.31) % vdgExtras.animation.frame_count;
      const mw = vdgWeights(vdgExtras, views[n], { sharpness, frame });
      for (const v of e.views) {
        const targets = vdgExtras.sphere.view_targets[pointOf.get(v.keys[0])];
        const sum = targets.reduce((s, t) => s + mw[t], 0);
        worst = Math.max(worst, Math.abs(sum - v.weight));
      }
    } else {
      const mw = vdgWeights(vdgExtras, views[n], { sharpness });
      for (let t = 0; t < names.length; ++t) {
        const w = e.keys[names[t]] || 0;
        worst = Math.max(worst, Math.abs(mw[t] - w));
      }
      // The rbf scheme weighs every key: the sphere weights hold the three heaviest and, as the
      // base, the rest; the base itself is that rest less the other keys' weights.
      let base = sw.base;
      if (vdgExtras.weights && vdgExtras.weights.scheme === 'rbf') {
        for (let t = 0; t < names.length; ++t) if (!sw.points.includes(t)) base -= mw[t];
      }
      worst = Math.max(worst, Math.abs(base - e.base));
    }
    if (worst > kWeightTol) {
      check(false, `${label}: view ${n} [${views[n]}]: weights differ by ${worst} (vdg ${JSON.stringify(e)}, ` +
        `runtime ${JSON.stringify(sw)})`);
      return;
    }
  }
  console.log(`ok ${label}: ${views.length} views, worst weight difference ${worst.toExponential(2)}`);
}

/**
 * POSITION + sum w_t target_t (the glTF morph), from the .glb.
 * @param {{json: any, bin: Buffer}} glb @param {Float64Array} weights
 */
function morphed(glb, weights) {
  const prim = glb.json.meshes[0].primitives[0];
  const out = readAccessor(glb, prim.attributes.POSITION);
  (prim.targets || []).forEach((t, i) => {
    if (weights[i] === 0) return;
    const d = readAccessor(glb, t.POSITION);
    for (let k = 0; k < out.length; ++k) out[k] += weights[i] * d[k];
  });
  return modelOrder(glb, prim, out);
}

/**
 * Exported vertices back in the model's order through `_VDG_VERTEX` (docs/gltf-export.md: a
 * vertex split on a uv seam has several copies; every copy must have moved to the same place).
 * @param {{json: any, bin: Buffer}} glb @param {any} prim @param {Float64Array} exported
 */
function modelOrder(glb, prim, exported) {
  const map = readAccessor(glb, prim.attributes._VDG_VERTEX);
  let count = 0;
  for (const v of map) count = Math.max(count, v + 1);
  const out = new Float64Array(count * 3).fill(NaN);
  map.forEach((v, i) => {
    for (let c = 0; c < 3; ++c) {
      const x = exported[i * 3 + c];
      check(Number.isNaN(out[v * 3 + c]) || out[v * 3 + c] === x, `copies of vertex ${v} differ`);
      out[v * 3 + c] = x;
    }
  });
  return out;
}

/** @param {string} path @returns {number[]} the "v" lines of an OBJ */
function objPositions(path) {
  const out = [];
  for (const line of readFileSync(path, 'utf8').split('\n')) {
    if (line.startsWith('v ')) out.push(...line.slice(2).trim().split(/\s+/).slice(0, 3).map(Number));
  }
  return out;
}

/**
 * Morphed positions against `vdg eval` at `views` (and `frames`).
 * @param {string} model @param {{glb: any, extras: any}} exported @param {number[][]} views
 * @param {number[]} frames @param {string} label
 */
function comparePositions(model, exported, views, frames, label) {
  let worst = 0;
  const objPath = join(workDir, 'eval.obj');
  for (const frame of frames) {
    for (const view of views) {
      const args = ['eval', model, '-q', '--view', view.join(','), '-o', objPath];
      if (exported.extras.vdg.animation) args.push('--frame', String(frame));
      run(args);
      const expected = objPositions(objPath);
      const mine = morphed(exported.glb, vdgWeights(exported.extras.vdg, view, { frame }));
      check(expected.length === mine.length, `${label}: ${expected.length} vs ${mine.length} coordinates`);
      for (let i = 0; i < mine.length; ++i) worst = Math.max(worst, Math.abs(mine[i] - expected[i]));
    }
  }
  check(worst <= kPosTol, `${label}: positions differ by ${worst}`);
  console.log(`ok ${label}: ${views.length * frames.length} evaluations, worst position difference ` +
    `${worst.toExponential(2)}`);
}

const examples = [
  ['spot', 'examples/spot/spot.vdg.json'],
  ['building', 'examples/building/building.vdg.json'],
  ['head', 'examples/figure13/head/head.vdg.json'],
  ['walker', 'examples/walk/walker.vdg.json'],
  ['walker-world', 'examples/walk/walker-world.vdg.json'],
];
const started = Date.now();
for (const [name, relative] of examples) {
  const manifest = join(sourceDir, relative);
  const exported = exportModel(manifest, name);
  const vdgExtras = exported.extras.vdg;
  check(vdgExtras.version === 2 && !!vdgExtras.sphere && !vdgExtras.weights,
    `${name}: extras version 2 with a sphere and no weight scheme (linear)`);
  const keyViews = vdgExtras.keys.map((k) => k.view);
  compareWeights(manifest, exported.extras, randomViews(kRandomViews, 17).concat(keyViews), name);
  compareWeights(manifest, exported.extras, randomViews(1000, 5), `${name} sharpness 3.5`, 3.5);
  // Positions: static models and the world-offset walker (morph targets only; the skinned walker
  // needs its skin, which three.js applies and the browser test checks).
  const views = [keyViews[0], [0.3, 0.4, 0.87], [-0.8, 0.1, -0.2]];
  if (!vdgExtras.animation) comparePositions(manifest, exported, views, [0], `${name} positions`);
  else if (vdgExtras.animation.base === 'frames') comparePositions(manifest, exported, views.slice(1), [0, 7, 23], `${name} positions`);
}

// The smooth weight scheme (extras version 3, docs/weights.md) on two shipped examples: the same
// manifest with "weights": {"scheme": "smooth"} and its meshes named by absolute paths.
/** @param {string} relative @param {string} name */
function smoothCopy(relative, name) {
  const source = join(sourceDir, relative);
  const folder = join(source, '..');
  const doc = JSON.parse(readFileSync(source, 'utf8'));
  doc.version = 3;
  doc.weights = { scheme: 'smooth' };
  doc.base = join(folder, doc.base);
  for (const key of doc.keys) key.mesh = join(folder, key.mesh);
  const manifest = join(workDir, `${name}.vdg.json`);
  writeFileSync(manifest, JSON.stringify(doc));
  return manifest;
}
for (const [name, relative] of [['spot', 'examples/spot/spot.vdg.json'], ['head', 'examples/figure13/head/head.vdg.json']]) {
  const manifest = smoothCopy(relative, `${name}-smooth`);
  const exported = exportModel(manifest, `${name}-smooth`);
  const vdgExtras = exported.extras.vdg;
  check(vdgExtras.version === 3 && vdgExtras.weights && vdgExtras.weights.scheme === 'smooth',
    `${name}-smooth: extras version 3 with the smooth scheme`);
  const keyViews = vdgExtras.keys.map((k) => k.view);
  compareWeights(manifest, exported.extras, randomViews(kRandomViews, 23).concat(keyViews), `${name} smooth`);
  compareWeights(manifest, exported.extras, randomViews(1000, 6), `${name} smooth sharpness 3.5`, 3.5);
  comparePositions(manifest, exported, [keyViews[0], [0.3, 0.4, 0.87]], [0], `${name} smooth positions`);
}

// The rbf weight scheme (extras version 4, docs/weights.md) on the shipped spot-rbf example: every
// key is weighed, from the written interpolation. Sharpness 2 (squares), 3 (multiplications), 3.5
// and 0.7 (powers) take the three paths of the sharpening.
{
  const manifest = join(sourceDir, 'examples/spot/spot-rbf.vdg.json');
  const exported = exportModel(manifest, 'spot-rbf');
  const vdgExtras = exported.extras.vdg;
  check(vdgExtras.version === 4 && vdgExtras.weights && vdgExtras.weights.scheme === 'rbf' &&
    !!vdgExtras.sphere.rbf, 'spot-rbf: extras version 4 with the rbf scheme and its interpolation');
  const keyViews = vdgExtras.keys.map((k) => k.view);
  compareWeights(manifest, exported.extras, randomViews(kRandomViews, 29).concat(keyViews), 'spot rbf');
  for (const [sharpness, seed] of [[2, 7], [3, 8], [3.5, 9], [0.7, 10]]) {
    compareWeights(manifest, exported.extras, randomViews(1000, seed), `spot rbf sharpness ${sharpness}`, sharpness);
  }
  comparePositions(manifest, exported, [keyViews[0], [0.3, 0.4, 0.87], [-0.8, 0.1, -0.2]], [0], 'spot rbf positions');
  // An rbf description without its interpolation (or with a short row) is refused with one message.
  for (const [what, change] of [['no sphere.rbf', (e) => { delete e.sphere.rbf; }],
    ['a short row', (e) => { e.sphere.rbf.coefficients[1].pop(); }], ['no kernel', (e) => { delete e.weights.kernel; }]]) {
    const broken = structuredClone(vdgExtras);
    change(broken);
    let message = '';
    try { vdgWeights(broken, [0, 0, 1]); } catch (e) { message = String(e.message); }
    check(message.includes("an rbf model needs mesh.extras.vdg 'weights'.'kernel' and 'sphere'.'rbf'"),
      `spot rbf with ${what}: refused in one message (got '${message}')`);
  }
}

// Degenerate key sets, written here: a tetrahedron base and keys that push one vertex each.
const tetra = 'v 0 0 1\nv 0.94 0 -0.33\nv -0.47 0.82 -0.33\nv -0.47 -0.82 -0.33\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n';
writeFileSync(join(workDir, 'base.obj'), tetra);
/** @param {number[][]} keyViews @param {string} uncovered @param {string} name @param {string} scheme */
function degenerate(keyViews, uncovered, name, scheme = 'linear') {
  const keys = keyViews.map((view, i) => {
    const mesh = `k${i}.obj`;
    writeFileSync(join(workDir, mesh), tetra.replace('v 0 0 1', `v ${0.1 * (i + 1)} ${0.05 * i} 1`));
    return { name: `key${i}`, mesh, view };
  });
  const manifest = join(workDir, `${name}.vdg.json`);
  // scheme: 'linear', 'smooth' or 'rbf-KERNEL'.
  const weights = scheme.startsWith('rbf-') ? { scheme: 'rbf', kernel: scheme.slice(4), width: 70 } : { scheme };
  const doc = scheme === 'linear' ? { version: 1, base: 'base.obj', uncovered, sharpness: 1.7, keys }
    : { version: 3, base: 'base.obj', uncovered, sharpness: 1.7, keys, weights };
  writeFileSync(manifest, JSON.stringify(doc));
  const exported = exportModel(manifest, name);
  compareWeights(manifest, exported.extras, randomViews(kDegenerateViews, 99).concat(keyViews), name);
  comparePositions(manifest, exported, [[0.2, 0.3, 0.93]], [0], `${name} positions`);
}
const sets = {
  'one key': [[0, 0, 1]],
  'two keys': [[0, 0, 1], [1, 0.2, 0]],
  'one side': [[0, 0.2, 1], [0.5, 0.1, 0.8], [-0.4, 0.3, 0.9], [0.1, 0.7, 0.7]],
  'great circle': [[1, 0, 0], [0, 0, 1], [-1, 0, 0], [0.3, 0, -0.9]],
  'small circle': [[1, 0.5, 0], [-0.5, 0.5, 0.87], [-0.5, 0.5, -0.87]],
};
for (const [set, keyViews] of Object.entries(sets)) {
  for (const mode of ['base', 'cosine', 'cosine2']) {
    degenerate(keyViews, mode, `${set.replace(' ', '-')}-${mode}`);
    degenerate(keyViews, mode, `${set.replace(' ', '-')}-${mode}-smooth`, 'smooth');
    for (const kernel of ['gaussian', 'inverse-multiquadric', 'wendland']) {
      degenerate(keyViews, mode, `${set.replace(' ', '-')}-${mode}-rbf-${kernel}`, `rbf-${kernel}`);
    }
  }
}

// Animated OBJ-sequence bases, not looping (natural splines, held outside the key frames) and
// looping (periodic): a view with three key frames, one with one, one with two.
/** @param {boolean} loop */
function animatedSequence(loop) {
  const frameCount = 12;
  for (let f = 0; f < frameCount; ++f) {
    writeFileSync(join(workDir, `f_${String(f).padStart(2, '0')}.obj`),
      tetra.replace('v 0.94 0 -0.33', `v ${0.94 + 0.03 * f} ${0.02 * f} -0.33`));
  }
  const keys = [[[0, 0, 1], 2], [[0, 0, 1], 5], [[0, 0, 1], 9], [[1, 0.2, 0], 4], [[0, 1, 0.1], 3], [[0, 1, 0.1], 8]]
    .map(([view, frame], i) => {
      const mesh = `ak${i}.obj`;
      const base = tetra.replace('v 0.94 0 -0.33', `v ${0.94 + 0.03 * frame} ${0.02 * frame} -0.33`);
      writeFileSync(join(workDir, mesh), base.replace('v 0 0 1', `v ${0.05 * (i + 1)} ${0.1 * i - 0.2} 1`));
      return { name: `a${i}`, mesh, view, frame };
    });
  const name = loop ? 'sequence-loop' : 'sequence';
  const manifest = join(workDir, `${name}.vdg.json`);
  writeFileSync(manifest, JSON.stringify({
    version: 2, uncovered: 'cosine', sharpness: 1.3, keys,
    base_animation: { obj_sequence: 'f_%02d.obj', frames: [0, frameCount - 1], loop },
  }));
  const exported = exportModel(manifest, name);
  compareWeights(manifest, exported.extras, randomViews(kDegenerateViews, 3), name);
  comparePositions(manifest, exported, [[0.2, 0.3, 0.93], [0.5, 0.6, 0.1]], [0, 3, 6, 11], `${name} positions`);
}
animatedSequence(false);
animatedSequence(true);

console.log(`${failures === 0 ? 'PASS' : 'FAIL'}: ${failures} failures in ${((Date.now() - started) / 1000).toFixed(1)} s`);
process.exit(failures === 0 ? 0 : 1);
