// web/vdg-three.js's three.js controllers in Node (no WebGL: the renderer's hooks are called as
// WebGLRenderer and WebGLShadowMap call them): .glb files from `vdg export` loaded by three's
// GLTFLoader, the rendering camera mapped into model space (root transforms, dequantize,
// orthographic cameras), the multi-camera rule (shadow and depth passes use mainCamera), frames and
// time, multi-primitive models, dispose, and crowds (InstancedMesh, 1,000 instances: every row
// equals vdg weights at that instance's eye, and the update time), and animated models played by
// three's AnimationMixer (three's own morph and skinning equal vdg eval at several frames).
// Usage: node controller.mjs VDG_BINARY SOURCE_DIR WEB_DIR WORK_DIR
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { nodeGltfLoader } from './three_node.mjs';

const kWeightTol = 1e-6;  // against the CLI (7 printed digits)
const kSameTol = 1e-12;  // the runtime against itself through another path
const kInstances = 1000;

const [vdg, sourceDir, webDir, workDir] = process.argv.slice(2);
if (!existsSync(join(webDir, 'node_modules', 'three'))) {
  console.log('SKIP: web/node_modules/three is missing (scripts/install-deps)');
  process.exit(process.env.VDG_REQUIRE_WEB === '1' ? 1 : 77);
}
const url = (/** @type {string} */ p) => pathToFileURL(join(webDir, p)).href;
const THREE = await import(url('node_modules/three/build/three.module.js'));
const { GLTFLoader } = await import(url('node_modules/three/examples/jsm/loaders/GLTFLoader.js'));
const { attachVdg, attachVdgInstanced, vdgWeights } = await import(url('vdg-three.js'));
rmSync(workDir, { recursive: true, force: true });
mkdirSync(workDir, { recursive: true });

let failures = 0;
/** @param {boolean} ok @param {string} what */
function check(ok, what) {
  if (!ok) {
    failures++;
    console.log(`FAIL: ${what}`);
  }
}
/** @param {ArrayLike<number>} a @param {ArrayLike<number>} b */
function maxDiff(a, b) {
  let worst = a.length === b.length ? 0 : Infinity;
  for (let i = 0; i < a.length; ++i) worst = Math.max(worst, Math.abs(a[i] - b[i]));
  return worst;
}

/** @param {string} relative @param {string} name */
async function load(relative, name) {
  const manifest = join(sourceDir, relative);
  const path = join(workDir, `${name}.glb`);
  execFileSync(vdg, ['export', manifest, '-q', '-o', path]);
  const bytes = readFileSync(path);
  const gltf = await nodeGltfLoader(GLTFLoader).parseAsync(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length), '');
  return { manifest, gltf };
}

/**
 * `vdg weights --views` at model-space eyes, as morph weights in target order (static models).
 * @param {string} manifest @param {number[][]} eyes @param {string[]} names
 */
function cliWeights(manifest, eyes, names) {
  const file = join(workDir, 'eyes.json');
  writeFileSync(file, JSON.stringify(eyes.map((eye) => ({ eye }))));
  const out = JSON.parse(execFileSync(vdg, ['weights', manifest, '--views', file], { encoding: 'utf8' }));
  return out.map((/** @type {any} */ r) => names.map((n) => r.keys[n] || 0));
}

const depth = new THREE.MeshDepthMaterial();
/** Calls the mesh's hooks as WebGLRenderer.renderObject does. @param {any} mesh @param {any} camera @param {any} [material] */
function render(mesh, camera, material = mesh.material) {
  camera.updateMatrixWorld();
  mesh.onBeforeRender(null, null, camera, mesh.geometry, material, null);
  return Array.from(mesh.morphTargetInfluences);
}

