// web/view/shading.js's hue rules against vdg render's: tests/render/golden/hue_rules.txt is written
// by vdg_render_tests from hueAdjustedConstants and ShadingParams (Shading.HueRulesMatchTheWebViewersRecord
// checks the C++ against it), a table of colours covering every rule (neutral, purple, red, other
// hues, dark) and their boundaries. Here the JS rules must give the same k1..k4, bit for bit in 32-bit
// floats, and the page's lights the same constants, so the viewer shades like `vdg render`.
// Usage: node hue_rules.mjs VDG_BINARY SOURCE_DIR WEB_DIR WORK_DIR
import { existsSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';

const [, sourceDir, webDir] = process.argv.slice(2);
if (!existsSync(join(webDir, 'node_modules', 'three'))) {
  console.log('SKIP: web/node_modules/three is missing (scripts/install-deps)');
  process.exit(process.env.VDG_REQUIRE_WEB === '1' ? 1 : 77);
}
const { SHADING, HUE_RULES, hueAdjusted, hueConstants, toHsv } = await import(
  pathToFileURL(join(webDir, 'view', 'shading.js')).href
);
const THREE = await import(pathToFileURL(join(webDir, 'node_modules/three/build/three.module.js')).href);

let failures = 0;
/** @param {boolean} ok @param {string} what */
function check(ok, what) {
  if (!ok) {
    failures++;
    console.log(`FAIL: ${what}`);
  }
}
// Both sides compute in 32-bit floats and the file prints 9 significant digits (a float's
// round trip), so the constants must be equal, not merely close.
const same = (/** @type {number} */ a, /** @type {number} */ b) => Math.fround(a) === Math.fround(b);

const record = join(sourceDir, 'tests', 'render', 'golden', 'hue_rules.txt');
const lines = readFileSync(record, 'utf8').split('\n').filter((l) => l.trim() && !l.startsWith('#'));
const params = lines.find((l) => l.startsWith('params '));
check(params !== undefined, `${record}: no params line`);
if (params) {
  const v = params.split(/\s+/).slice(1).map(Number);
  const js = [SHADING.ka, ...SHADING.warm, ...SHADING.cool, ...SHADING.lightWarm, ...SHADING.lightCool];
  check(v.length === js.length && v.every((x, i) => same(x, js[i])), `SHADING ${js} != ShadingParams ${v}`);
}

/** @type {Map<string, number>} rows per rule label */
const rules = new Map();
const outcomes = new Set();
let rows = 0;
for (const line of lines.filter((l) => !l.startsWith('params '))) {
  const [rule, ...numbers] = line.split(/\s+/);
  const v = numbers.map(Number);
  check(v.length === 11 && v.every(Number.isFinite), `${record}: bad row '${line}'`);
  const [rgb, caller, want] = [v.slice(0, 3), v.slice(3, 7), v.slice(7, 11)];
  const got = hueAdjusted(caller, rgb);
  const hsv = toHsv(rgb[0], rgb[1], rgb[2]);
  check(
    got.every((x, i) => same(x, want[i])),
    `${rule} (${rgb}) hsv (${hsv.h}, ${hsv.s}, ${hsv.v}), caller k ${caller}: JS k ${got}, vdg render ${want}`,
  );
  if (caller.every((x) => x === 1)) {
    const k = hueConstants(new THREE.Color(rgb[0], rgb[1], rgb[2])).toArray();
    check(k.every((x, i) => same(x, want[i])), `hueConstants(${rgb}) = ${k}, vdg render ${want}`);
  }
  rules.set(rule, (rules.get(rule) ?? 0) + 1);
  outcomes.add(want.join(' '));
  rows++;
}
// The table exercises every rule and every boundary, and the rules give different constants.
for (const rule of ['neutral', 'purple', 'red', 'other', 'dark', 'neutral-edge', 'hue-20-edge', 'hue-250-edge',
  'hue-330-edge', 'value-0.2-edge', 'value-0.5-edge']) {
  check(rules.has(rule), `${record}: no row for the rule '${rule}'`);
}
const kMinOutcomes = 8;
check(outcomes.size >= kMinOutcomes, `only ${outcomes.size} different k1..k4 in ${rows} rows`);
check(HUE_RULES.neutralSaturation === 0.2 && HUE_RULES.darkValue === 0.2 && HUE_RULES.litValue === 0.5,
  'HUE_RULES differ from shading.h');
console.log(`hue rules: ${rows} colours, ${rules.size} rule labels, ${outcomes.size} outcomes; ${failures} failures`);
process.exit(failures ? 1 : 0);
