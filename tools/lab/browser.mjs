#!/usr/bin/env node
// Drives the lab's page in headless Chromium (Debian's /usr/bin/chromium, or
// ILLUM_CHROMIUM) through puppeteer-core, for the browser test, the benchmark
// and the gallery's screenshots (docs/lab.md):
//
//   node tools/lab/browser.mjs test        URL OPTIONS.json OBSERVED.json
//   node tools/lab/browser.mjs student     URL OPTIONS.json OBSERVED.json   (URL unused: OPTIONS names the labs)
//   node tools/lab/browser.mjs bench       URL OPTIONS.json RESULTS.json
//   node tools/lab/browser.mjs screenshots URL OPTIONS.json FOLDER
//
// It clicks and reads the page as a student would and writes what it saw;
// the callers (tests/lab/run_browser_test.py, tools/lab/bench.py,
// tools/lab/screenshots.py) compare it with their own expectations. Chromium
// runs with a fresh profile and without reaching for the network; every
// request the page makes is recorded, so the test can check that nothing
// comes from anywhere but the lab. Exit status 2 when it cannot run
// (no Chromium, no puppeteer-core), 1 when the page misbehaves.
import fs from 'node:fs';
import path from 'node:path';
import { startChromium } from '../browser/chromium.mjs';

const LAB_ARGS = [
  // Tabs behind the first one keep running (the test drives several at once).
  '--disable-background-timer-throttling', '--disable-renderer-backgrounding', '--disable-backgrounding-occluded-windows',
  // WebGL on the CPU (SwiftShader): this machine has no GPU, and Chromium asks for the opt-in.
  '--enable-unsafe-swiftshader'];

function fatal(message, code = 2) {
  console.error(`browser.mjs: ${message}`);
  process.exit(code);
}

const [mode, url, optionsFile, output] = process.argv.slice(2);
if (!['test', 'student', 'bench', 'screenshots'].includes(mode) || !url || !optionsFile || !output)
  fatal('usage: node tools/lab/browser.mjs test|student|bench|screenshots URL OPTIONS.json OUTPUT');
const options = JSON.parse(fs.readFileSync(optionsFile, 'utf8'));
const { browser, close } = await startChromium(fatal, {
  extraArgs: LAB_ARGS, launch: { defaultViewport: { width: 1400, height: 1000 } } });
// The blank tab Chromium opens with: it draws frames of its own, which the benchmark would count.
for (const blank of await browser.pages()) await blank.close();
const seen = { requests: [], failed: [], errors: [], console: [] };
const t0 = Date.now();
const log = message => console.error(`browser.mjs: ${((Date.now() - t0) / 1000).toFixed(1)} s: ${message}`);

async function open(hash, viewport, base = url) {
  const page = await browser.newPage();
  if (viewport) await page.setViewport(viewport);
  page.on('request', r => seen.requests.push(r.url()));
  // net::ERR_ABORTED is the page's own doing (an image's src replaced while it loads: a quick second choice
  // of lesson or image), not a failure of the lab, which answers with a status or is unreachable.
  page.on('requestfailed', r => {
    const why = r.failure() && r.failure().errorText;
    if (why !== 'net::ERR_ABORTED') seen.failed.push(`${r.url()}: ${why}`);
  });
  page.on('pageerror', e => seen.errors.push(e.message));
  page.on('console', m => { if (m.type() === 'error') seen.console.push(m.text()); });
  await page.goto(`${base}#${hash}`, { waitUntil: 'load' });
  await page.waitForSelector('body[data-ready="true"]', { timeout: 30000 });
  return page;
}

const state = (page, id) => page.$eval(id, s => s.dataset.state);
async function waitState(page, id, states, timeout = 60000) {
  await page.waitForFunction((sel, want) => want.includes(document.querySelector(sel).dataset.state),
    { timeout, polling: 'mutation' }, id, states);
  const s = await state(page, id);
  const status = { '#tab-tree': '#tree-status', '#tab-radiosity': '#rad-status', '#tab-hemicube': '#hc-status', '#tab-hierarchy': '#hr-status', '#tab-compare': '#cmp-verdict' }[id];
  if (s === 'error') throw new Error(`${id}: ${await page.$eval(status, p => p.textContent)}`);
}

