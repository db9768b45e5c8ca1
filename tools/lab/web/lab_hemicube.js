// View 3: the hemicube on one patch (GET /api/hemicube): its five item
// buffers and delta form factors unfolded, the row they add up to, and its
// error against the exact factor from the centroid (Lambert's contour
// formula) as the resolution changes (GET /api/hemicube/study).
import { afterNextFrame, api, decodeBase64, displayNumber, el, loadThree, logChart, setStatus, threeMissing, Viewer } from './lab_util.js';
import { heat, PatchMesh } from './lab_mesh.js';

// lib/illum/radiosity/hemicube.cpp's hemicube_pixel and to_face, for the unfolded drawing.
function hemicubePixel(d, res) {
  if (!(d[2] >= 0)) return null;
  const ax = Math.abs(d[0]), ay = Math.abs(d[1]);
  let face;
  if (d[2] >= ax && d[2] >= ay) face = 0;
  else if (ax >= ay) face = d[0] > 0 ? 1 : 2;
  else face = d[1] > 0 ? 3 : 4;
  const [x, y, z] = d;
  const f = [[x, y, z], [y, z, x], [-y, z, -x], [-x, z, y], [x, z, -y]][face];
  const height = face === 0 ? res : res / 2;
  const col = Math.min(res - 1, Math.max(0, Math.floor((f[0] / f[2] + 1) * 0.5 * res)));
  const row = Math.min(height - 1, Math.max(0, Math.floor((f[1] / f[2] + (face === 0 ? 1 : 0)) * 0.5 * res)));
  return { face, col, row };
}

// The lesson's unfolding: the top face in the middle, each half face folded out with its base outwards.
function drawUnfolded(canvas, res, shade) {
  const n = Math.min(1024, Math.max(256, 2 * res));
  canvas.width = n, canvas.height = n;
  const context = canvas.getContext('2d');
  const image = context.createImageData(n, n);
  for (let py = 0; py < n; ++py)
    for (let px = 0; px < n; ++px) {
      const u = -2 + 4 * (px + 0.5) / n, v = 2 - 4 * (py + 0.5) / n;
      let d = null;
      if (Math.abs(u) <= 1 && Math.abs(v) <= 1) d = [u, v, 1];
      else if (u > 1 && Math.abs(v) <= 1) d = [1, v, 2 - u];
      else if (u < -1 && Math.abs(v) <= 1) d = [-1, v, 2 + u];
      else if (v > 1 && Math.abs(u) <= 1) d = [u, 1, 2 - v];
      else if (v < -1 && Math.abs(u) <= 1) d = [u, -1, 2 + v];
      const o = 4 * (py * n + px);
      const c = d ? shade(hemicubePixel(d, res)) : [246, 246, 243];
      image.data[o] = c[0], image.data[o + 1] = c[1], image.data[o + 2] = c[2], image.data[o + 3] = 255;
    }
  context.putImageData(image, 0, 0);
}

function patchColour(item) {
  let h = Math.imul(item + 1, 2654435761) >>> 0;
  h ^= h >>> 15;
  return [60 + (h & 0xbf), 60 + ((h >>> 8) & 0xbf), 60 + ((h >>> 16) & 0xbf)];
}

// The first surface's patch nearest its middle: a default placement with something to see.
function middlePatch(mesh) {
  const s = mesh.surfaces[0];
  const c = [0, 1, 2].map(k => { let sum = 0; for (let i = s.first; i < s.first + s.count; ++i) sum += mesh.centroid[3 * i + k]; return sum / s.count; });
  let best = s.first, distance = Infinity;
  for (let i = s.first; i < s.first + s.count; ++i) {
    const d = Math.hypot(...[0, 1, 2].map(k => mesh.centroid[3 * i + k] - c[k]));
    if (d < distance) best = i, distance = d;
  }
  return best;
}

