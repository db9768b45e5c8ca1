// Helpers every view of the lab shares: requests, numbers for people, small
// DOM and SVG builders, a log-scale chart, and the 3D viewer (three.js,
// loaded from the lab itself when the build has it).

// This tab, for the lab: its newer request of a kind stops the one still running (docs/lab.md).
const TAB = Math.random().toString(36).slice(2, 12);

// A request to the lab's API; throws an Error whose message is the lab's own
// ("parameter 'x' = ... is outside ...", or a NotImplemented hint) on any
// status but 200. `view` names the part of the page that asks (the lab stops
// that view's older request of the same kind); `signal` aborts it here.
// An error from a request a newer one replaced has `cancelled` set.
export async function api(path, params = {}, kind = 'json', { view = 'page', signal } = {}) {
  const query = new URLSearchParams();
  for (const [k, v] of Object.entries(params)) if (v !== undefined && v !== null && v !== '') query.set(k, v);
  const url = path + (query.toString() ? '?' + query : '');
  let response;
  try {
    response = await fetch(url, { headers: { 'X-Lab-Tab': `${TAB}/${view}` }, signal });
  } catch (e) {
    if (e.name === 'AbortError') e.cancelled = true;
    throw e;
  }
  if (!response.ok) {
    let message = `${response.status} ${response.statusText}`, body = {};
    try {
      body = await response.json();
      message = body.error || message;
      if (body.not_implemented) message = `Not written yet: ${body.error}`;
    } catch (e) { /* not JSON */ }
    const error = new Error(message);
    error.status = response.status;
    error.cancelled = Boolean(body.cancelled);
    error.notImplemented = body.not_implemented || null;
    error.hint = body.hint || '';
    throw error;
  }
  return kind === 'json' ? response.json() : kind === 'blob' ? response.blob() : response.text();
}

// Resolves in the frame after the next one: by then the next frame, with
// whatever was drawn before this call, has been handed to the screen.
export function afterNextFrame() {
  return new Promise(resolve => requestAnimationFrame(() => requestAnimationFrame(() => resolve(performance.now()))));
}

// "1 shot", "2 shots".
export function plural(n, word) { return `${n} ${word}${n === 1 ? '' : 's'}`; }

// The same rule as display_number in lib/illum/trace/ray_tree_view.cpp:
// three significant digits like C's %.3g, 0 below 1e-6 in magnitude.
export function displayNumber(v) {
  if (Number.isNaN(v)) return 'nan';
  if (!Number.isFinite(v)) return v > 0 ? 'inf' : '-inf';
  if (Math.abs(v) < 1e-6) return '0';
  let exponent = Math.floor(Math.log10(Math.abs(v)));
  let mantissa = Number((v / 10 ** exponent).toFixed(2));
  if (Math.abs(mantissa) >= 10) mantissa /= 10, exponent += 1;  // 9.996 rounds up to 10.0
  if (exponent < -4 || exponent >= 3) {
    const m = String(Number(mantissa.toFixed(2)));
    const e = Math.abs(exponent) < 10 ? '0' + Math.abs(exponent) : String(Math.abs(exponent));
    return `${m}e${exponent < 0 ? '-' : '+'}${e}`;
  }
  return String(Number(v.toPrecision(3)));
}

export function displayColour(c) {
  const [r, g, b] = c.map(displayNumber);
  return r === g && g === b ? r : `(${r}, ${g}, ${b})`;
}

// A little-endian typed array sent as base64 (the radiosity steps' float32 arrays, the hemicube's buffers).
export function decodeBase64(text, Type = Float32Array) {
  const raw = atob(text), bytes = new Uint8Array(raw.length);
  for (let i = 0; i < raw.length; ++i) bytes[i] = raw.charCodeAt(i);  // (Uint8Array.from with a map: 5 times slower)
  return new Type(bytes.buffer);
}

export function el(tag, attributes = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attributes)) {
    if (k === 'text') e.textContent = v;
    else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
    else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c);
  return e;
}

const SVG = 'http://www.w3.org/2000/svg';
export function svg(tag, attributes = {}, ...children) {
  const e = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attributes)) {
    if (k === 'text') e.textContent = v;
    else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c);
  return e;
}

export function setStatus(element, text, isError = false) {
  element.textContent = text;
  element.classList.toggle('error', isError);
}

