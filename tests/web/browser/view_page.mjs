// vdg view in a real browser (docs/web.md): Debian's Chromium driven by npm playwright-core, never a
// downloaded browser. One browser launch for every case:
//   - `vdg view` writes the folder for Spot and the walker; `vdg view --serve` serves them, and the
//     server answers with the right media types, 404 outside the folder and for hidden names, 405
//     for POST, and no body for HEAD;
//   - the page loads with no console error and no page error;
//   - for given cameras the page's blended positions equal `vdg eval` at the same eye within
//     POSITION_TOLERANCE (static Spot, and the animated walker at given frames);
//   - a screenshot of the clean page matches `vdg render` of the same camera: the intersection over
//     union of the non-background masks is at least SILHOUETTE_MIN_IOU;
//   - the walker with "world" offsets (its walk as frame targets) equals vdg eval too, and so does
//     Spot in the rbf weight scheme (extras version 4, every key weighed);
//   - a plain export with a texture (when the export writes one) has a map on its three.js material;
//   - a vdg .glb dropped on the page opens; the sharpness set on the page is vdg eval's --sharpness.
// Usage: node view_page.mjs VDG SOURCE_DIR WEB_DIR WORK_DIR. Exit 77 (skip) when Chromium or
// web/node_modules is missing, unless VDG_REQUIRE_WEB=1.
import { spawn, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const [vdg, sourceDir, webDir, workDir] = process.argv.slice(2);
const POSITION_TOLERANCE = 1e-4; // model units; the page's float32 morphing against vdg eval's doubles
const SILHOUETTE_MIN_IOU = 0.98; // masks of the same view differ only at the rim (anti-aliasing, stroke vs hull); measured 0.995-0.999
// Both images are drawn on pure green, a colour the shading never makes: a pixel farther than
// BACKGROUND_DISTANCE (sum of |r,g,b| in 0..255) from it is the model.
const BACKGROUND = [0, 1, 0];
const BACKGROUND_DISTANCE = 60;
const SIZE = 256;
const CHROMIUM = '/usr/bin/chromium';

function skip(why) {
  console.log(`SKIP: ${why}`);
  process.exit(process.env.VDG_REQUIRE_WEB === '1' ? 1 : 77);
}
const playwrightPath = path.join(webDir, 'node_modules', 'playwright-core', 'index.mjs');
if (!fs.existsSync(playwrightPath)) skip(`${playwrightPath} missing (run scripts/install-deps)`);
if (!fs.existsSync(CHROMIUM)) skip(`${CHROMIUM} missing (run scripts/install-deps)`);
if (!fs.existsSync(path.join(webDir, 'vdg-three.js'))) skip('web/vdg-three.js missing');
const { chromium } = await import(pathToFileURL(path.resolve(playwrightPath)).href);

let failures = 0;
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures += 1;
}

/** Runs vdg; throws with its stderr when it fails. */
function runVdg(...args) {
  const r = spawnSync(vdg, args, { encoding: 'utf8' });
  if (r.status !== 0) throw new Error(`vdg ${args.join(' ')}: exit ${r.status}: ${r.stderr}`);
  return r.stdout;
}

/** Starts `vdg view MODEL -o DIR --serve --port 0`; resolves to {url, child} once it prints its address. */
function serve(model, dir) {
  const child = spawn(vdg, ['view', model, '-o', dir, '--serve', '--port', '0', '-q'], { stdio: ['ignore', 'pipe', 'pipe'] });
  return new Promise((resolve, reject) => {
    let out = '', err = '';
    child.stderr.on('data', (d) => { err += d; });
    child.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/http:\/\/127\.0\.0\.1:\d+\//);
      if (m) resolve({ url: m[0], child });
    });
    child.on('exit', (code) => reject(new Error(`vdg view --serve ended (${code}): ${err}`)));
    setTimeout(() => reject(new Error('vdg view --serve printed no address in 20 s')), 20000);
  });
}

