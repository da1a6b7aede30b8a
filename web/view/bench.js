// vdg view's benchmark mode (?bench=1&instances=N&frames=F, docs/performance.md): the cost per
// frame of the view dependence (every instance's weights from its own view, written into the
// instanced mesh's morph texture, attachVdgInstanced) for 1 and N instances of the model in one
// InstancedMesh, against the same scene without view dependence (the same morph texture, weights
// left as they are). Each frame the camera moves a little around the crowd; a frame's time runs
// from before renderer.render to a one-pixel readPixels that waits for the GPU.
import * as THREE from 'three';
import { attachVdgInstanced } from './vdg-three.js';
import { warmCoolMaterial } from './shading.js';

/**
 * @param {number[]} values
 * @returns {number} the median
 */
function median(values) {
  const s = [...values].sort((a, b) => a - b);
  return s.length ? (s[(s.length - 1) >> 1] + s[s.length >> 1]) / 2 : NaN;
}

/**
 * One crowd of `count` instances in a grid, rendered `frames` times with or without the runtime.
 * @param {any} ctx {renderer, scene, camera, model}
 * @param {number} count @param {number} frames @param {boolean} viewDependent
 */
function measure(ctx, count, frames, viewDependent) {
  const { renderer, scene, camera, model } = ctx;
  const source = model.meshes[0];
  const material = warmCoolMaterial(/** @type {any} */ ({ color: new THREE.Color(0.85, 0.85, 0.85) }));
  const geometry = source.geometry.clone();
  geometry.clearGroups();
  const crowd = new THREE.InstancedMesh(geometry, material, count);
  crowd.frustumCulled = false;
  const side = Math.ceil(Math.sqrt(count));
  const spacing = 2.2 * model.radius;
  const m = new THREE.Matrix4();
  for (let i = 0; i < count; ++i) {
    m.makeTranslation(((i % side) - (side - 1) / 2) * spacing, 0, (Math.floor(i / side) - (side - 1) / 2) * spacing);
    crowd.setMatrixAt(i, m);
  }
  crowd.setMorphAt(0, { morphTargetInfluences: new Array(source.morphTargetInfluences.length).fill(0) });
  const controller = viewDependent ? attachVdgInstanced(crowd, model.extras, { mainCamera: camera }) : null;
  model.root.visible = false;
  scene.add(crowd);
  const gl = renderer.getContext();
  const pixel = new Uint8Array(4);
  const reach = side * spacing;
  /** @type {number[]} */
  const times = [];
  const warmUp = Math.min(5, Math.ceil(frames / 4));
  for (let f = -warmUp; f < frames; ++f) {
    const a = (f / frames) * Math.PI * 0.5;
    camera.position.set(Math.sin(a) * reach, 0.6 * reach + model.center.y, Math.cos(a) * reach);
    camera.lookAt(0, model.center.y, 0);
    camera.updateMatrixWorld();
    const t = performance.now();
    renderer.render(scene, camera);
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
    if (f >= 0) times.push(performance.now() - t);
  }
  // The update alone (weights of every instance + writing the morph texture), repeated for a
  // resolution finer than the browser's coarsened clock.
  let update_ms = 0;
  if (controller) {
    const repeats = Math.max(20, Math.ceil(20000 / count));
    const t = performance.now();
    for (let r = 0; r < repeats; ++r) controller.update(camera);
    update_ms = (performance.now() - t) / repeats;
  }
  scene.remove(crowd);
  controller?.dispose();
  model.root.visible = true;
  geometry.dispose();
  material.dispose();
  crowd.dispose();
  return { frame_ms: median(times), update_ms };
}

/**
 * Runs the benchmark; the result is also shown in the panel.
 * @param {{renderer: THREE.WebGLRenderer, scene: THREE.Scene, camera: THREE.PerspectiveCamera, model: any, params: URLSearchParams}} ctx
 * @returns {Promise<object[]>} per instance count: frame and update medians in milliseconds
 */
export async function runBenchmark(ctx) {
  const many = Math.max(1, Number(ctx.params.get('instances') ?? 1000));
  const frames = Math.max(1, Number(ctx.params.get('frames') ?? 120));
  const results = [];
  for (const count of many === 1 ? [1] : [1, many]) {
    await new Promise((r) => setTimeout(r, 0));
    const plain = measure(ctx, count, frames, false);
    console.log(`bench: ${count} without view dependence: ${plain.frame_ms.toFixed(2)} ms/frame`);
    const vdg = measure(ctx, count, frames, true);
    results.push({ instances: count, frames, targets: ctx.model.meshes[0].morphTargetInfluences.length,
      vdg_frame_ms: vdg.frame_ms, plain_frame_ms: plain.frame_ms, overhead_ms: vdg.frame_ms - plain.frame_ms,
      weights_and_morph_update_ms: vdg.update_ms });
  }
  const status = document.getElementById('status');
  if (status) status.textContent = results.map((r) => `${r.instances} instance(s): ${r.vdg_frame_ms.toFixed(2)} ms/frame ` +
    `(plain ${r.plain_frame_ms.toFixed(2)}), weights + morph update ${r.weights_and_morph_update_ms.toFixed(3)} ms`).join('\n');
  console.log('vdg bench', JSON.stringify(results));
  return results;
}
