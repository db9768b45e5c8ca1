// View 2: radiosity, shot by shot. A session (GET /api/radiosity/start) is
// solved step by step (GET /api/radiosity/step) by the build's own solvers:
// progressive refinement shoots one patch per step, its row drawn by the
// hemicube; Jacobi and Gauss–Seidel sweep the whole matrix; Southwell relaxes
// one row. The picture shows the patches flat or with lesson 12's vertex
// colours, or the shooter's form-factor row; the chart the unshot power.
// With a reference beside the build, progressive refinement runs there too,
// shot for shot, and each shot's shooter, row and update are compared.
import { afterNextFrame, api, decodeBase64, displayNumber, el, loadThree, logChart, plural, setStatus, threeMissing, Viewer } from './lab_util.js';
import { compareShot } from './lab_difference.js';
import { exposureFor, heat, PatchMesh } from './lab_mesh.js';

const UNIT = { progressive: 'shot', southwell: 'step', jacobi: 'sweep', gauss_seidel: 'sweep' };

export class RadiosityView {
  constructor(info) {
    this.info = info;
    this.section = document.getElementById('tab-radiosity');
    this.status = document.getElementById('rad-status');
    this.holder = document.getElementById('rad-3d');
    this.sceneSelect = document.getElementById('rad-scene');
    for (const s of info.scenes) this.sceneSelect.append(el('option', { value: s, text: s }));
    this.sceneSelect.value = info.scenes.includes('cornell') ? 'cornell' : info.scene;
    const resolution = document.getElementById('rad-resolution');
    for (const r of [16, 32, 64, 96, 128, 256]) resolution.append(el('option', { value: r, text: `${r} pixels` }));
    resolution.value = '128';
    this.method = document.getElementById('rad-method');
    this.method.addEventListener('change', () => {
      document.getElementById('rad-omega-label').hidden = this.method.value !== 'gauss_seidel';
      this.start();
    });
    for (const id of ['rad-scene', 'rad-patches', 'rad-resolution', 'rad-omega'])
      document.getElementById(id).addEventListener('change', () => this.start());
    document.getElementById('rad-start').addEventListener('click', () => this.start());
    for (const n of [1, 10, 100]) document.getElementById(`rad-step-${n}`).addEventListener('click', e => this.step(n, e.timeStamp));
    this.runButton = document.getElementById('rad-run');
    this.runButton.addEventListener('click', () => this.toggleRun());
    this.paint = document.getElementById('rad-paint');
    // Vertex colours and the row come with a step only when shown: ask again for the last one.
    this.paint.addEventListener('change', () => this.paint.value !== 'flat' && this.last ? this.step(0) : this.repaint());
    // Off by default: the ambient term lights every patch evenly, which hides what each shot did.
    this.ambient = document.getElementById('rad-ambient');
    this.ambient.addEventListener('change', () => this.repaint());
    this.versusBox = document.getElementById('rad-versus');
    this.versusPane = document.getElementById('rad-versus-pane');
    document.getElementById('rad-versus-label').hidden = !(info.reference && info.reference.available);
    this.versusBox.addEventListener('change', () => this.start());
    document.getElementById('rad-camera-view').addEventListener('click', () => this.patchMesh && this.viewer && this.patchMesh.cameraView(this.viewer));
    this.threeReady = info.three ? loadThree().catch(() => null) : Promise.resolve(null);
    this.session = null;
    this.busy = Promise.resolve();
  }

  params() {
    const p = { scene: this.sceneSelect.value, patches: document.getElementById('rad-patches').value,
      resolution: document.getElementById('rad-resolution').value, method: this.method.value };
    if (this.method.value === 'gauss_seidel') p.omega = document.getElementById('rad-omega').value;
    return p;
  }

  // Shot for shot against the reference: progressive refinement, with a reference beside the build.
  versus() { return this.info.reference && this.info.reference.available && this.versusBox.checked && this.method.value === 'progressive'; }

  // Requests run one after another: a step never overtakes the session's start.
  queue(task) {
    this.busy = this.busy.then(task, task);
    return this.busy;
  }

