// vdg's compressed exports in three.js (docs/gltf-export.md, "Smaller files"): GLTFLoader, with the
// meshopt decoder three ships (examples/jsm/libs/meshopt_decoder.module.js), parses the .glb of
// `vdg export --compress quantize` and `--compress meshopt` of the shipped examples in Node; every
// mesh's positions as a viewer places them (by the node: KHR_mesh_quantization's dequantisation;
// skinned at rest: vdg folds it into the inverse bind matrices) and its morph targets equal the
// float export's within half a grid step.
// Usage: node compress_three.mjs VDG_BINARY SOURCE_DIR WEB_DIR WORK_DIR
// Exit 0 pass, 1 fail, 77 skip (three.js not installed, unless VDG_REQUIRE_WEB=1).
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, rmSync } from 'node:fs';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { nodeGltfLoader } from '../node/three_node.mjs';

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
  const loader = nodeGltfLoader(GLTFLoader);
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
 * Positions of `attr` (normalized integers denormalised by three) as a viewer shows them at rest:
 * placed by the mesh node's world matrix, or, for a skinned mesh (glTF 2.0: it ignores its node's
 * transform), skinned by its skeleton at rest, `delta` (a morph target, or none) added first.
 * @param {any} mesh @param {any} attr @param {any} [delta]
 */
function placed(mesh, attr, delta) {
  const out = new Float64Array(attr.count * 3);
  const v = new THREE.Vector3();
  const d = new THREE.Vector3();
  for (let i = 0; i < attr.count; i++) {
    v.fromBufferAttribute(attr, i);
    if (delta) v.add(d.fromBufferAttribute(delta, i));
    if (mesh.isSkinnedMesh) mesh.applyBoneTransform(i, v);
    else v.applyMatrix4(mesh.matrixWorld);
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

/** @param {Float64Array} a @param {Float64Array} b @returns {Float64Array} a - b */
function minus(a, b) {
  return a.map((x, i) => x - b[i]);
}

/**
 * Half a step of the grid vdg quantises `mesh` on: the largest of its base's half extents and of
 * its targets' delta components, / 32767 / 2 (docs/gltf-export.md).
 * @param {any} mesh the float export's mesh
 */
function halfStep(mesh) {
  const pos = mesh.geometry.attributes.position;
  let s = 0;
  for (let c = 0; c < 3; c++) {
    let lo = Infinity;
    let hi = -Infinity;
    for (let i = 0; i < pos.count; i++) lo = Math.min(lo, pos.getComponent(i, c)), hi = Math.max(hi, pos.getComponent(i, c));
    s = Math.max(s, (hi - lo) / 2);
  }
  for (const t of mesh.geometry.morphAttributes.position ?? [])
    for (let i = 0; i < t.array.length; i++) s = Math.max(s, Math.abs(t.array[i]));
  return s / kSteps / 2;
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
      check(!!dq === !g.isSkinnedMesh, `${name} ${c}: mesh ${k}: dequantize ${dq ? 'present' : 'absent'} on a ${g.isSkinnedMesh ? 'skinned' : 'plain'} mesh`);
      if (dq) check(Math.abs(dq.scale[0] / kSteps / 2 - halfStep(r)) <= 1e-12, `${name} ${c}: mesh ${k}: dequantize.scale ${dq.scale[0]} is not the grid's`);
      // Skinning turns an error vector by a rotation: its largest component grows by sqrt(3) at most.
      const size = r.geometry.boundingSphere ?? (r.geometry.computeBoundingSphere(), r.geometry.boundingSphere);
      const tol = (g.isSkinnedMesh ? Math.sqrt(3) : 1) * halfStep(r) + kFloatTol * Math.max(1, size.radius);
      const pg = placed(g, g.geometry.attributes.position);
      const pr = placed(r, r.geometry.attributes.position);
      const wp = worst(pg, pr);
      check(wp <= tol, `${name} ${c}: mesh ${k}: positions off by ${wp}, tolerance ${tol}`);
      const tg = g.geometry.morphAttributes.position ?? [];
      const tr = r.geometry.morphAttributes.position ?? [];
      check(tg.length === tr.length, `${name} ${c}: mesh ${k}: ${tg.length} morph targets, expected ${tr.length}`);
      // A target's placed delta: placed(base + delta) - placed(base), each end within tol.
      let wt = 0;
      for (let t = 0; t < Math.min(tg.length, tr.length); t++) {
        const dg = minus(placed(g, g.geometry.attributes.position, tg[t]), pg);
        const dr = minus(placed(r, r.geometry.attributes.position, tr[t]), pr);
        wt = Math.max(wt, worst(dg, dr));
      }
      check(wt <= 2 * tol, `${name} ${c}: mesh ${k}: morph targets off by ${wt}, tolerance ${2 * tol}`);
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