const kPosTol = 1e-5;  // float positions, float bone matrices
/** @param {string} path @returns {number[][]} the "v" lines of an OBJ */
function objVertices(path) {
  return readFileSync(path, 'utf8').split('\n').filter((l) => l.startsWith('v '))
    .map((l) => l.slice(2).trim().split(/\s+/).slice(0, 3).map(Number));
}
/**
 * Plays the file's "base" clip with an AnimationMixer at `frame`, lets the controller's hook set the
 * weights for `camera` (after the mixer, as in a render loop), and compares three's own CPU morph and
 * skinning (Mesh.getVertexPosition) with `vdg eval --frame` at the camera's model-space eye.
 * @param {any} gltf @param {any} controller @param {string} manifest @param {any} camera @param {number} frame
 */
function animatedPositions(gltf, controller, manifest, camera, frame) {
  const mesh = controller.models[0].meshes[0];
  const extras = controller.models[0].extras;
  const mixer = new THREE.AnimationMixer(gltf.scene);
  mixer.clipAction(gltf.animations.find((/** @type {any} */ a) => a.name === 'base')).play();
  mixer.setTime(frame / extras.animation.fps);
  controller.time = frame / extras.animation.fps;
  gltf.scene.updateMatrixWorld(true);
  render(mesh, camera);
  const eye = camera.position.clone().applyMatrix4(mesh.matrixWorld.clone().invert()).toArray();
  const obj = join(workDir, 'eval.obj');
  execFileSync(vdg, ['eval', manifest, '-q', '--eye', eye.join(','), '--frame', String(frame), '-o', obj]);
  const want = objVertices(obj);
  const v = new THREE.Vector3();
  let worst = want.length === mesh.geometry.attributes.position.count ? 0 : Infinity;
  for (let i = 0; i < want.length; ++i) {
    mesh.getVertexPosition(i, v);
    worst = Math.max(worst, Math.abs(v.x - want[i][0]), Math.abs(v.y - want[i][1]), Math.abs(v.z - want[i][2]));
  }
  mixer.stopAllAction();
  return worst;
}