  start() {
    this.running = false;
    this.runButton.textContent = 'run ▶';
    return this.queue(async () => {
      this.section.dataset.state = 'starting';
      const p = this.params();
      setStatus(this.status, p.method === 'progressive' ? 'meshing…' : 'meshing and drawing the whole form-factor matrix (every row by the hemicube)…');
      try {
        const meshParams = { scene: p.scene, patches: p.patches };
        const key = JSON.stringify(meshParams);
        if (this.meshKey !== key) {
          this.mesh = await api('/api/radiosity/mesh', meshParams, 'json', { view: 'radiosity' });
          this.meshKey = key;
          await this.buildMesh();
        }
        const [started, reference] = await Promise.all([api('/api/radiosity/start', p, 'json', { view: 'radiosity' }),
          this.versus() ? api('/api/reference/radiosity/start', p, 'json', { view: 'radiosity' }) : null]);
        this.session = started.session;
        this.referenceSession = reference && reference.session;
        this.history = [[0, 1]];
        this.last = null;
        this.timing = '';
        this.firstDifference = null;
        this.versusPane.hidden = !this.referenceSession;
        this.showVersus(null, 0);
        this.section.dataset.steps = '0';
        this.section.dataset.fraction = '1';
        this.section.dataset.patches = String(started.patches);
        this.section.dataset.versus = '';
        document.querySelector('#rad-history tbody').replaceChildren();
        this.chart();
        this.paintFlat(new Array(3 * this.mesh.patches).fill(0), null);
        setStatus(this.status, `${started.scene}: ${started.patches} patches (edge ${displayNumber(started.edge)}), ` +
          `hemicube ${started.resolution}, ${p.method.replace('_', '–')}; ready`);
        this.section.dataset.state = 'ready';
      } catch (e) {
        this.section.dataset.state = 'error';
        setStatus(this.status, e.message, true);
      }
    });
  }

  async buildMesh() {
    const three = await this.threeReady;
    if (!three) { threeMissing(this.holder, this.info); this.viewer = null; this.patchMesh = null; return; }
    if (!this.viewer) this.viewer = new Viewer(this.holder, three, { antialias: false });
    this.viewer.scene.clear();
    this.patchMesh = new PatchMesh(three.THREE, this.mesh);
    this.viewer.scene.add(this.patchMesh.object);
    this.patchMesh.cameraView(this.viewer);
  }

  async request(session, steps, extra, reference = false) {
    const r = await api(`/api/${reference ? 'reference/' : ''}radiosity/step`, { session, steps, ...extra }, 'json', { view: 'radiosity' });
    r.radiosity = decodeBase64(r.radiosity);
    if (r.row) r.row = decodeBase64(r.row);
    if (r.vertex) r.vertex = decodeBase64(r.vertex);
    if (r.update) r.update = decodeBase64(r.update);
    return r;
  }

  // `pressedAt`: the press's event time (performance.now's clock); the status gives the time from it
  // to the frame that shows the step, once that frame is out (the next step need not wait for it).
  step(n, pressedAt = performance.now()) {
    if (!this.session) return this.start().then(() => this.session && this.step(n, pressedAt));
    return this.queue(async () => {
      if (!this.session) return;
      this.section.dataset.state = 'stepping';
      const t0 = performance.now();
      const extra = { vertex: this.paint.value === 'vertex' ? 1 : 0, row: this.paint.value === 'row' ? 1 : 0 };
      try {
        let r;
        if (this.referenceSession && n > 0) {
          // One shot a request on both sides, so that the first shot that differs is caught with its
          // row and update, and every shot after it is still compared.
          for (let k = 0; k < n; ++k) {
            const [mine, reference] = await Promise.all([this.request(this.session, 1, { ...extra, row: 1, update: 1 }),
              this.request(this.referenceSession, 1, { row: 1, update: 1 }, true)]);
            r = mine;
            this.record(r);
            this.compare(mine, reference);
            if (r.done || (this.running && performance.now() - t0 > 150)) break;
          }
        } else {
          r = await this.request(this.session, n, extra);
          if (n > 0) this.record(r);
        }
        this.last = r;
        if (n > 0) this.timing = `${displayNumber(r.seconds * 1000)} ms in the solver (${displayNumber(r.row_seconds * 1000)} in hemicube rows)`;
        this.repaintSoon();
        this.chartSoon();
        const ms = performance.now() - t0;
        this.section.dataset.steps = String(r.steps);
        this.section.dataset.fraction = String(r.fraction);
        this.showStatus(r);
        if (n > 0 && !this.running)
          afterNextFrame().then(shownAt => {
            if (this.last !== r) return;
            this.timing += `, on the screen ${Math.round(shownAt - pressedAt)} ms after the press`;
            this.showStatus(r);
          });
        this.section.dataset.state = r.done ? 'done' : 'ready';
        document.dispatchEvent(new CustomEvent('lab:radiosity-step', { detail: { steps: r.steps, ms } }));
      } catch (e) {
        this.section.dataset.state = 'error';
        this.running = false;
        if (e.status === 404) {  // the lab keeps the most recent sessions only: this one expired
          this.session = null;
          setStatus(this.status, `${e.message}: press a step button to start again from the beginning`, true);
        } else {
          setStatus(this.status, e.message, true);
        }
      }
    });
  }

