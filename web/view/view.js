// vdg view's page (docs/web.md): loads model.glb (or ?model=NAME), lets the runtime
// (../vdg-three.js) set the morph weights from the camera that renders, and draws the main view,
// the viewing-sphere widget (Figure 4) and an observer inset (Figure 6). Query options:
//   ?model=NAME.glb   another model in this folder     ?clean=1   no panel, widget or inset
//   ?bench=1&instances=N&frames=F   the benchmark (bench.js)
// window.vdgView is the page's hook for tests and scripts (see the end of this file).
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { MeshoptDecoder } from 'three/addons/libs/meshopt_decoder.module.js';
import { attachVdg } from './vdg-three.js';
import { styleModel, setOutlinePixel } from './shading.js';
import { SphereWidget } from './sphere-widget.js';

const params = new URLSearchParams(location.search);
const canvas = /** @type {HTMLCanvasElement} */ (document.getElementById('main'));
const $ = (/** @type {string} */ id) => /** @type {HTMLInputElement} */ (document.getElementById(id));
if (params.get('clean') === '1') document.body.classList.add('clean');

/** The background of vdg render (src/render: RenderStyle::background), so that screenshots compare. */
const BACKGROUND = new THREE.Color(0.97, 0.97, 0.95);
const OUTLINE_PIXELS = 2.5; // about the outer part of vdg render's silhouette stroke

const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.outputColorSpace = THREE.LinearSRGBColorSpace; // colours as vdg render computes them
renderer.setPixelRatio(1);
renderer.autoClear = false;

const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(30, 1, 0.01, 100);
const controls = new OrbitControls(camera, canvas);
controls.enableDamping = false;
const observer = new THREE.PerspectiveCamera(40, 1, 0.01, 100); // wide: the main camera stays in sight
observer.userData.vdgAuxiliary = true; // shows the shape the main camera sees (web/README.md's rule)
const mainProxy = new THREE.PerspectiveCamera(30, 1, 0.01, 1);
const mainHelper = new THREE.CameraHelper(mainProxy);
mainHelper.visible = false;
scene.add(mainHelper);

/**
 * @typedef {object} Loaded
 * @property {THREE.Object3D} root
 * @property {any} controller the runtime's controller (attachVdg)
 * @property {import('./vdg-three.js').VdgExtras} extras of the first vdg mesh
 * @property {THREE.Mesh[]} meshes the vdg meshes
 * @property {THREE.ShaderMaterial[]} outlines
 * @property {SphereWidget} widget
 * @property {THREE.AnimationMixer|null} mixer plays a skinned base animation
 * @property {THREE.Vector3} center model centre (model space = world space here)
 * @property {number} radius
 * @property {number} frameCount 0 for a static model
 */
/** @type {Loaded|null} */
let model = null;
let overlays = params.get('clean') !== '1';
let playing = true;
let frame = 0;
let lastTime = performance.now();

/**
 * Loads a vdg .glb (a URL) and makes it the page's model.
 * @param {string} url
 * @param {string} name shown in the panel
 */
async function open(url, name) {
  const loader = new GLTFLoader().setMeshoptDecoder(MeshoptDecoder);
  const gltf = await loader.loadAsync(url);
  /** @type {THREE.Mesh[]} */
  const meshes = [];
  gltf.scene.traverse((o) => { if (/** @type {THREE.Mesh} */ (o).isMesh && o.userData.vdg) meshes.push(/** @type {THREE.Mesh} */ (o)); });
  if (meshes.length === 0) throw new Error(`${name}: no mesh with extras.vdg (is it a vdg export?)`);
  if (model) close();
  const extras = meshes[0].userData.vdg;
  const outlines = styleModel(gltf.scene, OUTLINE_PIXELS);
  scene.add(gltf.scene);
  const controller = attachVdg(gltf.scene, { mainCamera: camera });
  gltf.scene.updateMatrixWorld(true);
  const center = new THREE.Vector3().fromArray(extras.center ?? [0, 0, 0]);
  let radius = 0;
  const v = new THREE.Vector3();
  for (const mesh of meshes)
    for (let i = 0; i < mesh.geometry.attributes.position.count; ++i)
      radius = Math.max(radius, mesh.getVertexPosition(i, v).applyMatrix4(mesh.matrixWorld).distanceTo(center));
  const animation = extras.animation;
  let mixer = null;
  if (animation && animation.base === 'skin' && gltf.animations.length > 0) {
    const clip = gltf.animations[animation.animation ?? 0] ?? gltf.animations[0];
    // Bones only: the runtime owns the morph weights.
    const bones = new THREE.AnimationClip(clip.name, clip.duration, clip.tracks.filter((t) => !t.name.endsWith('.morphTargetInfluences')));
    mixer = new THREE.AnimationMixer(gltf.scene);
    mixer.clipAction(bones).play();
  }
  model = { root: gltf.scene, controller, extras, meshes, outlines, widget: new SphereWidget(extras), mixer, center,
    radius: Math.max(radius, 1e-3), frameCount: animation ? animation.frame_count : 0 };
  frame = 0;
  frameCamera();
  setupPanel(name);
}

