// Shared by the Babylon.js tests: a static server on 127.0.0.1 for the page, Babylon.js's packages
// and the test's files, and Debian's Chromium driven by npm playwright-core.
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

export const CHROMIUM = '/usr/bin/chromium';
const TYPES = { '.js': 'text/javascript', '.mjs': 'text/javascript', '.html': 'text/html', '.json': 'application/json',
  '.glb': 'model/gltf-binary', '.gltf': 'model/gltf+json', '.bin': 'application/octet-stream', '.wasm': 'application/wasm' };

/**
 * Exits 77 (skip), or 1 when VDG_REQUIRE_WEB=1.
 * @param {string} why
 */
export function skip(why) {
  console.log(`SKIP: ${why}`);
  process.exit(process.env.VDG_REQUIRE_WEB === '1' ? 1 : 77);
}

/**
 * Loads playwright-core's chromium from web/node_modules, or skips when it, Chromium or Babylon.js is missing.
 * @param {string} webDir
 */
export async function loadChromium(webDir) {
  const playwrightPath = path.join(webDir, 'node_modules', 'playwright-core', 'index.mjs');
  if (!fs.existsSync(playwrightPath)) skip(`${playwrightPath} missing (run scripts/install-deps)`);
  if (!fs.existsSync(CHROMIUM)) skip(`${CHROMIUM} missing (run scripts/install-deps)`);
  for (const p of ['core', 'loaders'])
    if (!fs.existsSync(path.join(webDir, 'node_modules', '@babylonjs', p, 'package.json')))
      skip(`web/node_modules/@babylonjs/${p} missing (run scripts/install-deps)`);
  const { chromium } = await import(pathToFileURL(path.resolve(playwrightPath)).href);
  return chromium.launch({ executablePath: CHROMIUM,
    args: ['--no-sandbox', '--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'] });
}

/**
 * Serves /node_modules/ from web/node_modules, /page/ from the page folder and /work/ from the
 * work folder on 127.0.0.1 (a free port); resolves to {url, close}.
 * @param {{modules: string, page: string, work: string}} roots
 */
export function serve(roots) {
  const server = http.createServer((req, res) => {
    const url = new URL(req.url, 'http://127.0.0.1');
    const m = decodeURIComponent(url.pathname).match(/^\/(node_modules|page|work)\/(.*)$/);
    const root = m && { node_modules: roots.modules, page: roots.page, work: roots.work }[m[1]];
    const file = root && path.resolve(root, m[2]);
    if (!file || !file.startsWith(path.resolve(root) + path.sep) || !fs.existsSync(file) || !fs.statSync(file).isFile()) {
      res.writeHead(404).end();
      return;
    }
    res.writeHead(200, { 'content-type': TYPES[path.extname(file)] || 'application/octet-stream' });
    fs.createReadStream(file).pipe(res);
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () =>
    resolve({ url: `http://127.0.0.1:${server.address().port}/`, close: () => server.close() })));
}

/**
 * Opens the page; returns it with the list of console errors and warnings it logs.
 * @param {import('playwright-core').Browser} browser
 * @param {string} url
 */
export async function openPage(browser, url, size = 256) {
  const page = await browser.newPage({ viewport: { width: size, height: size } });
  const errors = [];
  const log = [];
  page.on('console', (m) => { log.push(`${m.type()}: ${m.text()}`); if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(e.message));
  await page.goto(`${url}page/index.html`);
  await page.waitForFunction(() => window.babylonPageReady === true, null, { timeout: 30000 });
  return { page, errors, log };
}