// Clicks the centre of image pixel (x, y) of the rendered scene; returns the time from the click to the drawn tree.
async function clickPixel(page, x, y) {
  const box = await page.$eval('#tree-image', img => {
    const r = img.getBoundingClientRect();
    return { left: r.left, top: r.top, width: r.width, height: r.height, w: img.naturalWidth, h: img.naturalHeight };
  });
  await page.mouse.click(box.left + (x + 0.5) * box.width / box.w, box.top + (y + 0.5) * box.height / box.h);
  await waitState(page, '#tab-tree', ['drawn', 'error']);
  return page.$eval('#tab-tree', s => ({ pixel: s.dataset.pixel.split(',').map(Number), ms: Number(s.dataset.clickMs) }));
}

async function treeObservation(page) {
  return page.evaluate(() => ({
    nodes: [...document.querySelectorAll('#tree-diagram .tree-node')].map(g => ({
      id: Number(g.dataset.id), kind: g.dataset.kind, depth: Number(g.dataset.depth), stop: g.dataset.stop,
      primitive: g.dataset.primitive, t: g.dataset.t === '' ? null : Number(g.dataset.t), segments: Number(g.dataset.segments),
      text: [...g.querySelectorAll('text')].map(t => t.textContent) })),
    stubs: [...document.querySelectorAll('#tree-diagram .stub')].map(g => ({ parent: Number(g.dataset.parent), kind: g.dataset.kind, fate: g.dataset.fate })),
    drawnRays: Number(document.querySelector('#tree-3d').dataset.drawnRays),
    drawnSegments: Number(document.querySelector('#tree-3d').dataset.drawnSegments),
    details: document.querySelector('#tree-details').textContent,
  }));
}

// What the diagram and the 3D view show of the tree drawn: whether the diagram fits its pane and
// every line fits its box, the eye's marker, and the ray materials (kept from click to click).
async function treeDrawing(page) {
  return page.evaluate(() => {
    const pane = document.querySelector('#tree-diagram'), svgEl = pane.querySelector('svg');
    const overflowing = [];
    for (const g of pane.querySelectorAll('.tree-node, .stub')) {
      const rect = g.querySelector('rect');
      const box = rect ? rect.getBBox() : null;
      for (const t of g.querySelectorAll('text')) {
        const b = t.getBBox();
        if (box && (b.x < box.x - 0.5 || b.x + b.width > box.x + box.width + 0.5)) overflowing.push(t.textContent);
      }
    }
    const tree = window.lab.views.tree, v = tree.viewer;
    const eye = v.scene.getObjectByName('eye');
    return {
      svgWidth: svgEl.getBoundingClientRect().width, paneWidth: pane.clientWidth, scale: Number(pane.dataset.scale),
      cut: [...pane.querySelectorAll('text')].map(t => t.textContent).filter(t => t.includes('…')), overflowing,
      eye: eye && { type: eye.type, size: eye.material.size, sizeAttenuation: eye.material.sizeAttenuation },
      legend: document.querySelector('#tab-tree .legend').textContent,
      materials: Object.values(tree.materials).map(m => m.uuid), programs: v.overlayRenderer.info.programs.length,
      clickMs: Number(document.querySelector('#tab-tree').dataset.clickMs),
    };
  });
}

async function openTab(page, name, id, states = ['ready', 'drawn', 'compared', 'missing']) {
  await press(page, `button[data-tab="${name}"]`);
  await waitState(page, id, [...states, 'error'], 120000);
}

// A button pressed through the DOM: puppeteer's mouse click waits for an animation frame, which a
// tab behind another never gets.
const press = (page, selector) => page.$eval(selector, b => b.click());