/** Vertex positions of an OBJ file. */
function objVertices(file) {
  const out = [];
  for (const line of fs.readFileSync(file, 'utf8').split('\n'))
    if (line.startsWith('v ')) out.push(...line.trim().split(/\s+/).slice(1, 4).map(Number));
  return out;
}

async function checkServer(url, dir) {
  const js = await fetch(`${url}view.js`);
  check(js.status === 200 && js.headers.get('content-type').startsWith('text/javascript'), 'server: .js is text/javascript');
  const glb = await fetch(`${url}model.glb`);
  const bytes = new Uint8Array(await glb.arrayBuffer());
  check(glb.headers.get('content-type') === 'model/gltf-binary' && bytes.length === fs.statSync(path.join(dir, 'model.glb')).size,
    'server: model.glb whole, as model/gltf-binary');
  check((await fetch(`${url}`)).headers.get('content-type').startsWith('text/html'), 'server: / is index.html');
  for (const bad of ['%2e%2e/%2e%2e/etc/passwd', '.vdg-view', 'three/', 'no-such-file.js'])
    check((await fetch(`${url}${bad}`)).status === 404, `server: ${bad} -> 404`);
  check((await fetch(url, { method: 'POST', body: 'x' })).status === 405, 'server: POST -> 405');
  const head = await fetch(`${url}view.js`, { method: 'HEAD' });
  check(head.status === 200 && (await head.text()) === '', 'server: HEAD without a body');
}

/** Opens the page; returns it with the list of console errors it logs. */
async function openPage(browser, url) {
  const page = await browser.newPage({ viewport: { width: SIZE, height: SIZE } });
  const errors = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(e.message));
  await page.goto(`${url}?clean=1`);
  await page.waitForFunction(() => window.vdgView !== undefined, null, { timeout: 20000 });
  await page.evaluate(() => window.vdgView.ready);
  return { page, errors };
}

async function checkParity(page, model, name, cameras, center) {
  for (const [i, { eye, frame, sharpness }] of cameras.entries()) {
    const got = await page.evaluate(([e, c, f, s]) => {
      window.vdgView.sharpness(s ?? null);
      window.vdgView.view(e, c, 30, f);
      return window.vdgView.positions();
    }, [eye, center, frame, sharpness]);
    const obj = path.join(workDir, `${name}_eval_${i}.obj`);
    runVdg('eval', model, '--eye', eye.join(','), ...(frame === undefined ? [] : ['--frame', String(frame)]),
      ...(sharpness === undefined ? [] : ['--sharpness', String(sharpness)]), '-o', obj, '-q');
    const want = objVertices(obj);
    let worst = got.length === want.length ? 0 : Infinity;
    for (let k = 0; k < want.length && worst < Infinity; ++k) worst = Math.max(worst, Math.abs(got[k] - want[k]));
    check(worst <= POSITION_TOLERANCE, `${name}: positions at eye ${eye}${frame === undefined ? '' : ` frame ${frame}`}` +
      `${sharpness === undefined ? '' : ` sharpness ${sharpness}`} ` +
      `equal vdg eval (max error ${worst.toExponential(2)} <= ${POSITION_TOLERANCE})`);
  }
  await page.evaluate(() => window.vdgView.sharpness(null));
}

/** IoU of the non-background masks of two PNGs (decoded in the page). */
function maskIou(page, pngA, pngB) {
  return page.evaluate(async ([a, b, limit, bg]) => {
    const pixels = async (base64) => {
      const bitmap = await createImageBitmap(await (await fetch(`data:image/png;base64,${base64}`)).blob());
      const c = new OffscreenCanvas(bitmap.width, bitmap.height);
      const g = c.getContext('2d');
      g.drawImage(bitmap, 0, 0);
      return g.getImageData(0, 0, bitmap.width, bitmap.height);
    };
    const [A, B] = [await pixels(a), await pixels(b)];
    if (A.width !== B.width || A.height !== B.height) return { iou: 0, why: 'sizes differ' };
    const inside = (d, i) => Math.abs(d[i] - bg[0]) + Math.abs(d[i + 1] - bg[1]) + Math.abs(d[i + 2] - bg[2]) > limit;
    let both = 0, either = 0;
    for (let i = 0; i < A.data.length; i += 4) {
      const x = inside(A.data, i), y = inside(B.data, i);
      both += x && y; either += x || y;
    }
    return { iou: either ? both / either : 0, area: either };
  }, [pngA.toString('base64'), pngB.toString('base64'), BACKGROUND_DISTANCE, BACKGROUND.map((c) => 255 * c)]);
}