  showStatus(r) {
    setStatus(this.status, `${plural(r.steps, UNIT[this.method.value])}; unshot / emitted ${displayNumber(r.fraction)}` +
      (r.shooter >= 0 ? `; last ${this.method.value === 'progressive' ? 'shooter' : 'row relaxed'}: patch ${r.shooter} (${this.surface(r.shooter)})` : '') +
      (r.done ? '; nothing left to shoot' : '') + (this.timing ? `; ${this.timing}` : '') +
      (r.ambient_error ? `; ambient term: ${r.ambient_error}` : '') + (r.vertex_error ? `; vertex colours: ${r.vertex_error}` : ''));
  }

  // A step's points in the history, the chart's series and the table.
  record(r) {
    const body = document.querySelector('#rad-history tbody');
    r.points.forEach(([s, f], i) => {
      this.history.push([s, f]);
      if (body.children.length >= 100) body.lastElementChild.remove();
      const shooter = r.shooters ? r.shooters[i] : -1;
      body.prepend(el('tr', { 'data-step': s, 'data-fraction': String(f) }, el('td', { text: s }),
        el('td', { text: displayNumber(f) }), el('td', { text: shooter >= 0 ? `${shooter} (${this.surface(shooter)})` : '' })));
    });
  }

  // This shot against the reference's: the first difference is kept, with its values and why.
  compare(mine, reference) {
    const d = compareShot(mine, reference, i => this.surface(i));
    if (d && !this.firstDifference) this.firstDifference = { shot: mine.steps, ...d };
    this.showVersus(d, mine.steps);
  }