async function radiosityStep(page, button, steps) {
  await press(page, button);
  await page.waitForFunction(n => document.querySelector('#tab-radiosity').dataset.steps === String(n) &&
    ['ready', 'done', 'error'].includes(document.querySelector('#tab-radiosity').dataset.state), { timeout: 120000, polling: 'mutation' }, steps);
}

const history = page => page.$$eval('#rad-history tbody tr', rows => rows.map(r => [Number(r.dataset.step), Number(r.dataset.fraction)]).reverse());

async function setValue(page, selector, value) {
  await page.$eval(selector, (e, v) => { e.value = String(v); e.dispatchEvent(new Event('change')); }, value);
}

async function hemicube(page, patch, resolution) {
  await page.$eval('#hc-patch', (e, v) => { e.value = String(v); e.dataset.chosen = 'true'; }, patch);
  await setValue(page, '#hc-resolution', resolution);
  await page.waitForFunction((p, r) => { const s = document.querySelector('#tab-hemicube').dataset;
    return s.state === 'drawn' && s.patch === String(p) && s.resolution === String(r) || s.state === 'error'; },
  { timeout: 120000, polling: 20 }, patch, resolution);
  await waitState(page, '#tab-hemicube', ['drawn']);
  return page.evaluate(() => ({
    patch: Number(document.querySelector('#tab-hemicube').dataset.patch),
    resolution: Number(document.querySelector('#tab-hemicube').dataset.resolution),
    sum: Number(document.querySelector('#hc-sum').dataset.value),
    study: [...document.querySelectorAll('#hc-targets .study-row')].map(r => [Number(r.dataset.resolution), Number(r.dataset.sum)]),
    errors: document.querySelector('#hc-errors') ? { ...document.querySelector('#hc-errors').dataset } : null,
  }));
}

async function compare(page, lesson, image) {
  await setValue(page, '#cmp-lesson', lesson);
  await page.waitForFunction(() => !['loading'].includes(document.querySelector('#tab-compare').dataset.state), { polling: 20 });
  await setValue(page, '#cmp-image', image);
  await page.waitForFunction(() => ['compared', 'missing', 'error'].includes(document.querySelector('#tab-compare').dataset.state), { timeout: 60000, polling: 20 });
  return page.evaluate(() => ({
    state: document.querySelector('#tab-compare').dataset.state,
    matches: document.querySelector('#tab-compare').dataset.matches,
    sizes: document.querySelector('#tab-compare').dataset.sizes || null,
    share: document.querySelector('#cmp-number') ? Number(document.querySelector('#cmp-number').dataset.share) : null,
    verdict: document.querySelector('#cmp-verdict').textContent,
  }));
}