async function checkSilhouette(page, model, name, eye, center, frame) {
  // vdg render strokes the silhouette 3 pixels wide (at this size), centred on it: 1.5 pixels outside.
  await page.evaluate(([e, c, f, bg]) => { window.vdgView.background(bg); window.vdgView.outline(1.5); window.vdgView.view(e, c, 30, f); },
    [eye, center, frame, BACKGROUND]);
  const shot = await page.locator('#main').screenshot();
  const shotFile = path.join(workDir, `${name}_page.png`);
  fs.writeFileSync(shotFile, shot);
  const cameraFile = path.join(workDir, `${name}.camera.json`);
  fs.writeFileSync(cameraFile, JSON.stringify({ eye, target: center, up: [0, 1, 0], fov_deg: 30 }));
  const out = path.join(workDir, `${name}_render`);
  runVdg('render', model, '--camera', cameraFile, '--size', `${SIZE}x${SIZE}`, '--background', BACKGROUND.join(','), '-o', out, '-q',
    ...(frame === undefined ? [] : ['--hold-frame', String(frame)]));
  const { iou, area } = await maskIou(page, shot, fs.readFileSync(path.join(out, 'frame_0000.png')));
  check(iou >= SILHOUETTE_MIN_IOU && area > 0.02 * SIZE * SIZE,
    `${name}: screenshot ${shotFile} matches vdg render's silhouette (IoU ${iou.toFixed(4)} >= ${SILHOUETTE_MIN_IOU})`);
}

async function checkTexture(page, dir) {
  const glb = fs.readFileSync(path.join(dir, 'model.glb'));
  const json = JSON.parse(glb.subarray(20, 20 + glb.readUInt32LE(12)).toString('utf8'));
  if (!json.images || json.images.length === 0) {
    console.log('skip texture check: the export writes no image yet (materials not merged)');
    return;
  }
  const hasMap = await page.evaluate(async () => {
    const { GLTFLoader } = await import('three/addons/loaders/GLTFLoader.js');
    const gltf = await new GLTFLoader().loadAsync('model.glb');
    let found = false;
    gltf.scene.traverse((o) => { if (o.isMesh && o.material && o.material.map && o.material.map.image) found = true; });
    return found;
  });
  check(hasMap, 'spot: a plain export loaded by GLTFLoader has a texture map on its material');
}

fs.rmSync(workDir, { recursive: true, force: true });
fs.mkdirSync(workDir, { recursive: true });
const spot = path.join(sourceDir, 'examples/spot/spot.vdg.json');
const walker = path.join(sourceDir, 'examples/walk/walker.vdg.json');
const walkerWorld = path.join(sourceDir, 'examples/walk/walker-world.vdg.json');
const spotRbf = path.join(sourceDir, 'examples/spot/spot-rbf.vdg.json');
runVdg('view', spot, '-o', path.join(workDir, 'spot'), '-q');
runVdg('export', walker, '-o', path.join(workDir, 'walker-export.glb'), '-q');
check(fs.existsSync(path.join(workDir, 'spot/.vdg-view')), 'vdg view -o writes the folder with its marker');
const servers = [];
const browser = await chromium.launch({ executablePath: CHROMIUM,
  args: ['--no-sandbox', '--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'] });