export class HemicubeView {
  constructor(info) {
    this.info = info;
    this.section = document.getElementById('tab-hemicube');
    this.status = document.getElementById('hc-status');
    this.holder = document.getElementById('hc-3d');
    this.sceneSelect = document.getElementById('hc-scene');
    for (const s of info.scenes) this.sceneSelect.append(el('option', { value: s, text: s }));
    this.sceneSelect.value = info.scenes.includes('cornell') ? 'cornell' : info.scene;
    this.resolution = document.getElementById('hc-resolution');
    for (const r of [8, 16, 32, 64, 128, 256, 512]) this.resolution.append(el('option', { value: r, text: `${r} pixels` }));
    this.resolution.value = '64';
    this.patchInput = document.getElementById('hc-patch');
    document.getElementById('hc-show').addEventListener('click', e => this.show(e.timeStamp));
    this.resolution.addEventListener('change', e => this.show(e.timeStamp));
    this.patchInput.addEventListener('change', e => { this.patchInput.dataset.chosen = 'true'; this.show(e.timeStamp); });
    for (const id of ['hc-scene', 'hc-patches']) document.getElementById(id).addEventListener('change', e => this.show(e.timeStamp));
    this.threeReady = info.three ? loadThree().catch(() => null) : Promise.resolve(null);
    this.busy = Promise.resolve();
  }

  meshParams() { return { scene: this.sceneSelect.value, patches: document.getElementById('hc-patches').value }; }

  async ensureMesh() {
    const key = JSON.stringify(this.meshParams());
    if (this.meshKey === key) return;
    this.mesh = await api('/api/radiosity/mesh', this.meshParams());
    this.meshKey = key;
    this.patchInput.max = this.mesh.patches - 1;
    if (this.patchInput.dataset.chosen !== 'true') this.patchInput.value = middlePatch(this.mesh);
    const three = await this.threeReady;
    if (!three) { threeMissing(this.holder, this.info); this.viewer = null; this.patchMesh = null; return; }
    if (!this.viewer) {
      this.viewer = new Viewer(this.holder, three, { antialias: false });
      this.viewer.renderer.domElement.addEventListener('click', e => {
        if (!this.patchMesh) return;
        const hit = this.viewer.pick(e, [this.patchMesh.object]);
        if (hit) {
          this.patchInput.value = this.patchMesh.patchOfTriangle[hit.faceIndex];
          this.patchInput.dataset.chosen = 'true';
          this.show(e.timeStamp);
        }
      });
    }
    this.viewer.scene.clear();
    this.patchMesh = new PatchMesh(three.THREE, this.mesh);
    this.viewer.scene.add(this.patchMesh.object);
    this.paintSurfaces();
    this.patchMesh.cameraView(this.viewer);
  }

  paintSurfaces() {
    const m = this.mesh;
    this.patchMesh.paintPatches(i => m.emission[3 * i] > 0 ? [1, 0.9, 0.6] : [0, 1, 2].map(k => 0.15 + 0.8 * m.reflectance[3 * i + k]));
  }

  // `askedAt`: the event's time; the status gives the time from it to the frame that shows the row.
  show(askedAt = performance.now()) {
    this.busy = this.busy.then(() => this.place(askedAt), () => this.place(askedAt));
    return this.busy;
  }