async function test() {
  const observed = {};
  // Wide enough that the image shows at its own size: a click lands on the pixel aimed at.
  const page = await open('tree', { width: 1640, height: 1000 });
  await waitState(page, '#tab-tree', ['ready']);
  log('the tree');
  // 1. The glass ball: the click, its tree, a step back in depth.
  observed.click = await clickPixel(page, ...options.pixel);
  observed.tree = await treeObservation(page);
  observed.drawing = await treeDrawing(page);
  // Two more clicks: the same materials and shader programs draw them.
  await clickPixel(page, 100, 300);
  await clickPixel(page, ...options.pixel);
  observed.drawingLater = await treeDrawing(page);
  await press(page, '#tree-depth-down');
  observed.depthDown = await page.evaluate(() => ({ shown: document.querySelector('#tab-tree').dataset.shownDepth,
    hidden: [...document.querySelectorAll('#tree-diagram .tree-node.hidden-depth')].map(g => Number(g.dataset.id)) }));
  log('radiosity');
  // 2. Ten shots on the 2,124-patch box, then lesson 11's quick figure shot by shot.
  await openTab(page, 'radiosity', '#tab-radiosity');
  observed.patches = Number(await page.$eval('#tab-radiosity', s => s.dataset.patches));
  observed.ambientChecked = await page.$eval('#rad-ambient', c => c.checked);
  await radiosityStep(page, '#rad-step-10', 10);
  observed.tenShots = await history(page);
  await page.$eval('#rad-patches', e => { e.value = '300'; });
  await page.$eval('#rad-resolution', e => { e.value = '32'; });
  await press(page, '#rad-start');
  await waitState(page, '#tab-radiosity', ['ready']);
  observed.quickPatches = Number(await page.$eval('#tab-radiosity', s => s.dataset.patches));
  const radiosityText = () => page.evaluate(() => ({ status: document.querySelector('#rad-status').textContent,
    ticks: [...document.querySelectorAll('#rad-chart .x-tick')].map(t => t.textContent) }));
  for (let k = 1; k <= 8; ++k) {
    await radiosityStep(page, '#rad-step-1', k);
    if (k === 1) observed.oneShot = await radiosityText();
  }
  observed.quickShots = await history(page);
  observed.eightShots = await radiosityText();
  // Another way to paint the same shot asks for it again (steps=0): the status keeps the shot's times.
  await setValue(page, '#rad-paint', 'row');
  await page.waitForFunction(() => document.querySelector('#rad-caption').textContent.includes('row F_ij'), { polling: 20 });
  await waitState(page, '#tab-radiosity', ['ready']);
  observed.afterRepaint = await radiosityText();
  await setValue(page, '#rad-paint', 'flat');
  for (const method of ['jacobi', 'gauss_seidel', 'southwell']) {
    await setValue(page, '#rad-method', method);
    await waitState(page, '#tab-radiosity', ['ready']);
    await radiosityStep(page, '#rad-step-10', 10);
    observed[`method_${method}`] = await history(page);
  }
  log('the hemicube');
  // 3. The hemicube on the patch the caller chose, at two resolutions.
  await openTab(page, 'hemicube', '#tab-hemicube', ['drawn']);
  observed.hemicube = [];
  for (const r of options.resolutions) observed.hemicube.push(await hemicube(page, options.patch, r));
  // A patch of the red wall, whose other triangle lies nearly in its plane: the explanation.
  await hemicube(page, options.redPatch, 64);
  observed.redWall = await page.evaluate(() => ({
    why: document.querySelector('#hc-why').textContent, edgeOn: Number(document.querySelector('#hc-why').dataset.edgeOn),
    rows: [...document.querySelectorAll('#hc-targets .study-row')].map(r => ({ resolution: Number(r.dataset.resolution),
      weighted: Number(r.dataset.weightedRel), mean: Number(r.dataset.meanRel), above: Number(r.dataset.meanRelAbove) })) }));
  log('the hierarchy');
  // 4. Lesson 14's hierarchy on the scene the caller chose: a click on the middle of the view (a mouse
  // click, as a student's), the links drawn for it; then a bad ε_F, refused.
  await openTab(page, 'hierarchy', '#tab-hierarchy', ['drawn']);
  await setValue(page, '#hr-scene', options.hierarchyScene);
  await page.waitForFunction(s => { const d = document.querySelector('#tab-hierarchy').dataset;
    return window.lab.views.hierarchy.h?.scene === s && d.state === 'drawn' || d.state === 'error'; },
  { timeout: 120000, polling: 20 }, options.hierarchyScene);
  await waitState(page, '#tab-hierarchy', ['drawn']);
  const canvas = await page.$eval('#hr-3d canvas', c => { const r = c.getBoundingClientRect(); return { x: r.left + r.width / 2, y: r.top + r.height / 2 }; });
  await page.mouse.click(canvas.x, canvas.y);
  await page.waitForFunction(() => document.querySelector('#tab-hierarchy').dataset.element !== undefined ||
    document.querySelector('#tab-hierarchy').dataset.state === 'error', { timeout: 60000, polling: 20 });
  await waitState(page, '#tab-hierarchy', ['drawn']);
  observed.hierarchy = await page.evaluate(() => { const v = window.lab.views.hierarchy, d = document.querySelector('#tab-hierarchy').dataset;
    return { params: v.params(), elements: Number(d.elements), links: Number(d.links), element: Number(d.element),
      selectedLinks: Number(d.selectedLinks), drawnLines: v.links.children.reduce((n, c) => n + c.geometry.attributes.position.count / 2, 0),
      count: document.querySelector('#hr-link-count').textContent, status: document.querySelector('#hr-status').textContent }; });
  const consoleBefore = seen.console.length;
  await setValue(page, '#hr-epsilon-f', '0');
  await page.waitForFunction(() => ['error', 'drawn'].includes(document.querySelector('#tab-hierarchy').dataset.state),
    { timeout: 60000, polling: 20 });
  observed.hierarchyRefused = await page.evaluate(() => ({ state: document.querySelector('#tab-hierarchy').dataset.state,
    status: document.querySelector('#hr-status').textContent }));
  observed.hierarchyRefused.console = seen.console.splice(consoleBefore);  // the refusal's own 400, checked apart
  await setValue(page, '#hr-epsilon-f', '0.4');
  await waitState(page, '#tab-hierarchy', ['drawn']);
  log('your pictures');
  // 5. Your pictures.
  await openTab(page, 'compare', '#tab-compare', ['compared', 'missing']);
  observed.compare = {};
  for (const [lesson, image] of options.compare) observed.compare[`${lesson}/${image}`] = await compare(page, lesson, image);
  log('two more tabs');
  // 6. Two more tabs at once, each with its own session: the same ten shots.
  const [a, b] = await Promise.all([open('radiosity'), open('radiosity')]);
  await Promise.all([waitState(a, '#tab-radiosity', ['ready'], 120000), waitState(b, '#tab-radiosity', ['ready'], 120000)]);
  await Promise.all([radiosityStep(a, '#rad-step-10', 10), radiosityStep(b, '#rad-step-10', 10)]);
  observed.twoTabs = [await history(a), await history(b)];
  log('done');
  observed.seen = seen;
  fs.writeFileSync(output, JSON.stringify(observed, null, 1));
}