// A line chart with a logarithmic y axis (values ≤ 0 are left out), in `holder`.
// series: [{points: [[x, y], ...], className}]
// integerX: the x values are counts (steps, shots): ticks on whole numbers only.
export function logChart(holder, series, { xLabel = '', yLabel = '', logX = false, integerX = false } = {}) {
  const width = 560, height = 260, left = 58, right = 12, top = 10, bottom = 34;
  const all = series.flatMap(s => s.points).filter(p => p[1] > 0 && (!logX || p[0] > 0));
  holder.replaceChildren();
  const root = svg('svg', { viewBox: `0 0 ${width} ${height}`, role: 'img', 'aria-label': yLabel });
  holder.append(root);
  if (!all.length) return;
  const fx = v => logX ? Math.log10(v) : v;
  const least = values => values.reduce((a, b) => Math.min(a, b), Infinity);
  const most = values => values.reduce((a, b) => Math.max(a, b), -Infinity);
  let x0 = least(all.map(p => fx(p[0]))), x1 = most(all.map(p => fx(p[0])));
  if (x1 === x0) x1 = x0 + 1;
  let y0 = Math.floor(Math.log10(least(all.map(p => p[1])))), y1 = Math.ceil(Math.log10(most(all.map(p => p[1]))));
  if (y1 === y0) y1 = y0 + 1;
  const X = v => left + (fx(v) - x0) / (x1 - x0) * (width - left - right);
  const Y = v => top + (y1 - Math.log10(v)) / (y1 - y0) * (height - top - bottom);
  for (let e = y0; e <= y1; ++e) {
    root.append(svg('line', { x1: left, x2: width - right, y1: Y(10 ** e), y2: Y(10 ** e), class: 'grid' }));
    root.append(svg('text', { x: left - 4, y: Y(10 ** e) + 4, 'text-anchor': 'end', text: `1e${e}` }));
  }
  root.append(svg('line', { x1: left, x2: left, y1: top, y2: height - bottom, class: 'axis' }));
  root.append(svg('line', { x1: left, x2: width - right, y1: height - bottom, y2: height - bottom, class: 'axis' }));
  let ticks = logX ? [] : [x0, (x0 + x1) / 2, x1];
  if (integerX) {  // at most 7 whole-number ticks, 1, 2 or 5 times a power of ten apart
    let step = 1;
    for (let k = 1; (x1 - x0) / step > 6; ++k) step = [1, 2, 5][k % 3] * 10 ** Math.floor(k / 3);
    ticks = [];
    for (let t = Math.ceil(x0 / step) * step; t <= x1; t += step) ticks.push(t);
  }
  if (logX) for (let e = Math.ceil(x0); e <= x1; e += Math.max(1, Math.round((x1 - x0) / 6))) ticks.push(e);
  for (const t of ticks) {
    const v = logX ? 10 ** t : t;
    root.append(svg('text', { x: X(v), y: height - bottom + 14, 'text-anchor': 'middle', class: 'x-tick', text: displayNumber(Math.round(v * 100) / 100) }));
  }
  root.append(svg('text', { x: (left + width - right) / 2, y: height - 4, 'text-anchor': 'middle', text: xLabel }));
  for (const s of series) {
    let pts = s.points.filter(p => p[1] > 0 && (!logX || p[0] > 0));
    if (pts.length > 1500) {  // more points than the chart has pixels across: every k-th, and the last
      const k = Math.ceil(pts.length / 1500);
      pts = pts.filter((p, i) => i % k === 0 || i === pts.length - 1);
    }
    if (!pts.length) continue;
    root.append(svg('polyline', { points: pts.map(p => `${X(p[0]).toFixed(1)},${Y(p[1]).toFixed(1)}`).join(' '), class: s.className || 'series' }));
    if (s.label) root.append(svg('text', { x: X(pts[pts.length - 1][0]) - 4, y: Y(pts[pts.length - 1][1]) - 6, 'text-anchor': 'end', text: s.label }));
  }
}

// --- the 3D viewer ---------------------------------------------------------------

let threePromise = null;
// three.js and OrbitControls, from the lab (embedded at build time from node_modules/three).
export function loadThree() {
  if (!threePromise)
    threePromise = Promise.all([import('./three/three.module.js'), import('./three/OrbitControls.js'),
      import('./three/LineSegments2.js'), import('./three/LineSegmentsGeometry.js'), import('./three/LineMaterial.js')])
      .then(([THREE, controls, segments, geometry, material]) => ({ THREE, OrbitControls: controls.OrbitControls,
        LineSegments2: segments.LineSegments2, LineSegmentsGeometry: geometry.LineSegmentsGeometry, LineMaterial: material.LineMaterial }));
  return threePromise;
}