// ---- A static model under a transformed root: the rendering camera decides ----
{
  const { manifest, gltf } = await load('examples/spot/spot.vdg.json', 'spot');
  const root = gltf.scene;
  root.position.set(3, -1, 2);
  root.quaternion.setFromEuler(new THREE.Euler(0.3, 1.1, -0.2));
  root.scale.setScalar(2.5);
  root.updateMatrixWorld(true);
  const main = new THREE.PerspectiveCamera();
  main.position.set(10, 4, 7);
  const other = new THREE.PerspectiveCamera();
  other.position.set(-6, 1, -9);
  const ortho = new THREE.OrthographicCamera();
  ortho.position.set(3, 20, 5);
  ortho.lookAt(0, 0, 0);
  const controller = attachVdg(root, { mainCamera: main });
  check(controller.models.length === 1, `spot: ${controller.models.length} models`);
  const model = controller.models[0];
  const mesh = model.meshes[0];
  const extras = model.extras;
  const names = mesh.userData.targetNames;
  // Model-space eyes by hand: the inverse of the mesh's world matrix (root * mesh node).
  const inverse = mesh.matrixWorld.clone().invert();
  const eyeOf = (/** @type {any} */ cam) => cam.position.clone().applyMatrix4(inverse).toArray();
  const expected = cliWeights(manifest, [eyeOf(main), eyeOf(other)], names);
  const a = render(mesh, main), b = render(mesh, other);
  check(maxDiff(a, expected[0]) <= kWeightTol, `spot: main camera weights differ by ${maxDiff(a, expected[0])}`);
  check(maxDiff(b, expected[1]) <= kWeightTol, `spot: other camera weights differ by ${maxDiff(b, expected[1])}`);
  check(maxDiff(a, b) > 0.01, 'spot: the two cameras see different blends');
  check(maxDiff(controller.lastWeights(model), b) === 0, 'spot: lastWeights is the last view rendered');
  const sphere = controller.lastSphereWeights(model);
  check(!!sphere && Math.abs(sphere.weights.reduce((s, x) => s + x, 0) + sphere.base - 1) < 1e-9,
    'spot: lastSphereWeights sum to 1');
  // Orthographic: its direction (the camera's +Z axis, towards the eye) mapped into model space.
  ortho.updateMatrixWorld();
  const up = new THREE.Vector3().setFromMatrixColumn(ortho.matrixWorld, 2).transformDirection(inverse);
  check(up.distanceTo(new THREE.Vector3(3, 20, 5).normalize().transformDirection(inverse)) < 1e-9,
    'spot: the orthographic camera looks at the origin');
  const o = render(mesh, ortho);
  check(maxDiff(o, vdgWeights(extras, up)) <= kSameTol, 'spot: an orthographic camera uses its direction');
  // Auxiliary passes use mainCamera: a depth material, a marked camera, a shadow map.
  check(maxDiff(render(mesh, other, depth), a) <= kSameTol, 'spot: a depth pass uses mainCamera');
  other.userData.vdgAuxiliary = true;
  check(maxDiff(render(mesh, other), a) <= kSameTol, 'spot: a vdgAuxiliary camera uses mainCamera');
  delete other.userData.vdgAuxiliary;
  render(mesh, other);
  mesh.onBeforeShadow(null, mesh, other, new THREE.OrthographicCamera(), mesh.geometry, depth, null);
  check(maxDiff(Array.from(mesh.morphTargetInfluences), a) <= kSameTol, 'spot: a shadow pass uses mainCamera');
  check(maxDiff(controller.lastWeights(model), b) === 0, 'spot: auxiliary passes leave lastWeights alone');
  // Sharpness: a controller value overrides the model's.
  controller.sharpness = 4;
  check(maxDiff(render(mesh, main), vdgWeights(extras, eyeOf(main).map((x, i) => x - extras.center[i]), { sharpness: 4 }))
    <= kSameTol, 'spot: controller.sharpness');
  controller.dispose();
  check(mesh.morphTargetInfluences.every((/** @type {number} */ x) => x === 0), 'spot: dispose resets the base');
  mesh.onBeforeRender(null, null, main, mesh.geometry, mesh.material, null);
  check(mesh.morphTargetInfluences.every((/** @type {number} */ x) => x === 0), 'spot: dispose unhooks');
  console.log('ok spot: cameras, orthographic, auxiliary passes, sharpness, dispose');

  // Dequantize: the mesh node carries offset + scale * p, so a world eye maps to itself.
  const quantised = { ...mesh.userData.vdg, dequantize: { scale: [0.01, 0.02, 0.005], offset: [1, -2, 0.5] } };
  const qmesh = mesh.clone();
  qmesh.userData = { vdg: quantised };
  qmesh.position.set(1, -2, 0.5);
  qmesh.scale.set(0.01, 0.02, 0.005);
  qmesh.updateMatrixWorld(true);
  const q = attachVdg(qmesh, { mainCamera: main });
  const eye = main.position.toArray().map((x, i) => x - quantised.center[i]);
  check(maxDiff(render(qmesh, main), vdgWeights(quantised, eye)) <= 1e-9, 'spot: dequantize maps the camera');
  q.dispose();

  // Multi-primitive: a Group of Meshes sharing one target list and one extras object.
  const group = new THREE.Group();
  const first = mesh.clone(), second = mesh.clone();
  second.userData = first.userData;
  group.add(first, second);
  group.updateMatrixWorld(true);
  const g = attachVdg(group, { mainCamera: main });
  check(g.models.length === 1 && g.models[0].meshes.length === 2, 'multi-primitive: one model of two meshes');
  const w1 = render(first, main), w2 = render(second, main);
  check(maxDiff(w1, w2) === 0 && maxDiff(w1, [0]) !== 0, 'multi-primitive: both primitives get the weights');
  g.dispose();
  console.log('ok spot: dequantize, multi-primitive');

  // ---- Crowds ----
  const crowd = new THREE.InstancedMesh(mesh.geometry, mesh.material, kInstances);
  crowd.userData = mesh.userData;
  const rnd = (() => { let s = 7; return () => (s = (s * 16807) % 2147483647) / 2147483647; })();
  const m = new THREE.Matrix4();
  for (let i = 0; i < kInstances; ++i) {
    m.compose(new THREE.Vector3(rnd() * 40 - 20, 0, rnd() * 40 - 20),
      new THREE.Quaternion().setFromEuler(new THREE.Euler(0, rnd() * 6.28, 0)), new THREE.Vector3().setScalar(0.5 + rnd()));
    crowd.setMatrixAt(i, m);
  }
  crowd.position.set(0, -1, 0);
  crowd.updateMatrixWorld(true);
  const c = attachVdgInstanced(crowd, extras, { mainCamera: main });
  main.updateMatrixWorld();
  c.update(main);
  const data = crowd.morphTexture.source.data.data;
  const width = names.length + 1;
  const sample = [0, 1, 2, 499, 998, 999];
  const eyes = sample.map((i) => {
    crowd.getMatrixAt(i, m);
    return main.position.clone().applyMatrix4(m.premultiply(crowd.matrixWorld).invert()).toArray();
  });
  const want = cliWeights(manifest, eyes, names);
  sample.forEach((i, k) => {
    const row = Array.from(data.subarray(i * width, (i + 1) * width));
    check(Math.abs(row[0] - 1) < 1e-9, `crowd: instance ${i}'s base influence is ${row[0]} (relative targets)`);
    check(maxDiff(row.slice(1), want[k]) <= kWeightTol, `crowd: instance ${i} differs by ${maxDiff(row.slice(1), want[k])}`);
  });
  const frames = 30;
  const t0 = performance.now();
  for (let f = 0; f < frames; ++f) {
    main.position.x += 0.05;  // a moving camera, as in an application
    main.updateMatrixWorld();
    crowd.onBeforeRender(null, null, main, crowd.geometry, crowd.material, null);
  }
  const ms = (performance.now() - t0) / frames;
  console.log(`ok crowd: ${kInstances} instances match vdg weights; update ${ms.toFixed(2)} ms per frame ` +
    `(${names.length} targets, ${extras.sphere.triangles.length} triangles)`);
  check(crowd.morphTexture.version > 0, 'crowd: the morph texture is marked for upload');
  c.dispose();
}