try {
  const spotServer = await serve(spot, path.join(workDir, 'spot'));
  servers.push(spotServer.child);
  await checkServer(spotServer.url, path.join(workDir, 'spot'));
  const s = await openPage(browser, spotServer.url);
  const spotCenter = await s.page.evaluate(() => window.vdgView.center());
  await checkParity(s.page, spot, 'spot', [{ eye: [0, 0.3, 3] }, { eye: [2.2, 0.8, -1.5] }, { eye: [-1.9, -0.6, 1.2] },
    { eye: [1.7, 0.4, 2.1], sharpness: 4 }], spotCenter);
  await checkSilhouette(s.page, spot, 'spot', [1.6, 0.7, 2.4], spotCenter);
  await checkTexture(s.page, path.join(workDir, 'spot'));
  // Dropping another vdg .glb on the page opens it: the walker's export, dropped as a file.
  fs.copyFileSync(path.join(workDir, 'walker-export.glb'), path.join(workDir, 'spot', 'dropped-walker.glb'));
  const dropped = await s.page.evaluate(async () => {
    const bytes = await (await fetch('dropped-walker.glb')).blob();
    const data = new DataTransfer();
    data.items.add(new File([bytes], 'dropped-walker.glb'));
    dispatchEvent(new DragEvent('drop', { dataTransfer: data, cancelable: true }));
    for (let i = 0; i < 200 && window.vdgView.info()?.frames !== 40; ++i) await new Promise((r) => setTimeout(r, 50));
    return { info: window.vdgView.info(), title: document.getElementById('title').textContent };
  });
  check(dropped.info?.frames === 40 && dropped.title === 'dropped-walker.glb', `spot: a dropped walker .glb opens (${JSON.stringify(dropped)})`);
  check(s.errors.length === 0, `spot: no console error (${s.errors.join(' | ')})`);

  const walkerServer = await serve(walker, path.join(workDir, 'walker'));
  servers.push(walkerServer.child);
  const w = await openPage(browser, walkerServer.url);
  const walkerCenter = await w.page.evaluate(() => window.vdgView.center());
  await checkParity(w.page, walker, 'walker', [{ eye: [0.5, 1.2, 4], frame: 10 }, { eye: [3.5, 1.5, 1.5], frame: 23 }], walkerCenter);
  await checkSilhouette(w.page, walker, 'walker', [2.5, 1.6, 3.5], walkerCenter, 10);
  check(w.errors.length === 0, `walker: no console error (${w.errors.join(' | ')})`);

  // The walker with "world" offsets: its base animation exported as frame targets, which the
  // runtime weighs as the glTF animation plays them, next to the key targets.
  const worldServer = await serve(walkerWorld, path.join(workDir, 'walker-world'));
  servers.push(worldServer.child);
  const ww = await openPage(browser, worldServer.url);
  await checkParity(ww.page, walkerWorld, 'walker-world', [{ eye: [3.5, 1.5, 1.5], frame: 17 }], walkerCenter);
  check(ww.errors.length === 0, `walker-world: no console error (${ww.errors.join(' | ')})`);

  // Spot in the rbf weight scheme (extras version 4): every key weighed from the written
  // interpolation, in the browser as vdg eval does.
  const rbfServer = await serve(spotRbf, path.join(workDir, 'spot-rbf'));
  servers.push(rbfServer.child);
  const r = await openPage(browser, rbfServer.url);
  const rbfCenter = await r.page.evaluate(() => window.vdgView.center());
  await checkParity(r.page, spotRbf, 'spot-rbf', [{ eye: [1.2, 1.1, -2.2] }, { eye: [-1.9, -0.6, 1.2], sharpness: 2.5 }],
    rbfCenter);
  await checkSilhouette(r.page, spotRbf, 'spot-rbf', [1.2, 1.1, -2.2], rbfCenter);
  check(r.errors.length === 0, `spot-rbf: no console error (${r.errors.join(' | ')})`);
} finally {
  await browser.close();
  for (const child of servers) child.kill('SIGINT');
}
console.log(failures === 0 ? 'all passed' : `${failures} failed`);
process.exit(failures === 0 ? 0 : 1);