// A renderer, a perspective camera with orbit controls and a scene, drawn on
// demand (not every frame: the lab shares a machine with the student's builds).
export class Viewer {
  // antialias: worth it for thin rays; a mesh of patches does without (and on a machine without a
  // GPU, where WebGL runs on the CPU, multisampling costs more than the rest of a frame).
  // overlay: a second, transparent canvas over the first with a scene of its own (`overlay`),
  // drawn without depth against the first: what changes often (a pixel's rays) is redrawn alone
  // (drawOverlay), and the scene's geometry only when the camera moves. On a CPU's WebGL a frame of
  // the Whitted scene is 20 ms of work, its rays under 1 ms.
  constructor(holder, three, { antialias = true, overlay = false } = {}) {
    const { THREE, OrbitControls } = three;
    this.THREE = THREE;
    this.three = three;
    this.lineMaterials = new Set();  // wide lines need the canvas size; kept (a new one is a shader compile)
    this.holder = holder;
    this.renderer = new THREE.WebGLRenderer({ antialias });
    this.renderer.setPixelRatio(Math.min(2, window.devicePixelRatio || 1));
    this.renderer.setClearColor(0x10131a);
    holder.replaceChildren(this.renderer.domElement);
    if (overlay) {
      this.overlayRenderer = new THREE.WebGLRenderer({ antialias, alpha: true });
      this.overlayRenderer.setPixelRatio(this.renderer.getPixelRatio());
      this.overlayRenderer.setClearColor(0x000000, 0);
      Object.assign(this.overlayRenderer.domElement.style, { position: 'absolute', left: '0', top: '0', pointerEvents: 'none' });
      holder.append(this.overlayRenderer.domElement);
      this.overlay = new THREE.Scene();
    }
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
    this.scene = new THREE.Scene();
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener('change', () => this.draw());
    this.resize();
    new ResizeObserver(() => { this.resize(); this.draw(); }).observe(holder);
  }
  resize() {
    const w = Math.max(1, this.holder.clientWidth), h = Math.max(1, this.holder.clientHeight);
    for (const r of [this.renderer, this.overlayRenderer].filter(Boolean)) {
      r.setSize(w, h, false);
      r.domElement.style.width = '100%';
      r.domElement.style.height = '100%';
    }
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    for (const m of this.lineMaterials) m.resolution.set(w, h);
  }
  // A line material `width` CSS pixels wide (three's LineMaterial), kept sized with the canvas.
  lineMaterial(options) {
    const m = new this.three.LineMaterial({ ...options });
    m.resolution.set(Math.max(1, this.holder.clientWidth), Math.max(1, this.holder.clientHeight));
    this.lineMaterials.add(m);
    return m;
  }
  draw() {
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame(() => { this.pending = false; this.drawNow(); });
  }
  drawNow() {
    this.renderer.render(this.scene, this.camera);
    this.drawOverlay();
  }
  drawOverlay() { if (this.overlayRenderer) this.overlayRenderer.render(this.overlay, this.camera); }
  // Look from `eye` at `target` with `up` and a vertical field of view, the clip planes fitted to `size`.
  look(eye, target, up, fov, size) {
    const { THREE } = this;
    this.camera.position.set(...eye);
    this.camera.up.set(...up);
    this.camera.fov = fov;
    this.camera.near = Math.max(1e-4, size * 1e-3);
    this.camera.far = size * 50;
    this.camera.updateProjectionMatrix();
    this.controls.target.set(...target);
    this.camera.lookAt(new THREE.Vector3(...target));
    this.controls.update();
    this.draw();
  }
  // Which object of `objects` is under the mouse event, and where.
  pick(event, objects) {
    const { THREE } = this;
    const rect = this.renderer.domElement.getBoundingClientRect();
    const mouse = new THREE.Vector2(((event.clientX - rect.left) / rect.width) * 2 - 1,
      -((event.clientY - rect.top) / rect.height) * 2 + 1);
    const caster = new THREE.Raycaster();
    caster.setFromCamera(mouse, this.camera);
    return caster.intersectObjects(objects, false)[0] || null;
  }
}

export function threeMissing(holder, info) {
  holder.replaceChildren(el('div', { class: 'message', text: info && !info.three
    ? 'This build has no three.js: run tools/install-deps (it runs npm ci), then build again (cmake --build --preset release --target illum_cli).'
    : 'The 3D view could not start (WebGL is unavailable in this browser).' }));
}