// ---- Animated: frames, time and the "frames" base; a skinned base's key targets ----
{
  const { gltf, manifest: world } = await load('examples/walk/walker-world.vdg.json', 'walker-world');
  const controller = attachVdg(gltf.scene);
  const model = controller.models[0];
  const mesh = model.meshes[0];
  const extras = model.extras;
  const cam = new THREE.PerspectiveCamera();
  cam.position.set(2, 1.5, 4);
  const view = cam.position.toArray().map((x, i) => x - extras.center[i]);
  controller.frame = 7.5;
  check(maxDiff(render(mesh, cam), vdgWeights(extras, view, { frame: 7.5 })) <= kSameTol, 'walker-world: frame 7.5');
  controller.time = 1.0;  // 24 fps: frame 24
  const w = render(mesh, cam);
  check(maxDiff(w, vdgWeights(extras, view, { frame: 24 })) <= kSameTol, 'walker-world: time 1 s is frame 24');
  const frameTarget = mesh.userData.targetNames.indexOf('base frame 24');
  check(frameTarget >= 0 && Math.abs(w[frameTarget] - 1) < 1e-12, 'walker-world: base frame 24 has weight 1');
  controller.time = 40 / 24 + 0.5;  // looping: wraps to frame 12
  check(maxDiff(render(mesh, cam), vdgWeights(extras, view, { frame: 12 })) <= 1e-9, 'walker-world: time wraps');
  // The base clip's weights track is overridden by the hook: three's morphed positions = vdg eval.
  let worst = 0;
  for (const frame of [0, 13, 30]) worst = Math.max(worst, animatedPositions(gltf, controller, world, cam, frame));
  check(worst <= kPosTol, `walker-world: positions differ from vdg eval by ${worst}`);
  controller.dispose();
  console.log(`ok walker-world: frame, time, base frames; positions = vdg eval within ${worst.toExponential(2)}`);

  const skinned = await load('examples/walk/walker.vdg.json', 'walker');
  const sc = attachVdg(skinned.gltf.scene);
  const smesh = sc.models[0].meshes[0];
  check(!!smesh.isSkinnedMesh, 'walker: the skinned base loads as a SkinnedMesh');
  sc.frame = 20;
  const sw = render(smesh, cam);
  const sv = vdgWeights(sc.models[0].extras, cam.position.toArray().map((x, i) => x - sc.models[0].extras.center[i]),
    { frame: 20 });
  check(maxDiff(sw, sv) <= kSameTol && sw.length === sc.models[0].extras.keys.length, 'walker: key targets only');
  // The skeleton played by three's AnimationMixer, the key targets by the hook: three's morph then
  // skin (glTF's order) equals vdg eval of the skinned offsets.
  let skinWorst = 0;
  for (const frame of [0, 9, 25]) {
    skinWorst = Math.max(skinWorst, animatedPositions(skinned.gltf, sc, skinned.manifest, cam, frame));
  }
  check(skinWorst <= kPosTol, `walker: skinned positions differ from vdg eval by ${skinWorst}`);
  sc.dispose();
  console.log(`ok walker: skinned base, key targets; three's morph + skin = vdg eval within ${skinWorst.toExponential(2)}`);
}