function close() {
  if (!model) return;
  model.controller.dispose();
  scene.remove(model.root);
  model = null;
}

/** Puts the orbit camera and the observer around the model (the observer to its side, further out). */
function frameCamera() {
  if (!model) return;
  const { center, radius } = model;
  const distance = (1.5 * radius) / Math.sin(THREE.MathUtils.degToRad(camera.fov) / 2); // with a margin
  camera.position.copy(center).add(new THREE.Vector3(0, Math.sin(0.26), Math.cos(0.26)).multiplyScalar(distance));
  camera.near = distance / 100;
  camera.far = distance * 10;
  controls.target.copy(center);
  controls.update();
  observer.position.copy(center).add(new THREE.Vector3(2.2, 1.6, -0.9).normalize().multiplyScalar(distance * 1.6));
  observer.near = distance / 100;
  observer.far = distance * 20;
  observer.lookAt(center);
}

/** @param {string} name */
function setupPanel(name) {
  if (!model) return;
  $('title').textContent = name;
  const own = model.extras.sharpness ?? 1;
  const slider = $('sharpness'), check = $('sharpness-model');
  slider.value = String(Math.log2(own));
  check.checked = true;
  const apply = () => {
    const value = 2 ** Number(slider.value);
    $('sharpness-value').textContent = (check.checked ? own : value).toFixed(2);
    if (model) model.controller.sharpness = check.checked ? null : value;
  };
  slider.oninput = () => { check.checked = false; apply(); };
  check.onchange = apply;
  apply();
  $('time-row').hidden = model.frameCount === 0;
  const time = $('time');
  time.max = String(Math.max(0, model.frameCount - 1));
  time.oninput = () => { setFrame(Number(time.value)); $('play').checked = false; playing = false; };
  $('play').onchange = () => { playing = $('play').checked; };
  const e = model.extras;
  $('status').textContent = `${e.keys.length} keys, ${e.sphere.views} views, ${e.sphere.points.length - e.sphere.views} dummy points\n` +
    `${e.sphere.triangles.length} hull triangles, uncovered: ${e.uncovered}` + (model.frameCount ? `\n${model.frameCount} frames at ${e.animation?.fps} fps` : '');
}

/** @param {number} f */
function setFrame(f) {
  if (!model || model.frameCount === 0) return;
  frame = f;
  model.controller.frame = f;
  if (model.mixer) model.mixer.setTime(f / (model.extras.animation?.fps || 24));
  $('time').value = String(f);
  $('time-value').textContent = f.toFixed(1);
}

/** Renders the main view, then (with overlays) the observer inset and the sphere widget. */
function render() {
  const width = canvas.clientWidth, height = canvas.clientHeight;
  if (canvas.width !== width || canvas.height !== height) renderer.setSize(width, height, false);
  camera.aspect = width / Math.max(1, height);
  camera.updateProjectionMatrix();
  renderer.setScissorTest(false);
  renderer.setViewport(0, 0, width, height);
  renderer.setClearColor(BACKGROUND, 1);
  renderer.clear();
  if (!model) return;
  setOutlinePixel(model.outlines, camera, height);
  renderer.render(scene, camera);
  if (!overlays) return;
  const inset = Math.round(Math.min(width, height) * 0.3);
  renderObserver(width - inset - 10, 10, inset);
  renderWidget(width - inset - 10, inset + 20, inset);
}

/**
 * Figure 6: the model seen from a fixed observer with the weights of the main camera (the observer
 * is an auxiliary camera, userData.vdgAuxiliary: the runtime weighs for mainCamera), and the main
 * camera drawn.
 * @param {number} x @param {number} y @param {number} size
 */
function renderObserver(x, y, size) {
  if (!model) return;
  mainProxy.position.copy(camera.position);
  mainProxy.quaternion.copy(camera.quaternion);
  mainProxy.fov = camera.fov;
  mainProxy.aspect = camera.aspect;
  mainProxy.far = camera.position.distanceTo(model.center) * 0.6;
  mainProxy.updateProjectionMatrix();
  mainProxy.updateMatrixWorld();
  mainHelper.update();
  mainHelper.visible = true;
  observer.aspect = 1;
  observer.updateProjectionMatrix();
  setOutlinePixel(model.outlines, observer, size);
  drawInset(x, y, size, new THREE.Color(0.86, 0.9, 0.97), () => renderer.render(scene, observer));
  mainHelper.visible = false;
  const caption = document.getElementById('observer-caption');
  if (caption) Object.assign(caption.style, { right: '14px', bottom: `${y + size - 18}px`, top: '' });
}

/** @param {number} x @param {number} y @param {number} size */
function renderWidget(x, y, size) {
  if (!model) return;
  const view = camera.position.clone().sub(model.center).normalize();
  model.widget.update(view, camera, model.controller.lastSphereWeights(model.controller.models[0]) ?? null);
  drawInset(x, y, size, new THREE.Color(1, 1, 1), () => renderer.render(model.widget.scene, model.widget.camera));
  const caption = document.getElementById('sphere-caption');
  if (caption) Object.assign(caption.style, { right: '14px', bottom: `${y + size - 18}px`, top: '' });
}

