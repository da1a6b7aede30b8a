// Babylon.js plays the KHR_interactivity graph of `vdg export --interactivity` (docs/interactivity.md)
// with no vdg code: a page with Babylon.js only (page/, pinned in web/package.json) loads each export,
// the driver places the camera at given eyes (RANDOM_VIEWS seeded random ones and every key view),
// renders one frame each, and reads what Babylon shows:
//   - the morph target influences equal `vdg weights --views FILE --json` within WEIGHT_TOLERANCE
//     (target i is key extras.targetNames[i]; a key with no entry weighs 0);
//   - the morphed positions (base + sum influence * (target - base), from the mesh data Babylon
//     holds) equal `vdg eval` within POSITION_TOLERANCE at every POSITION_EVERY-th view
//     (exported vertex i is model vertex _VDG_VERTEX[i], read here by the driver, never by the page),
//     for every model but the cosine-mode sets (the blend depends on the influences alone);
//   - Spot's influences are the same in a right-handed Babylon scene (scene.useRightHandedSystem);
//   - the page logs no error (Babylon rejects a graph it cannot play with a console error);
//   - the same export without --interactivity keeps every influence at 0 while the camera moves:
//     the graph, not the page, moves the shape;
//   - the page's source holds no vdg code (no "vdg", no glTF extras, only @babylonjs imports).
// Models: every shipped static example with keys (Spot, the figure 13 head, the building) and
// degenerate key sets written here: Spot with 1, 2 and 3 of its keys in each uncovered mode (base,
// cosine, cosine2), and the tutorial's Suzanne (shipped with no keys) with the key docs/tutorial.md
// adds by `vdg deform`, and with two.
// Writes spot_a.png and spot_b.png in WORK_DIR: two views of Spot, the plain export (the base) left,
// Babylon playing the graph right (docs/images/interactivity_spot_{a,b}.png).
// Usage: node babylon_interactivity.mjs VDG SOURCE_DIR WEB_DIR WORK_DIR. Exit 77 (skip) when
// Chromium, playwright-core or Babylon.js is missing, unless VDG_REQUIRE_WEB=1.
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { loadChromium, openPage, serve } from './harness.mjs';

const [vdg, sourceDir, webDir, workDir] = process.argv.slice(2);
const here = path.dirname(fileURLToPath(import.meta.url));
const WEIGHT_TOLERANCE = 1e-5; // Babylon's graph runs in float32 matrices and double scalars against vdg's doubles
const POSITION_TOLERANCE = 1e-4; // model units; float32 morph targets against vdg eval's doubles
const RANDOM_VIEWS = 20;
const POSITION_EVERY = 3; // positions against vdg eval at every third view (one vdg eval each: most of the test's time)
const EYE_DISTANCE = 3; // eyes at this many bounding radii from the centre
const PARITY_SIZE = 64; // pixels: the parity views render small (software GL), the screenshots at SHOT_SIZE
const SHOT_SIZE = 320;
const SHOT_DISTANCE = 4.0; // the screenshots' eye distance from Spot's centre (model units)
const UNCOVERED_MODES = ['base', 'cosine', 'cosine2']; // the degenerate sets' uncovered modes the graph plays

let failures = 0;
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures += 1;
}

/** Runs vdg; returns {status, stdout, stderr}. */
function vdgRun(...args) {
  return spawnSync(vdg, args, { encoding: 'utf8', maxBuffer: 64 << 20 });
}
/** Runs vdg; throws with its stderr when it fails. */
function runVdg(...args) {
  const r = vdgRun(...args);
  if (r.status !== 0) throw new Error(`vdg ${args.join(' ')}: exit ${r.status}: ${r.stderr}`);
  return r.stdout;
}

/** The JSON and BIN chunks of a .glb. */
function readGlb(file) {
  const b = fs.readFileSync(file);
  const jsonLength = b.readUInt32LE(12);
  const json = JSON.parse(b.subarray(20, 20 + jsonLength).toString('utf8'));
  const binStart = 20 + jsonLength;
  const bin = binStart < b.length ? b.subarray(binStart + 8, binStart + 8 + b.readUInt32LE(binStart)) : null;
  return { json, bin };
}

/** The scalars of a dense SCALAR accessor (any component type, with or without byteStride), as numbers. */
function accessorScalars({ json, bin }, index) {
  const a = json.accessors[index];
  const view = json.bufferViews[a.bufferView];
  const read = { 5121: 'getUint8', 5123: 'getUint16', 5125: 'getUint32', 5126: 'getFloat32' }[a.componentType];
  const size = { 5121: 1, 5123: 2, 5125: 4, 5126: 4 }[a.componentType];
  const data = new DataView(bin.buffer, bin.byteOffset + (view.byteOffset || 0) + (a.byteOffset || 0));
  const out = [];
  for (let i = 0; i < a.count; ++i) out.push(data[read](i * (view.byteStride || size), true));
  return out;
}