  async place(askedAt) {
    this.section.dataset.state = 'placing';
    setStatus(this.status, 'placing the hemicube…');
    try {
      await this.ensureMesh();
      const patch = Math.min(Math.max(0, Number(this.patchInput.value) || 0), this.mesh.patches - 1);
      this.patchInput.value = patch;
      const res = Number(this.resolution.value);
      const [h, study] = await Promise.all([
        api('/api/hemicube', { ...this.meshParams(), patch, resolution: res }, 'json', { view: 'hemicube' }),
        api('/api/hemicube/study', { ...this.meshParams(), patch }, 'json', { view: 'hemicube' }).catch(e => ({ rows: [], error: e.message }))]);
      this.draw(h, study);
      this.section.dataset.patch = String(patch);
      this.section.dataset.resolution = String(res);
      this.section.dataset.sum = String(h.sum);
      const status = `patch ${patch} (${h.surface}), resolution ${res}: the row sums to ${displayNumber(h.sum)} ` +
        `(1 − Σ = ${displayNumber(1 - h.sum)} of the hemisphere sees no patch); its hemicube took ${displayNumber(h.seconds * 1000)} ms`;
      setStatus(this.status, status);
      this.section.dataset.state = 'drawn';
      const shownAt = await afterNextFrame();
      if (this.section.dataset.patch === String(patch) && this.section.dataset.resolution === String(res))
        setStatus(this.status, `${status}, on the screen ${Math.round(shownAt - askedAt)} ms after it was asked for`);
    } catch (e) {
      this.section.dataset.state = 'error';
      setStatus(this.status, e.message, true);
    }
  }

  draw(h, study) {
    const res = h.resolution;
    const faces = h.faces.map(f => decodeBase64(f.items, Int32Array));
    drawUnfolded(document.getElementById('hc-items'), res, p => {
      const item = faces[p.face][p.row * res + p.col];
      return item === -1 ? [0, 0, 0] : item === -2 ? [70, 70, 70] : patchColour(item);
    });
    const top = decodeBase64(h.deltas.top, Float32Array), side = decodeBase64(h.deltas.side, Float32Array);
    let maxDelta = 0;  // (not Math.max(...top): a 512-pixel face is more arguments than a call may take)
    for (const d of top) maxDelta = Math.max(maxDelta, d);
    drawUnfolded(document.getElementById('hc-deltas'), res, p => {
      const d = (p.face === 0 ? top : side)[p.row * res + p.col] / maxDelta;
      const g = Math.round(255 * Math.sqrt(Math.max(0, d)));
      return [g, Math.round(g * 0.85), Math.round(g * 0.5)];
    });
    if (this.patchMesh) {
      this.patchMesh.paintPatches(i => i === h.patch ? [1, 0.1, 0.8] : heat(h.row[i]));
      this.patchMesh.outlinePatch(this.viewer.scene, h.patch);
      this.viewer.draw();
    }
    const summary = document.getElementById('hc-summary');
    const items = [el('p', {}, 'Σ', el('sub', { text: 'j' }), ` F_ij = `, el('strong', { id: 'hc-sum', 'data-value': String(h.sum), text: displayNumber(h.sum) }),
      ` from ${res} × ${res} + 4 × ${res} × ${res / 2} pixels.`)];
    if (h.exact) {
      const e = h.errors;
      items.push(el('p', { id: 'hc-errors', 'data-targets': e.targets, 'data-mean-rel': e.mean_rel, 'data-max-abs': e.max_abs,
        'data-weighted-rel': e.weighted_rel, 'data-edge-on': e.edge_on,
        text: `Against the exact factor from the centroid, over the ${e.targets} patches it sees whole: largest error ${displayNumber(e.max_abs)}, ` +
          `mean ${displayNumber(e.mean_abs)}; the share of the row's total on the wrong patch ${displayNumber(e.weighted_rel)}; ` +
          `mean relative error ${displayNumber(e.mean_rel)} (${displayNumber(e.mean_rel_above)} without the ${e.edge_on} seen edge-on).` }));
    } else {
      items.push(el('p', { class: 'error', text: `No exact reference: ${h.exact_error}` }));
    }
    const rows = study.rows;
    if (study.error) items.push(el('p', { class: 'error', text: `No resolution study: ${study.error}` }));
    summary.replaceChildren(...items);
    logChart(document.getElementById('hc-chart'), [
      { points: rows.map(r => [r.resolution, r.weighted_rel]), className: 'series', label: 'Σ|ΔF| / ΣF' },
      { points: rows.map(r => [r.resolution, r.mean_rel_above]), className: 'series3', label: 'mean relative error (above 1°)' },
      { points: rows.map(r => [r.resolution, r.max_abs]), className: 'series2', label: 'largest error' }],
      { xLabel: 'resolution (pixels across the top face)', logX: true });
    this.explain(rows);
    // The largest factors of the row, beside their exact values.
    const table = document.getElementById('hc-targets');
    const order = h.row.map((f, j) => j).sort((a, b) => h.row[b] - h.row[a]).slice(0, 12);
    table.replaceChildren(el('caption', { text: `The twelve largest factors of row ${h.patch}, and the study of the same row at every resolution` }),
      el('tr', {}, ...['patch', 'surface', 'hemicube F_ij', 'exact from the centroid', 'error', 'seen whole'].map(t => el('th', { text: t }))),
      ...order.map(j => el('tr', {}, el('td', { text: j }), el('td', { text: this.patchMesh ? this.patchMesh.surfaceOf(j) : '' }),
        el('td', { text: displayNumber(h.row[j]) }), el('td', { text: h.exact ? displayNumber(h.exact[j]) : '—' }),
        el('td', { text: h.exact ? displayNumber(h.row[j] - h.exact[j]) : '—' }), el('td', { text: h.exact ? (h.seen_whole[j] ? 'yes' : 'no') : '—' }))),
      el('tr', {}, ...['resolution', 'Σ F_ij', 'largest error', 'Σ|ΔF| / ΣF', 'mean relative error, all', 'above 1°', 'patches seen whole', 'edge-on', 'ms'].map(t => el('th', { text: t }))),
      ...rows.map(r => el('tr', { class: 'study-row', 'data-resolution': r.resolution, 'data-sum': String(r.sum),
        'data-weighted-rel': String(r.weighted_rel), 'data-mean-rel': String(r.mean_rel), 'data-mean-rel-above': String(r.mean_rel_above) },
        el('td', { text: r.resolution }), el('td', { text: displayNumber(r.sum) }), el('td', { text: displayNumber(r.max_abs) }),
        el('td', { text: displayNumber(r.weighted_rel) }), el('td', { text: displayNumber(r.mean_rel) }), el('td', { text: displayNumber(r.mean_rel_above) }),
        el('td', { text: r.targets }), el('td', { text: r.edge_on }), el('td', { text: displayNumber(r.seconds * 1000) }))));
  }

