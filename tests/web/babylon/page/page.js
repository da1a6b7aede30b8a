// A Babylon.js page with no code of the exporter: it loads a glTF (whose KHR_interactivity graph, if
// any, Babylon's loader plays), places a free camera, renders frames, and reports what Babylon shows:
// the morph target influences and the mesh data to morph. window.babylonPage is the driver's handle.
import { Engine } from '@babylonjs/core/Engines/engine.js';
import { Scene } from '@babylonjs/core/scene.js';
import { FreeCamera } from '@babylonjs/core/Cameras/freeCamera.js';
import { HemisphericLight } from '@babylonjs/core/Lights/hemisphericLight.js';
import { Vector3 } from '@babylonjs/core/Maths/math.vector.js';
import { Color4 } from '@babylonjs/core/Maths/math.color.js';
import { LoadAssetContainerAsync } from '@babylonjs/core/Loading/sceneLoader.js';
import '@babylonjs/loaders/glTF/index.js';

const canvas = /** @type {HTMLCanvasElement} */ (document.getElementById('main'));
const engine = new Engine(canvas, true, { preserveDrawingBuffer: true });
window.addEventListener('resize', () => engine.resize());
/** @type {Scene | null} */
let scene = null;
/** @type {FreeCamera | null} */
let camera = null;

/**
 * glTF coordinates (right-handed) to this scene's: Babylon's default left-handed scene shows a glTF
 * mirrored in x (its loader's root node), a right-handed scene takes them as they are.
 * @param {number[]} p
 * @returns {Vector3}
 */
function toScene(p) {
  return new Vector3(scene && scene.useRightHandedSystem ? p[0] : -p[0], p[1], p[2]);
}

/** The first mesh with morph targets, or the first mesh with vertices. */
function morphMesh() {
  const meshes = scene ? scene.meshes.filter((m) => m.getTotalVertices() > 0) : [];
  return meshes.find((m) => m.morphTargetManager && m.morphTargetManager.numTargets > 0) || meshes[0] || null;
}

window.babylonPage = {
  /**
   * Loads a .glb/.gltf into a fresh scene; resolves once the scene is ready.
   * @param {string} url
   * @param {{rightHanded?: boolean, background?: number[]}} [options]
   */
  async load(url, options = {}) {
    if (scene) scene.dispose();
    engine.resize(); // the canvas may have changed size since the last load
    scene = new Scene(engine);
    scene.useRightHandedSystem = !!options.rightHanded;
    const bg = options.background || [0.12, 0.12, 0.14];
    scene.clearColor = new Color4(bg[0], bg[1], bg[2], 1);
    camera = new FreeCamera('camera', new Vector3(0, 0, 5), scene);
    camera.minZ = 0.01;
    new HemisphericLight('light', new Vector3(0.3, 1, 0.6), scene);
    const container = await LoadAssetContainerAsync(url, scene);
    container.addAllToScene();
    await scene.whenReadyAsync();
  },
  /**
   * Places the camera at eye looking at target (glTF coordinates), then renders `frames` frames.
   * @param {number[]} eye
   * @param {number[]} target
   * @param {number} [fovDeg]
   * @param {number} [frames]
   */
  view(eye, target, fovDeg = 30, frames = 1) {
    camera.position = toScene(eye);
    camera.setTarget(toScene(target));
    // setTarget moves the camera 0.001 along z when its z equals the target's (a Babylon guard
    // against a degenerate look-at): put it back where it was asked to be.
    camera.position = toScene(eye);
    camera.fov = (fovDeg * Math.PI) / 180;
    for (let i = 0; i < frames; ++i) scene.render();
  },
  /** @returns {number[]} the camera's position as Babylon holds it (its world matrix), in glTF coordinates */
  eye() {
    const t = camera.getWorldMatrix().getTranslation();
    return [scene.useRightHandedSystem ? t.x : -t.x, t.y, t.z];
  },
  /** Renders one frame without moving anything. */
  render() { scene.render(); },
  /** @returns {number[]} the influences of the morph targets of the morphed mesh */
  influences() {
    const m = morphMesh();
    const mtm = m && m.morphTargetManager;
    const out = [];
    for (let i = 0; mtm && i < mtm.numTargets; ++i) out.push(mtm.getTarget(i).influence);
    return out;
  },
  /**
   * The morphed positions as Babylon blends them (base + sum influence * (target - base)), in the
   * mesh's own (glTF) coordinates, from the mesh data Babylon holds.
   * @returns {number[]}
   */
  positions() {
    const m = morphMesh();
    const base = Array.from(m.getVerticesData('position'));
    const mtm = m.morphTargetManager;
    const out = base.slice();
    for (let i = 0; mtm && i < mtm.numTargets; ++i) {
      const t = mtm.getTarget(i);
      const p = t.getPositions();
      for (let k = 0; k < out.length; ++k) out[k] += t.influence * (p[k] - base[k]);
    }
    return out;
  },
};
window.babylonPageReady = true;
