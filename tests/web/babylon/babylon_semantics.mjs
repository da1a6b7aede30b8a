// What Babylon.js's KHR_interactivity player does with the node types and pointers vdg's graph uses
// (docs/interactivity.md, "Babylon.js"): hand-made glTF triangles whose graphs write values into the
// morph weights, read back as influences in the Babylon-only page (page/). Checks:
//   - activeCamera/position reads the camera's glTF (right-handed) coordinates, in Babylon's default
//     left-handed scene and in a right-handed one; onTick runs before the frame renders (one frame);
//   - inverse(/nodes/0/globalMatrix) applied to (eye, 1) with math/transform gives the eye in the
//     mesh node's space (translated, scaled, child of a translated parent);
//   - the math nodes (dot, normalize, length, cross, select, ge, lt, and, or, not, pow, max, div, sub,
//     mul, clamp, abs, acos, transform with a column-major float4x4 literal) give the spec's values;
//   - pointer/set on /nodes/{}/weights/{} moves the influence, on /meshes/{}/weights/{} it does not;
//   - one variable/set of several variables, read by variable/get, feeds several pointer/sets;
//   - Babylon 9.28 rejects (console error, no weights) a graph with an empty "variables" array, a
//     flow to an earlier node, or math/extract3 of a float3: what vdg's graph must avoid.
// Usage: node babylon_semantics.mjs VDG SOURCE_DIR WEB_DIR WORK_DIR (VDG and SOURCE_DIR unused).
// Exit 77 (skip) when Chromium, playwright-core or Babylon.js is missing, unless VDG_REQUIRE_WEB=1.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { Graph, triangle } from './graph_builder.mjs';
import { loadChromium, openPage, serve } from './harness.mjs';

const [, , webDir, workDir] = process.argv.slice(2);
const here = path.dirname(fileURLToPath(import.meta.url));
const TOLERANCE = 1e-5; // the camera's position comes from its float32 world matrix (~2e-7 at these distances)
const EYES = [[3, 4, 5], [-2, -1, 7]];

let failures = 0;
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures += 1;
}
const close = (got, want) => got.length === want.length && got.every((g, i) => Math.abs(g - want[i]) <= TOLERANCE);
const fmt = (a) => `[${a.map((x) => +x.toFixed(5)).join(', ')}]`;

/** x, y, z of a float3 output through math/dot with unit literals (math/extract3 is rejected). */
function components(g, source) {
  return [[1, 0, 0], [0, 1, 0], [0, 0, 1]].map((u) => g.out(g.node('math/dot', { a: source, b: g.lit('float3', u) })));
}

/** The camera graph: weights 0-2 the eye, 3-5 the eye in node 0's space. */
function cameraGraph() {
  const g = new Graph();
  const eye = g.out(g.get('/extensions/KHR_interactivity/activeCamera/position', 'float3'));
  const [x, y, z] = components(g, eye);
  const inverse = g.node('math/inverse', { a: g.out(g.get('/nodes/0/globalMatrix', 'float4x4')) });
  const eye4 = g.node('math/combine4', { a: x, b: y, c: z, d: g.lit('float', 1) });
  const local = g.out(g.node('math/transform', { a: g.out(eye4), b: g.out(inverse) }));
  const dots = [0, 1, 2].map((i) => g.out(g.node('math/dot', { a: local, b: g.lit('float4', [0, 1, 2, 3].map((j) => +(i === j))) })));
  g.setWeights([x, y, z, ...dots]);
  return g;
}

/** The math graph: [weights sources, expected values]. */
function mathGraph() {
  const g = new Graph();
  const f = (v) => g.lit('float', v);
  const b = (v) => g.lit('bool', v);
  const n = (op, values) => g.out(g.node(op, values));
  const select = (c) => n('math/select', { condition: c, a: f(1), b: f(0) });
  const ge = n('math/ge', { a: f(2), b: f(2) });
  const cases = [
    [n('math/dot', { a: n('math/normalize', { a: g.lit('float3', [3, 4, 0]) }), b: g.lit('float3', [1, 0, 0]) }), 0.6],
    [n('math/length', { a: g.lit('float3', [3, 4, 12]) }), 13],
    [n('math/dot', { a: n('math/cross', { a: g.lit('float3', [1, 0, 0]), b: g.lit('float3', [0, 1, 0]) }), b: g.lit('float3', [0, 0, 1]) }), 1],
    [n('math/select', { condition: ge, a: f(10), b: f(20) }), 10],
    [select(n('math/lt', { a: f(1), b: f(1) })), 0],
    [select(n('math/and', { a: ge, b: b(false) })), 0],
    [select(n('math/or', { a: b(false), b: ge })), 1],
    [select(n('math/not', { a: b(true) })), 0],
    [n('math/pow', { a: f(2), b: f(3) }), 8],
    [n('math/max', { a: f(2), b: f(5) }), 5],
    [n('math/div', { a: f(1), b: f(4) }), 0.25],
    [n('math/sub', { a: f(1), b: f(3) }), -2],
    [n('math/dot', { a: n('math/mul', { a: g.lit('float3', [1, 2, 3]), b: g.lit('float3', [2, 2, 2]) }), b: g.lit('float3', [0, 0, 1]) }), 6],
    [n('math/clamp', { a: f(5), b: f(0), c: f(1) }), 1],
    [n('math/abs', { a: f(-3) }), 3],
    [n('math/acos', { a: f(0) }), Math.PI / 2],
    [n('math/dot', { a: n('math/transform', { a: g.lit('float4', [1, 2, 3, 1]),
      b: g.lit('float4x4', [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 10, 20, 30, 1]) }), b: g.lit('float4', [0, 1, 0, 0]) }), 22],
  ];
  g.setWeights(cases.map((c) => c[0]));
  return [g, cases.map((c) => c[1])];
}

