// vdg's compressed exports in three.js (docs/gltf-export.md, "Smaller files"): GLTFLoader, with the
// meshopt decoder three ships (examples/jsm/libs/meshopt_decoder.module.js), parses the .glb of
// `vdg export --compress quantize` and `--compress meshopt` of the shipped examples in Node; every
// mesh's positions, placed by its node (KHR_mesh_quantization's dequantisation), and its morph
// targets (times the node's scale) equal the float export's within half a grid step.
// Usage: node compress_three.mjs VDG_BINARY SOURCE_DIR WEB_DIR WORK_DIR
// Exit 0 pass, 1 fail, 77 skip (three.js not installed, unless VDG_REQUIRE_WEB=1).
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, rmSync } from 'node:fs';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';

const [vdg, sourceDir, webDir, workDir] = process.argv.slice(2);
const threeDir = join(webDir, 'node_modules', 'three');
if (!existsSync(threeDir)) {
  console.log('SKIP: web/node_modules/three is missing (scripts/install-deps)');
  process.exit(process.env.VDG_REQUIRE_WEB === '1' ? 1 : 77);
}
const THREE = await import(pathToFileURL(join(threeDir, 'build', 'three.module.js')).href);
const { GLTFLoader } = await import(pathToFileURL(join(threeDir, 'examples/jsm/loaders/GLTFLoader.js')).href);
const { MeshoptDecoder } = await import(pathToFileURL(join(threeDir, 'examples/jsm/libs/meshopt_decoder.module.js')).href);
await MeshoptDecoder.ready;
rmSync(workDir, { recursive: true, force: true });
mkdirSync(workDir, { recursive: true });

// A normalized SHORT holds q / 32767: half a step of the grid's scale, plus float rounding of the
// transform (relative to the model's size).
const kSteps = 32767;
const kFloatTol = 1e-5;

let failures = 0;
/** @param {boolean} ok @param {string} what */
function check(ok, what) {
  if (!ok) {
    failures++;
    if (failures <= 20) console.log(`FAIL: ${what}`);
  }
}

/** @param {string} path @returns {Promise<any>} the parsed glTF */
function parse(path) {
  const bytes = readFileSync(path);
  const buffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
  const loader = new GLTFLoader();
  loader.setMeshoptDecoder(MeshoptDecoder);
  return new Promise((resolve, reject) => loader.parse(buffer, '', resolve, reject));
}

/** @param {any} gltf @returns {any[]} the scene's meshes, in traversal order */
function meshes(gltf) {
  const out = [];
  gltf.scene.updateMatrixWorld(true);
  gltf.scene.traverse((o) => {
    if (o.isMesh) out.push(o);
  });
  return out;
}

/**
 * Positions of `attr` (normalized integers denormalised by three) placed by `matrix` (none: as
 * they are).
 * @param {any} attr @param {any} matrix
 */
function placed(attr, matrix) {
  const out = new Float64Array(attr.count * 3);
  const v = new THREE.Vector3();
  for (let i = 0; i < attr.count; i++) {
    v.fromBufferAttribute(attr, i);
    if (matrix) v.applyMatrix4(matrix);
    out[i * 3] = v.x;
    out[i * 3 + 1] = v.y;
    out[i * 3 + 2] = v.z;
  }
  return out;
}

/** @param {Float64Array} a @param {Float64Array} b */
function worst(a, b) {
  let w = 0;
  for (let i = 0; i < a.length; i++) w = Math.max(w, Math.abs(a[i] - b[i]));
  return a.length === b.length ? w : Infinity;
}

/**
 * The node's world matrix that places the mesh's vertices; null for a skinned mesh (glTF 2.0: a
 * skinned mesh ignores its node's transform, so vdg keeps its positions float).
 * @param {any} mesh
 */
function placement(mesh) {
  return mesh.isSkinnedMesh ? null : mesh.matrixWorld;
}

/**
 * Morph target deltas of `attr`, moved by the linear part of `matrix` (none: as they are).
 * @param {any} attr @param {any} matrix
 */
function deltas(attr, matrix) {
  const out = new Float64Array(attr.count * 3);
  const v = new THREE.Vector3();
  const linear = matrix ? new THREE.Matrix3().setFromMatrix4(matrix) : null;
  for (let i = 0; i < attr.count; i++) {
    v.fromBufferAttribute(attr, i);
    if (linear) v.applyMatrix3(linear);
    out[i * 3] = v.x;
    out[i * 3 + 1] = v.y;
    out[i * 3 + 2] = v.z;
  }
  return out;
}

/** @param {string} name @param {string} manifest */
async function compare(name, manifest) {
  const files = {};
  for (const c of ['none', 'quantize', 'meshopt']) {
    files[c] = join(workDir, `${name}-${c}.glb`);
    execFileSync(vdg, ['export', join(sourceDir, manifest), '-o', files[c], '--compress', c, '-q'], { stdio: 'pipe' });
  }
  const reference = meshes(await parse(files.none));
  for (const c of ['quantize', 'meshopt']) {
    const got = meshes(await parse(files[c]));
    check(got.length === reference.length && got.length > 0, `${name} ${c}: ${got.length} meshes, expected ${reference.length}`);
    for (let k = 0; k < Math.min(got.length, reference.length); k++) {
      const g = got[k];
      const r = reference[k];
      const dq = g.userData?.vdg?.dequantize;
      const step = dq ? dq.scale[0] / kSteps / 2 : 0;
      check(!!dq === !g.isSkinnedMesh, `${name} ${c}: mesh ${k}: dequantize ${dq ? 'present' : 'absent'} on a ${g.isSkinnedMesh ? 'skinned' : 'plain'} mesh`);
      const size = r.geometry.boundingSphere ?? (r.geometry.computeBoundingSphere(), r.geometry.boundingSphere);
      const tol = step + kFloatTol * Math.max(1, size.radius);
      const pg = placed(g.geometry.attributes.position, placement(g));
      const pr = placed(r.geometry.attributes.position, null);
      const wp = worst(pg, pr);
      check(wp <= tol, `${name} ${c}: mesh ${k}: positions off by ${wp}, tolerance ${tol}`);
      const tg = g.geometry.morphAttributes.position ?? [];
      const tr = r.geometry.morphAttributes.position ?? [];
      check(tg.length === tr.length, `${name} ${c}: mesh ${k}: ${tg.length} morph targets, expected ${tr.length}`);
      let wt = 0;
      for (let t = 0; t < Math.min(tg.length, tr.length); t++)
        wt = Math.max(wt, worst(deltas(tg[t], placement(g)), deltas(tr[t], null)));
      check(wt <= tol, `${name} ${c}: mesh ${k}: morph targets off by ${wt}, tolerance ${tol}`);
      console.log(`${name} ${c}: mesh ${k}: ${g.geometry.attributes.position.count} vertices, ${tg.length} targets, ` +
                  `positions within ${wp.toExponential(2)}, targets within ${wt.toExponential(2)} (tolerance ${tol.toExponential(2)})`);
    }
  }
}

await compare('spot', 'examples/spot/spot.vdg.json');
await compare('walker', 'examples/walk/walker.vdg.json');
await compare('walker-world', 'examples/walk/walker-world.vdg.json');
if (failures > 0) {
  console.log(`${failures} failure(s)`);
  process.exit(1);
}
console.log('PASS');