/** Vertex positions of an OBJ file. */
function objVertices(file) {
  const out = [];
  for (const line of fs.readFileSync(file, 'utf8').split('\n'))
    if (line.startsWith('v ')) out.push(line.trim().split(/\s+/).slice(1, 4).map(Number));
  return out;
}

/** A seeded random number generator (mulberry32), so every run checks the same views. */
function random(seed) {
  let s = seed >>> 0;
  return () => {
    s = (s + 0x6d2b79f5) >>> 0;
    let t = Math.imul(s ^ (s >>> 15), 1 | s);
    t = (t + Math.imul(t ^ (t >>> 7), 61 | t)) ^ t;
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

/** RANDOM_VIEWS random eyes and one per key view, at EYE_DISTANCE radii from the centre. */
function eyes(json, seed) {
  const vdgExtras = json.meshes[0].extras.vdg;
  const position = json.accessors[json.meshes[0].primitives[0].attributes.POSITION];
  const radius = Math.hypot(...position.max.map((m, i) => m - position.min[i])) / 2;
  const c = vdgExtras.center;
  const rnd = random(seed);
  const dirs = [];
  for (let i = 0; i < RANDOM_VIEWS; ++i) {
    const z = 2 * rnd() - 1, phi = 2 * Math.PI * rnd(), r = Math.sqrt(1 - z * z);
    dirs.push([r * Math.cos(phi), z, r * Math.sin(phi)]);
  }
  for (const k of vdgExtras.keys) dirs.push(k.view);
  return dirs.map((d) => {
    const n = Math.hypot(...d);
    return d.map((x, i) => c[i] + (EYE_DISTANCE * radius * x) / n);
  });
}

/** Checks that the page holds no vdg code: only Babylon.js imports, no "vdg", no glTF extras. */
function checkPageSource() {
  const dir = path.join(here, 'page');
  for (const name of fs.readdirSync(dir)) {
    const text = fs.readFileSync(path.join(dir, name), 'utf8');
    check(!/vdg/i.test(text), `page/${name} names no vdg code (no "vdg" anywhere)`);
    check(!/extras|view_targets|inverses|targetNames\b/.test(text), `page/${name} reads no glTF extras`);
    const imports = [...text.matchAll(/(?:import\s[^'"]*|import\s*\()\s*['"]([^'"]+)['"]/g)].map((m) => m[1]);
    check(imports.every((s) => s.startsWith('@babylonjs/')), `page/${name} imports only @babylonjs (${imports.length} imports)`);
  }
}

/** Loads glb in the page (Babylon's default left-handed scene, or a right-handed one) and returns, per eye, the influences and the morphed positions. */
async function play(page, glbUrl, eyeList, center, rightHanded = false) {
  await page.evaluate(([u, rh]) => window.babylonPage.load(u, { rightHanded: rh }), [glbUrl, rightHanded]);
  return page.evaluate(([list, c]) => list.map((e) => {
    window.babylonPage.view(e, c);
    return { influences: window.babylonPage.influences(), positions: window.babylonPage.positions() };
  }), [eyeList, center]);
}

/** The largest |influence - vdg weight| over every view and target, and the view where it is. */
function weightError(got, want, names) {
  let worst = 0, at = -1;
  for (const [v, { influences }] of got.entries()) {
    if (influences.length !== names.length) return { worst: Infinity, at: v };
    for (const [i, key] of names.entries()) {
      const err = Math.abs(influences[i] - (want[v].keys[key] ?? 0));
      if (!(err <= worst)) { worst = Number.isNaN(err) ? Infinity : err; at = v; }
    }
  }
  return { worst, at };
}

/** One model: export with the graph, play it at every eye, compare with vdg weights and vdg eval. */
async function checkModel(page, name, manifest, seed, withPositions, rightHanded) {
  const glb = path.join(workDir, `${name}.glb`);
  const t0 = Date.now();
  const exported = vdgRun('export', manifest, '--interactivity', '-o', glb, '-q');
  if (exported.status !== 0) {
    check(false, `${name}: vdg export --interactivity: ${exported.stderr.trim()}`);
    return;
  }
  const data = readGlb(glb);
  const { json } = data;
  const ext = json.extensions && json.extensions.KHR_interactivity;
  check(!!ext && (json.extensionsUsed || []).includes('KHR_interactivity') && !(json.extensionsRequired || []).includes('KHR_interactivity'),
    `${name}: the export holds a KHR_interactivity graph, in extensionsUsed, not extensionsRequired`);
  if (!ext) return;
  const nodeCount = ext.graphs.reduce((n, g) => n + g.nodes.length, 0);
  const names = json.meshes[0].extras.targetNames;
  const center = json.meshes[0].extras.vdg.center;
  const list = eyes(json, seed);
  const viewsFile = path.join(workDir, `${name}.views.json`);
  fs.writeFileSync(viewsFile, JSON.stringify(list.map((eye) => ({ eye }))));
  const want = JSON.parse(runVdg('weights', manifest, '--views', viewsFile, '--json'));
  const got = await play(page, `/work/${name}.glb`, list, center);
  const vertexOf = accessorScalars(data, json.meshes[0].primitives[0].attributes._VDG_VERTEX);
  const { worst: worstWeight, at: worstAt } = weightError(got, want, names);
  let worstPosition = 0, moved = 0;
  for (const [v, eye] of list.entries()) {
    const { influences, positions } = got[v];
    if (v > 0 && influences.some((w, i) => Math.abs(w - got[0].influences[i]) > WEIGHT_TOLERANCE)) moved += 1;
    if (!withPositions || v % POSITION_EVERY !== 0) continue;
    const obj = path.join(workDir, `${name}_eval.obj`);
    runVdg('eval', manifest, '--eye', eye.join(','), '-o', obj, '-q');
    const model = objVertices(obj);
    if (positions.length !== 3 * vertexOf.length) worstPosition = Infinity;
    for (let i = 0; i < vertexOf.length && worstPosition < Infinity; ++i)
      for (let c = 0; c < 3; ++c) worstPosition = Math.max(worstPosition, Math.abs(positions[3 * i + c] - model[vertexOf[i]][c]));
  }
  check(worstWeight <= WEIGHT_TOLERANCE, `${name}: Babylon's influences equal vdg weights at ${list.length} views ` +
    `(max error ${worstWeight.toExponential(2)} <= ${WEIGHT_TOLERANCE}${worstAt >= 0 ? `, worst at eye ${list[worstAt].map((x) => x.toFixed(3))}: ` +
    `Babylon ${JSON.stringify(got[worstAt].influences)}, vdg ${JSON.stringify(names.map((k) => want[worstAt].keys[k] ?? 0))}` : ''})`);
  if (withPositions)
    check(worstPosition <= POSITION_TOLERANCE, `${name}: Babylon's morphed positions equal vdg eval at ${Math.ceil(list.length / POSITION_EVERY)} views ` +
      `(max error ${worstPosition.toExponential(2)} <= ${POSITION_TOLERANCE})`);
  if (rightHanded) {
    const rh = weightError(await play(page, `/work/${name}.glb`, list, center, true), want, names);
    check(rh.worst <= WEIGHT_TOLERANCE, `${name}: the same in a right-handed Babylon scene (max error ${rh.worst.toExponential(2)})`);
  }
  check(moved > 0, `${name}: moving the camera changes the influences (${moved} of ${list.length - 1} views differ from the first)`);
  console.log(`     ${name}: ${names.length} targets, graph of ${nodeCount} nodes, ${((Date.now() - t0) / 1000).toFixed(1)} s`);
}

/** Without --interactivity the influences stay 0 wherever the camera goes. */
async function checkControl(page, manifest) {
  const glb = path.join(workDir, 'control.glb');
  runVdg('export', manifest, '-o', glb, '-q');
  const { json } = readGlb(glb);
  const got = await play(page, '/work/control.glb', eyes(json, 7).slice(0, 5), json.meshes[0].extras.vdg.center);
  const most = Math.max(...got.flatMap((g) => g.influences.map(Math.abs)));
  check(most === 0, `control: a plain export (no graph) keeps every influence 0 while the camera moves (max ${most})`);
}

/**
 * Degenerate key sets, written into the work folder: Spot with 1, 2 and 3 of its keys (in each
 * uncovered mode of UNCOVERED_MODES), and the tutorial's Suzanne with the key docs/tutorial.md adds
 * by `vdg deform` (1 key) and a second one (2 keys).
 */
function degenerateManifests() {
  const spotDir = path.join(sourceDir, 'examples/spot');
  const spot = JSON.parse(fs.readFileSync(path.join(spotDir, 'spot.vdg.json'), 'utf8'));
  const abs = (k) => ({ ...k, mesh: path.join(spotDir, k.mesh) });
  const out = {};
  for (const mode of UNCOVERED_MODES)
    for (const keys of [['front'], ['front', 'right'], ['front', 'right', 'top']]) {
      const name = `spot_${keys.length}key${keys.length > 1 ? 's' : ''}_${mode}`;
      const file = path.join(workDir, `${name}.vdg.json`);
      fs.writeFileSync(file, JSON.stringify({ ...spot, uncovered: mode, base: path.join(spotDir, spot.base),
        keys: spot.keys.filter((k) => keys.includes(k.name)).map(abs) }, null, 1));
      out[name] = file;
    }
  const tutorial = path.join(sourceDir, 'examples/tutorial');
  for (const [name, views] of [['tutorial_1key', [[0.7, 0.2, 0.7]]], ['tutorial_2keys', [[0.7, 0.2, 0.7], [-0.6, 0.3, 0.75]]]]) {
    const dir = path.join(workDir, name);
    fs.mkdirSync(dir);
    for (const f of ['suzanne.obj', 'suzanne.vdg.json', 'edits.json']) fs.copyFileSync(path.join(tutorial, f), path.join(dir, f));
    views.forEach((v, i) => runVdg('deform', path.join(dir, 'suzanne.vdg.json'), '--key', `key${i}`, '--view', v.join(','),
      '--ops', path.join(dir, 'edits.json'), '-q'));
    out[name] = path.join(dir, 'suzanne.vdg.json');
  }
  return out;
}

/**
 * Two screenshots of Spot, spot_a.png and spot_b.png in the work folder: at each view, the plain
 * export (what an engine without KHR_interactivity shows: the base) on the left and the export with
 * the graph, as Babylon plays it, on the right.
 */
async function screenshots(page) {
  const manifest = path.join(sourceDir, 'examples/spot/spot.vdg.json');
  if (!fs.existsSync(path.join(workDir, 'spot.glb'))) return; // its export failed: checked above
  const { json } = readGlb(path.join(workDir, 'spot.glb'));
  const c = json.meshes[0].extras.vdg.center;
  for (const [label, dir] of [['a', [-1.0, 0.3, -0.35]], ['b', [0.9, 0.45, 1.0]]]) {
    const n = Math.hypot(...dir);
    const eye = dir.map((x, i) => c[i] + (SHOT_DISTANCE * x) / n);
    const halves = [];
    for (const glb of ['control.glb', 'spot.glb']) {
      await page.evaluate((u) => window.babylonPage.load(u, { background: [0.93, 0.93, 0.95] }), `/work/${glb}`);
      await page.evaluate(([e, t]) => window.babylonPage.view(e, t, 30, 2), [eye, c]);
      halves.push((await page.locator('#main').screenshot()).toString('base64'));
    }
    const png = await page.evaluate(async (parts) => {
      const bitmaps = await Promise.all(parts.map(async (p) => createImageBitmap(await (await fetch(`data:image/png;base64,${p}`)).blob())));
      const canvas = new OffscreenCanvas(bitmaps[0].width * 2, bitmaps[0].height);
      const g = canvas.getContext('2d');
      bitmaps.forEach((b, i) => g.drawImage(b, i * b.width, 0));
      const bytes = new Uint8Array(await (await canvas.convertToBlob({ type: 'image/png' })).arrayBuffer());
      let s = '';
      for (const x of bytes) s += String.fromCharCode(x);
      return btoa(s);
    }, halves);
    fs.writeFileSync(path.join(workDir, `spot_${label}.png`), Buffer.from(png, 'base64'));
    const w = JSON.parse(runVdg('weights', manifest, '--eye', eye.join(','), '--json'));
    console.log(`     spot_${label}.png: eye ${eye.map((x) => x.toFixed(2))}, vdg weights ${JSON.stringify(w)}`);
  }
}

fs.rmSync(workDir, { recursive: true, force: true });
fs.mkdirSync(workDir, { recursive: true });
checkPageSource();
const browser = await loadChromium(webDir);
const server = await serve({ modules: path.join(webDir, 'node_modules'), page: path.join(here, 'page'), work: workDir });
try {
  const { page, errors } = await openPage(browser, server.url, PARITY_SIZE);
  const models = {
    spot: path.join(sourceDir, 'examples/spot/spot.vdg.json'),
    head: path.join(sourceDir, 'examples/figure13/head/head.vdg.json'),
    building: path.join(sourceDir, 'examples/building/building.vdg.json'),
    ...degenerateManifests(),
  };
  let seed = 1;
  // Positions depend on the influences alone (checked for every model): the cosine-mode sets skip them.
  for (const [name, manifest] of Object.entries(models)) await checkModel(page, name, manifest, seed++, !/_cosine2?$/.test(name), name === 'spot');
  await checkControl(page, models.spot);
  await page.setViewportSize({ width: SHOT_SIZE, height: SHOT_SIZE });
  await screenshots(page);
  check(errors.length === 0, `the page logged no error${errors.length ? `: ${errors.slice(0, 3).join(' | ')}` : ''}`);
} finally {
  await browser.close();
  server.close();
}
if (failures) {
  console.log(`${failures} check(s) failed`);
  process.exit(1);
}
console.log('all Babylon.js checks passed');