  // Why the mean relative error over every target may not fall as the resolution grows, in this
  // row's own numbers (lab_radiosity.cpp, row_errors).
  explain(rows) {
    const why = document.getElementById('hc-why');
    if (rows.length < 2) { why.textContent = ''; return; }
    const a = rows[0], b = rows[rows.length - 1], range = (f, x = v => v) => `${displayNumber(x(a[f]))} at ${a.resolution} pixels to ${displayNumber(x(b[f]))} at ${b.resolution}`;
    const common = `The mean relative error counts every target alike, the smallest factors as much as the largest; a target whose outline ` +
      `covers a few pixels is drawn too large or too small by a pixel's worth, so its relative error falls only as fast as a pixel shrinks. ` +
      `Weighted by the factors, the share of the row's total put on the wrong patch goes from ${range('weighted_rel')}, and the largest error from ${range('max_abs')}.`;
    why.textContent = b.edge_on > 0
      ? `${b.edge_on} of the ${b.targets} targets lie within ${b.edge_on_degrees}° of this patch's plane, seen edge-on (their factors add up to ` +
        `${displayNumber(b.edge_on_factor)}): at every resolution they fall in the side faces' lowest row of pixels, whose delta form factor, ` +
        `taken at the pixel's centre, is far from their tiny factors, so their relative errors stay near 1 and the mean over every target goes from ` +
        `${range('mean_rel')}. Without them it goes from ${range('mean_rel_above')}. ${common}`
      : `Every target lies more than ${b.edge_on_degrees}° above this patch's plane; the mean relative error goes from ${range('mean_rel')}. ${common}`;
    why.dataset.edgeOn = String(b.edge_on);
  }
}