  showVersus(d, shot) {
    const text = document.getElementById('rad-versus-text');
    const f = this.firstDifference;
    const parts = [];
    if (!shot) parts.push(el('p', { class: 'muted', text: 'Each shot of yours will be held against the reference\'s: the shooter (Task 6b), its row (lesson 10) and what it adds (Task 6c).' }));
    else if (!f) parts.push(el('p', { class: 'same', text: `Shots 1 to ${shot} are the reference's: the same shooters, rows and updates (within 10⁻⁵), the same unshot power.` }));
    if (f) {
      parts.push(el('p', {}, el('strong', { text: `First difference: shot ${f.shot}, the ${f.field}: ` }),
        el('span', { class: 'yours-value', text: `yours ${f.yours}` }), ', ', el('span', { class: 'reference-value', text: `the reference's ${f.reference}` }), '.'),
      el('p', { class: 'why', text: f.why }));
      if (shot > f.shot)
        parts.push(el('p', { class: 'muted', text: `Shot ${shot}: ${d ? `the ${d.field} differs too (yours ${d.yours}, the reference's ${d.reference})` : 'the same'}; ` +
          `the two states have differed since shot ${f.shot}, so later shots start from different places.` }));
    }
    text.replaceChildren(...parts);
    this.section.dataset.versus = f ? `${f.shot}|${f.field}` : shot ? 'same' : '';
  }

  // Steps until paused, as many per request as keep the picture moving about seven times a second:
  // one at first, more as long as a frame (the request, the repaint, the browser's drawing) takes
  // less than 150 ms. Every step still adds its point to the chart and the table.
  async toggleRun() {
    this.running = !this.running;
    this.runButton.textContent = this.running ? 'pause ❚❚' : 'run ▶';
    let batch = 1;
    const started = performance.now(), first = this.last ? this.last.steps : 0;
    while (this.running) {
      const t0 = performance.now();
      await this.step(batch);
      await new Promise(resolve => requestAnimationFrame(() => resolve()));
      if (!this.last || this.last.done || this.last.fraction < 1e-6 || this.section.dataset.state === 'error') break;
      const frame = performance.now() - t0;
      batch = Math.max(Math.ceil(batch / 2), Math.min(2 * batch, 200, Math.round(batch * 150 / Math.max(1, frame)) || 1));
      const rate = (this.last.steps - first) / ((performance.now() - started) / 1000);
      this.section.dataset.runRate = rate.toFixed(1);
      this.runButton.textContent = `pause ❚❚ (${Math.round(rate)} steps a second)`;
    }
    this.running = false;
    this.runButton.textContent = 'run ▶';
    this.chart();
  }

  surface(i) { return this.patchMesh ? this.patchMesh.surfaceOf(i) : (this.mesh.surfaces.find(s => i >= s.first && i < s.first + s.count) || {}).name; }

  displayed() {
    const r = this.last, m = this.mesh;
    const b = r.radiosity.slice();
    if (this.ambient.checked && r.ambient)
      for (let i = 0; i < m.patches; ++i) for (let k = 0; k < 3; ++k) b[3 * i + k] += m.reflectance[3 * i + k] * r.ambient[k];
    return b;
  }

  paintFlat(b, shooter) {
    if (!this.patchMesh) return;
    const exposure = exposureFor(this.mesh, b);
    this.patchMesh.paintPatches(i => [0, 1, 2].map(k => Math.min(1, exposure * b[3 * i + k])));
    this.patchMesh.outlinePatch(this.viewer.scene, shooter === null ? -1 : shooter);
    this.viewer.draw();
  }

  repaint() {
    if (!this.last || !this.patchMesh) return;
    const r = this.last, m = this.mesh;
    const caption = document.getElementById('rad-caption');
    if (this.paint.value === 'row' && r.row) {
      this.patchMesh.paintPatches(i => i === r.shooter ? [1, 0.1, 0.8] : heat(r.row[i]));
      caption.textContent = r.row_kind === 'row'
        ? `Patch ${r.shooter}'s row F_ij, log scale (10⁻⁶ dark blue … 1 yellow): how much of what it shoots lands on each patch.`
        : `Column F_j${r.shooter} of the patch Southwell relaxed, log scale: how its change reaches every other residual.`;
    } else if (this.paint.value === 'vertex' && r.vertex) {
      const b = this.displayed();
      const exposure = exposureFor(m, b);
      const extra = i => this.ambient.checked && r.ambient ? [0, 1, 2].map(k => m.reflectance[3 * i + k] * r.ambient[k]) : [0, 0, 0];
      this.patchMesh.paintCorners((c, i) => { const a = extra(i); return [0, 1, 2].map(k => Math.min(1, exposure * (r.vertex[3 * c + k] + a[k]))); });
      caption.textContent = 'Vertex colours (lesson 12, extrapolated at the walls\' edges), Gouraud-shaded; the shooter is outlined.';
    } else {
      this.paintFlat(this.displayed(), r.shooter >= 0 ? r.shooter : null);
      caption.textContent = 'One flat colour per patch' + (this.ambient.checked && r.ambient ? ', the ambient term added for display' : ': what the shots so far have sent, no ambient term') + '; the shooter is outlined.';
      return;
    }
    this.patchMesh.outlinePatch(this.viewer.scene, r.shooter);
    this.viewer.draw();
  }

  // The picture at most ten times a second, the last step's always: on a CPU's WebGL a picture of
  // the 2,124-patch box is half of what a shot costs, and steps pressed faster than that (or run)
  // are seen as they add up.
  repaintSoon() {
    const wait = 100 - (performance.now() - (this.repainted || 0));
    if (wait <= 0) { clearTimeout(this.repaintTimer); this.repaintTimer = null; this.repainted = performance.now(); this.repaint(); return; }
    if (!this.repaintTimer) this.repaintTimer = setTimeout(() => { this.repaintTimer = null; this.repainted = performance.now(); this.repaint(); }, wait);
  }

  // The chart at most about seven times a second, the last step's always (shots pressed or run
  // faster than that add their points between two drawings).
  chartSoon() {
    const wait = 150 - (performance.now() - (this.chartDrawn || 0));
    if (wait <= 0) { clearTimeout(this.chartTimer); this.chartTimer = null; this.chart(); return; }
    if (!this.chartTimer) this.chartTimer = setTimeout(() => { this.chartTimer = null; this.chart(); }, wait);
  }

  chart() {
    this.chartDrawn = performance.now();
    const unit = UNIT[this.method.value];
    logChart(document.getElementById('rad-chart'), [{ points: this.history }],
      { xLabel: `${unit}s`, yLabel: 'unshot / emitted', integerX: true });
  }
}