/** Weights set through /meshes (ignored) and /nodes (applied), and through a multi-variable variable/set. */
function pointerGraph() {
  const g = new Graph();
  g.setWeights([g.lit('float', 7)], '/meshes/0/weights');
  const ft = g.type('float');
  g.variables = [0, 1].map(() => ({ type: ft, value: [0] }));
  const eyeX = components(g, g.out(g.get('/extensions/KHR_interactivity/activeCamera/position', 'float3')))[0];
  const set = g.node('variable/set', { 0: eyeX, 1: g.out(g.node('math/add', { a: eyeX, b: g.lit('float', 1) })) },
    { variables: { value: [0, 1] } });
  g.then(set);
  g.setWeights([0, 1].map((k) => g.out(g.node('variable/get', {}, { variable: { value: [k] } }))), '/nodes/0/weights', 1);
  return g;
}

/** Graphs Babylon 9.28 rejects as a whole. */
function rejectedGraphs() {
  const emptyVariables = new Graph();
  emptyVariables.setWeights([emptyVariables.lit('float', 1)]);
  emptyVariables.variables = [];
  const backwards = new Graph();
  backwards.setWeights([backwards.lit('float', 1)]);
  const set = backwards.nodes[1].flows['0000'].node;
  backwards.nodes[set].flows = { out: { node: 1, socket: 'in' } };
  const extract = new Graph();
  const eye = extract.get('/extensions/KHR_interactivity/activeCamera/position', 'float3');
  extract.setWeights([extract.out(extract.node('math/extract3', { a: extract.out(eye) }), '0')]);
  return { empty_variables: emptyVariables, flow_to_earlier_node: backwards, extract3_of_float3: extract };
}

function write(name, gltf) {
  fs.writeFileSync(path.join(workDir, `${name}.gltf`), JSON.stringify(gltf));
  return `/work/${name}.gltf`;
}

/** Loads url, views each eye (one frame) and returns the influences per eye. */
async function influences(page, url, eyes, rightHanded = false) {
  await page.evaluate(([u, rh]) => window.babylonPage.load(u, { rightHanded: rh }), [url, rightHanded]);
  return page.evaluate((list) => list.map((e) => { window.babylonPage.view(e, [0, 0, 0]); return window.babylonPage.influences(); }), eyes);
}

fs.rmSync(workDir, { recursive: true, force: true });
fs.mkdirSync(workDir, { recursive: true });
const browser = await loadChromium(webDir);
const server = await serve({ modules: path.join(webDir, 'node_modules'), page: path.join(here, 'page'), work: workDir });
try {
  const { page, errors } = await openPage(browser, server.url);
  const placements = {
    translated: { nodes: [{ mesh: 0, translation: [1, 2, 3] }], roots: [0], local: (e) => [e[0] - 1, e[1] - 2, e[2] - 3] },
    scaled: { nodes: [{ mesh: 0, translation: [1, 2, 3], scale: [2, 2, 2] }], roots: [0], local: (e) => [(e[0] - 1) / 2, (e[1] - 2) / 2, (e[2] - 3) / 2] },
    child: { nodes: [{ mesh: 0, translation: [0, 0, 1] }, { children: [0], translation: [1, 2, 3] }], roots: [1], local: (e) => [e[0] - 1, e[1] - 2, e[2] - 4] },
  };
  for (const [name, p] of Object.entries(placements)) {
    const url = write(`camera_${name}`, cameraGraph().into(triangle(6, p.nodes, p.roots)));
    for (const rightHanded of [false, true]) {
      const got = await influences(page, url, EYES, rightHanded);
      EYES.forEach((e, i) => check(close(got[i], [...e, ...p.local(e)]),
        `${name} node, ${rightHanded ? 'right' : 'left'}-handed scene, one frame at glTF eye ${fmt(e)}: position and eye in node space ${fmt(got[i])}`));
    }
  }
  const [math, want] = mathGraph();
  const gotMath = (await influences(page, write('math', math.into(triangle(want.length))), [EYES[0]]))[0];
  want.forEach((w, i) => check(Math.abs(gotMath[i] - w) <= TOLERANCE, `math case ${i}: ${gotMath[i]} (spec: ${w})`));
  const gotPointer = (await influences(page, write('pointers', pointerGraph().into(triangle(3))), [EYES[1]]))[0];
  check(gotPointer[0] === 0, `pointer/set /meshes/0/weights/0 is ignored (influence ${gotPointer[0]})`);
  check(close(gotPointer.slice(1), [EYES[1][0], EYES[1][0] + 1]),
    `one variable/set of two variables, read by variable/get, sets /nodes/0/weights/1,2: ${fmt(gotPointer.slice(1))}`);
  check(errors.length === 0, `no console error for the accepted graphs${errors.length ? `: ${errors[0]}` : ''}`);
  for (const [name, g] of Object.entries(rejectedGraphs())) {
    const before = errors.length;
    const got = (await influences(page, write(name, g.into(triangle(1))), [EYES[0]]))[0];
    check(got[0] === 0 && errors.slice(before).some((e) => /rejecting behavior graph/.test(e)),
      `${name}: Babylon rejects the graph (console error, influence ${got[0]})`);
  }
} finally {
  await browser.close();
  server.close();
}
if (failures) {
  console.log(`${failures} check(s) failed`);
  process.exit(1);
}
console.log('all Babylon.js semantics checks passed');