// ---- Bad input: one clear error, nothing half-done ----
{
  const { gltf } = await load('examples/figure13/head/head.vdg.json', 'head');
  let extras = null;
  gltf.scene.traverse((/** @type {any} */ o) => { if (o.userData.vdg) extras = o.userData.vdg; });
  const thrown = (/** @type {() => void} */ f) => { try { f(); return ''; } catch (e) { return String(e); } };
  check(thrown(() => vdgWeights(extras, [0, 0, 0])).includes('finite and non-zero'), 'a zero view is refused');
  check(thrown(() => vdgWeights(extras, [NaN, 0, 1])).includes('finite and non-zero'), 'a NaN view is refused');
  check(thrown(() => vdgWeights(extras, [0, 0, 1], { sharpness: 0 })).includes('sharpness'), 'sharpness 0 is refused');
  check(thrown(() => vdgWeights(extras, [1e-300, 0, 0])) === '', 'a 1e-300 long view is a direction');
  check(maxDiff(vdgWeights(extras, [1e300, 1e300, 0]), vdgWeights(extras, [1, 1, 0])) <= kSameTol, 'a 1e300 view');
  const v1 = { ...extras, version: 1 };
  delete v1.sphere;
  check(thrown(() => vdgWeights(v1, [0, 0, 1])).includes('re-export'), 'a version 1 description asks for a re-export');
  const root = new THREE.Group();
  const mesh = new THREE.Mesh(new THREE.BufferGeometry(), new THREE.MeshBasicMaterial());
  mesh.morphTargetInfluences = [0, 0, 0];
  mesh.userData = { vdg: v1 };
  root.add(mesh);
  check(thrown(() => attachVdg(root)).includes('re-export'), 'attachVdg refuses a version 1 export');
  check(mesh.onBeforeRender === THREE.Mesh.prototype.onBeforeRender, 'a refused attach leaves no hook');
  console.log('ok bad input');
}

console.log(failures === 0 ? 'PASS' : `FAIL: ${failures} failures`);
process.exit(failures === 0 ? 0 : 1);