/**
 * @param {number} x @param {number} y bottom-left corner in pixels
 * @param {number} size @param {THREE.Color} background @param {() => void} draw
 */
function drawInset(x, y, size, background, draw) {
  renderer.setViewport(x, y, size, size);
  renderer.setScissor(x, y, size, size);
  renderer.setScissorTest(true);
  renderer.setClearColor(background, 1);
  renderer.clear();
  draw();
  renderer.setScissorTest(false);
}

function loop() {
  const now = performance.now();
  if (model && model.frameCount > 0 && playing) {
    const fps = model.extras.animation?.fps || 24;
    let f = frame + ((now - lastTime) / 1000) * fps;
    f = model.extras.animation?.loop ? f % model.frameCount : Math.min(f, model.frameCount - 1);
    setFrame(f);
  }
  lastTime = now;
  render();
  requestAnimationFrame(loop);
}

// Dropping another vdg .glb on the page opens it.
addEventListener('dragover', (e) => { e.preventDefault(); document.body.classList.add('dragging'); });
addEventListener('dragleave', () => document.body.classList.remove('dragging'));
addEventListener('drop', (e) => {
  e.preventDefault();
  document.body.classList.remove('dragging');
  const file = e.dataTransfer?.files?.[0];
  if (!file) return;
  const url = URL.createObjectURL(file);
  open(url, file.name).catch((error) => { $('status').textContent = String(error.message ?? error); })
    .finally(() => URL.revokeObjectURL(url));
});

/**
 * The model-space positions of the blended mesh as the last rendered view set them, in vdg's vertex
 * order (split vertices mapped back through the _VDG_VERTEX attribute when the export has it).
 * @returns {number[]} x, y, z of each vertex
 */
function blendedPositions() {
  if (!model) return [];
  /** @type {number[]} */
  const out = [];
  const v = new THREE.Vector3();
  let offset = 0;
  for (const mesh of model.meshes) {
    mesh.updateMatrixWorld(true);
    const count = mesh.geometry.attributes.position.count;
    const original = mesh.geometry.getAttribute('_vdg_vertex');
    for (let i = 0; i < count; ++i) {
      mesh.getVertexPosition(i, v).applyMatrix4(mesh.matrixWorld);
      const k = original ? original.getX(i) : offset + i;
      out[3 * k] = v.x; out[3 * k + 1] = v.y; out[3 * k + 2] = v.z;
    }
    if (!original) offset += count;
  }
  return out;
}

/** The test and scripting hook. */
const hook = {
  /** @type {Promise<void>} resolves once the first model is shown */
  ready: Promise.resolve(),
  /** @param {boolean} on the panel, widget and inset */
  overlays(on) { overlays = on; document.body.classList.toggle('clean', !on); },
  /**
   * Puts the main camera at `eye` looking at `target` with a vertical field of view `fov` degrees,
   * stops the animation at `frameNumber` (animated models), and renders once.
   * @param {number[]} eye @param {number[]} target @param {number} fov @param {number} [frameNumber]
   */
  view(eye, target, fov, frameNumber) {
    playing = false;
    $('play').checked = false;
    camera.fov = fov;
    camera.position.fromArray(eye);
    controls.target.fromArray(target);
    camera.lookAt(controls.target);
    camera.updateMatrixWorld();
    if (frameNumber !== undefined) setFrame(frameNumber);
    if (model?.mixer) model.mixer.update(0);
    render();
  },
  /** @param {number[]} rgb the main view's background, each in [0, 1] (tests use a colour vdg render is given too) */
  background(rgb) { BACKGROUND.setRGB(rgb[0], rgb[1], rgb[2]); },
  /** @param {number} pixels the outline's width outside the silhouette (vdg render's 3-pixel stroke: 1.5) */
  outline(pixels) { if (model) for (const m of model.outlines) m.uniforms.uPixels.value = pixels; },
  positions: blendedPositions,
  /** @returns {number[]} the main camera's morph weights of the first vdg mesh */
  weights() { return model ? Array.from(model.meshes[0].morphTargetInfluences ?? []) : []; },
  /** @param {number|null} s sharpness, null: the model's */
  sharpness(s) { if (model) model.controller.sharpness = s; },
  /** @returns {number[]} the model's centre (the views' origin) */
  center() { return model ? model.center.toArray() : [0, 0, 0]; },
  info() { return model ? { keys: model.extras.keys.length, frames: model.frameCount, meshes: model.meshes.length } : null; },
  /** @param {string} url */
  open(url) { return open(url, url); },
  render,
};
/** @type {any} */ (window).vdgView = hook;

const modelUrl = params.get('model') ?? 'model.glb';
hook.ready = open(modelUrl, modelUrl.replace(/^.*\//, '')).then(async () => {
  if (params.get('bench') === '1') {
    const { runBenchmark } = await import('./bench.js');
    /** @type {any} */ (window).vdgBench = runBenchmark({ renderer, scene, camera, model, params });
  }
});
hook.ready.catch((error) => { $('status').textContent = String(error.message ?? error); console.error(error); });
requestAnimationFrame(loop);