// A student's builds beside the reference (options.labs: the URLs of the mutant's lab, the stubs'
// lab with the reference, the stubs' lab alone): the first difference of a tree and of a shot, the
// reference's picture and tree where the student's evaluate is not written, and a page with
// nothing to draw that says so.
async function student() {
  const observed = {};
  const look = async (page, x, y) => {
    const s = await page.evaluate(() => ({ state: document.querySelector('#tab-tree').dataset.state,
      drawnBy: document.querySelector('#tab-tree').dataset.drawnBy, imageHidden: document.querySelector('#tree-image').hidden,
      imageWidth: document.querySelector('#tree-image').naturalWidth, note: document.querySelector('#tree-image-note').textContent,
      noteHidden: document.querySelector('#tree-image-note').hidden,
      message3d: [...document.querySelectorAll('#tree-3d .message')].map(m => m.textContent).join(' ') }));
    if (x !== undefined) {
      await clickPixel(page, x, y);
      Object.assign(s, await page.evaluate(() => { const v = document.querySelector('#tree-versus');
        const first = document.querySelector('#tree-diagram .tree-node.first-difference');
        return { first: v.dataset.first, rows: Number(v.dataset.rows), summary: (v.querySelector('#versus-summary') || {}).textContent,
          firstNode: first ? Number(first.dataset.id) : null, caption: document.querySelector('#tree-diagram-caption').textContent,
          referenceSegments: Number(document.querySelector('#tree-3d').dataset.referenceSegments) }; }));
    }
    return s;
  };
  log('the mutant beside the reference');
  const mutant = await open('tree', { width: 1640, height: 1000 }, options.labs.mutant);
  await waitState(mutant, '#tab-tree', ['ready']);
  observed.mutantTree = await look(mutant, ...options.pixel);
  await openTab(mutant, 'radiosity', '#tab-radiosity');
  for (let k = 1; k <= options.shots; ++k) await radiosityStep(mutant, '#rad-step-1', k);
  observed.mutantShots = await mutant.evaluate(() => ({ versus: document.querySelector('#tab-radiosity').dataset.versus,
    text: document.querySelector('#rad-versus-text').textContent }));
  log('the stubs beside the reference');
  const stubs = await open('tree', { width: 1640, height: 1000 }, options.labs.stubsReference);
  await waitState(stubs, '#tab-tree', ['ready']);
  observed.stubsReference = await look(stubs, ...options.pixel);
  log('the stubs alone');
  const alone = await open('tree', { width: 1640, height: 1000 }, options.labs.stubsAlone);
  await settled(alone);
  observed.stubsAlone = await look(alone);
  observed.seen = seen;
  fs.writeFileSync(output, JSON.stringify(observed, null, 1));
}

// The tree view settled, whatever it shows (the stubs alone: an error that says what to write).
const settled = page => page.waitForFunction(() => ['ready', 'error'].includes(document.querySelector('#tab-tree').dataset.state),
  { timeout: 120000, polling: 'mutation' });

// CPU seconds (user + system) of Chromium's processes and of the lab (options.labPid) so far: the
// benchmark's figure that the machine's load does not change (Linux, /proc).
function cpuSeconds() {
  const stat = pid => { try { return fs.readFileSync(`/proc/${pid}/stat`, 'utf8').split(') ')[1].split(' '); } catch { return null; } };
  const children = {};
  for (const pid of fs.readdirSync('/proc').filter(p => /^\d+$/.test(p))) {
    const f = stat(pid);
    if (f) (children[f[1]] = children[f[1]] || []).push(pid);
  }
  const pids = [String(browser.process().pid)];
  for (let i = 0; i < pids.length; ++i) pids.push(...(children[pids[i]] || []));
  if (options.labPid) pids.push(String(options.labPid));
  const tick = 100;  // USER_HZ on Linux
  return pids.reduce((sum, pid) => { const f = stat(pid); return f ? sum + (Number(f[11]) + Number(f[12])) / tick : sum; }, 0);
}

async function bench() {
  const results = { clicks: [], shots: [] };
  const page = await open('tree');
  await waitState(page, '#tab-tree', ['ready']);
  results.clickCpu = 0;
  for (const scene of options.scenes) {
    await setValue(page, '#tree-scene', scene);
    await waitState(page, '#tab-tree', ['ready'], 120000);
    const size = await page.$eval('#tree-image', img => [img.naturalWidth, img.naturalHeight]);
    // A grid of pixels over the image, each clicked once, a quarter of a second apart (as a person
    // clicks); the first click counts too.
    for (let i = 0; i < options.clicks; ++i) {
      const x = Math.floor((0.1 + 0.8 * ((i * 7) % options.clicks) / options.clicks) * size[0]);
      const y = Math.floor((0.15 + 0.7 * ((i * 3) % options.clicks) / options.clicks) * size[1]);
      await new Promise(resolve => setTimeout(resolve, 250));
      const cpu = cpuSeconds();
      const r = await clickPixel(page, x, y);
      results.clickCpu += cpuSeconds() - cpu;
      results.clicks.push({ scene, pixel: r.pixel, ms: r.ms, nodes: (await treeObservation(page)).nodes.length });
    }
  }
  await openTab(page, 'radiosity', '#tab-radiosity');
  results.patches = Number(await page.$eval('#tab-radiosity', s => s.dataset.patches));
  // One shot per press of "1 step": the request, the repaint and the chart after every shot.
  await radiosityStep(page, '#rad-step-1', 1);
  let started = Date.now(), cpu = cpuSeconds();
  for (let k = 2; k <= options.single + 1; ++k) await radiosityStep(page, '#rad-step-1', k);
  results.single = { shots: options.single, seconds: (Date.now() - started) / 1000, cpu: cpuSeconds() - cpu };
  // "run": as many shots per request as keep the picture moving (lab_radiosity.js, toggleRun).
  const before = Number(await page.$eval('#tab-radiosity', s => s.dataset.steps));
  started = Date.now();
  await press(page, '#rad-run');
  await page.waitForFunction(n => Number(document.querySelector('#tab-radiosity').dataset.steps) >= n, { timeout: 600000, polling: 50 }, before + options.shots);
  await press(page, '#rad-run');
  await waitState(page, '#tab-radiosity', ['ready', 'done']);
  const after = Number(await page.$eval('#tab-radiosity', s => s.dataset.steps));
  results.run = { shots: after - before, seconds: (Date.now() - started) / 1000 };
  fs.writeFileSync(output, JSON.stringify(results, null, 1));
}

async function screenshots() {
  fs.mkdirSync(output, { recursive: true });
  const shot = async (page, file, height) => {
    await page.setViewport({ width: 1200, height });
    await page.evaluate(() => window.scrollTo(0, 0));
    // The 3D views redraw at the new size: the ResizeObserver fires in the next frame's layout,
    // its draw() asks for the frame after (lab_util.js), and the one after that is composited.
    // At most 2 s, should a page ever stop getting frames (the 400 ms this replaced, five times over).
    await page.evaluate(() => new Promise(done => {
      let frames = 0;
      const next = () => (++frames >= 3 ? done() : requestAnimationFrame(next));
      requestAnimationFrame(next);
      setTimeout(done, 2000);
    }));
    await page.screenshot({ path: path.join(output, file) });
  };
  const page = await open('tree', { width: 1200, height: 1000 });
  await waitState(page, '#tab-tree', ['ready']);
  await clickPixel(page, ...options.pixel);
  // The shadow ray that crosses the glass, selected: its segments in the details.
  await page.$eval('#tree-diagram .tree-node[data-kind="shadow"][data-segments="2"]', g => g.dispatchEvent(new MouseEvent('click')));
  await shot(page, 'lab_ray_tree.png', 1000);
  await openTab(page, 'radiosity', '#tab-radiosity');
  await radiosityStep(page, '#rad-step-10', 10);
  await shot(page, 'lab_radiosity.png', 760);
  await setValue(page, '#rad-paint', 'row');
  await page.waitForFunction(() => document.querySelector('#rad-caption').textContent.includes('row'), { polling: 20 });
  await shot(page, 'lab_radiosity_row.png', 760);
  await openTab(page, 'hemicube', '#tab-hemicube', ['drawn']);
  if (options.patch !== null) await hemicube(page, options.patch, 64);
  await shot(page, 'lab_hemicube.png', 1180);
  // Lesson 14's hierarchy on its default scene, the element in the middle of the view clicked: its links.
  await openTab(page, 'hierarchy', '#tab-hierarchy', ['drawn']);
  const middle = await page.$eval('#hr-3d canvas', c => { const r = c.getBoundingClientRect(); return { x: r.left + r.width / 2, y: r.top + r.height / 2 }; });
  await page.mouse.click(middle.x, middle.y);
  await page.waitForFunction(() => document.querySelector('#tab-hierarchy').dataset.element !== undefined,
    { timeout: 60000, polling: 20 });
  await waitState(page, '#tab-hierarchy', ['drawn']);
  await shot(page, 'lab_hierarchy.png', 900);
  await openTab(page, 'compare', '#tab-compare', ['compared', 'missing']);
  if (options.compare) await compare(page, ...options.compare);
  await shot(page, 'lab_compare.png', 640);
  fs.writeFileSync(path.join(output, 'browser.json'), JSON.stringify(seen, null, 1));
}

try {
  await { test, student, bench, screenshots }[mode]();
} catch (e) {
  console.error(`browser.mjs: ${e.stack || e}`);
  process.exitCode = 1;
} finally {
  await close();
}
