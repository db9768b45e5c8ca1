// View 1: a pixel's ray tree. The image is rendered by the build's evaluate
// (GET /api/render); a click asks for that pixel's tree (GET /api/trace, the
// JSON `illum trace --pixel` writes) and draws it in 3D over the scene's
// geometry (GET /api/scene) and as a diagram, depth by depth. With a
// reference beside the build (docs/lab.md), the reference's tree of the same
// pixel is held against it node by node (lab_difference.js).
import { afterNextFrame, api, displayColour, displayNumber, el, loadThree, setStatus, svg, threeMissing, Viewer } from './lab_util.js';
import { compareTrees, showTreeComparison } from './lab_difference.js';

const KIND_COLOUR = { primary: 0xeeeeee, reflection: 0x22ccee, refraction: 0xff8c1a, shadow: 0xf2dc33, blocked: 0xff2a2a };
const KIND_FILL = { primary: '#e8e8e8', reflection: '#cdeff5', refraction: '#fde0c2', shadow: '#fbf3c0', blocked: '#f6c6c6' };
const EDGE_LABEL = { reflection: 'k_r', refraction: 'k_t', shadow: 'shadow' };
const STUB_REASON = { total_internal_reflection: 'total internal reflection', pruned: 'pruned', not_cast: 'missing (check evaluate)' };
const SELECTED = [1, 0.2, 0.8], REFERENCE_GREY = 0x9aa0a8;

// The diagram's text, measured as the SVG draws it (lab.css: 11px DejaVu Sans).
const FONT = '11px "DejaVu Sans", sans-serif';
let measurer = null;
function textWidth(text) {
  if (!measurer) { measurer = document.createElement('canvas').getContext('2d'); measurer.font = FONT; }
  return measurer.measureText(text).width;
}
// A line cut after a comma or a space so that no piece is wider than `width` pixels (never cut short).
function wrap(line, width) {
  if (textWidth(line) <= width) return [line];
  const out = [];
  let current = '';
  for (const word of line.split(/(?<=[ ,])/)) {
    if (current && textWidth(current + word) > width) out.push(current.trimEnd()), current = '  ' + word.trimStart();
    else current += word;
  }
  if (current.trim()) out.push(current.trimEnd());
  return out;
}

export class TreeView {
  constructor(info) {
    this.info = info;
    this.reference = info.reference && info.reference.available;
    this.section = document.getElementById('tab-tree');
    this.image = document.getElementById('tree-image');
    this.imageNote = document.getElementById('tree-image-note');
    this.status = document.getElementById('tree-status');
    this.holder = document.getElementById('tree-3d');
    this.diagram = document.getElementById('tree-diagram');
    this.details = document.getElementById('tree-details');
    this.versus = document.getElementById('tree-versus');
    this.sceneSelect = document.getElementById('tree-scene');
    this.depthInput = document.getElementById('tree-depth');
    this.planInput = document.getElementById('tree-plan');
    this.pruneInput = document.getElementById('tree-prune');
    for (const s of info.scenes) this.sceneSelect.append(el('option', { value: s, text: s }));
    this.sceneSelect.value = info.scene;
    this.depthInput.value = info.settings.depth;
    this.planInput.checked = info.settings.plan;
    this.pruneInput.value = info.settings.prune;
    for (const input of [this.sceneSelect, this.depthInput, this.planInput, this.pruneInput])
      input.addEventListener('change', e => this.loadScene(e.timeStamp));
    this.image.addEventListener('click', e => this.clicked(e));
    document.getElementById('tree-camera-view').addEventListener('click', () => this.cameraView());
    document.getElementById('tree-depth-down').addEventListener('click', () => this.showDepth(this.shown === null ? this.maxDepth() - 1 : this.shown - 1));
    document.getElementById('tree-depth-up').addEventListener('click', () => this.showDepth(this.shown === null ? null : this.shown + 1));
    document.getElementById('tree-depth-all').addEventListener('click', () => this.showDepth(null));
    document.getElementById('tree-versus-pane').hidden = !this.reference;
    document.querySelector('#tab-tree .legend .k-reference').hidden = !this.reference;
    this.shown = null;
    this.tree = null;
    this.threeReady = info.three ? loadThree().catch(() => null) : Promise.resolve(null);
  }

  settings() {
    return { scene: this.sceneSelect.value, depth: this.depthInput.value, plan: this.planInput.checked ? 1 : 0,
      prune: this.pruneInput.value };
  }

  // The scene's picture and geometry: this build's, or, when its evaluate is not written yet and a
  // reference runs beside it, the reference's (said so over the picture), so that a click still
  // shows the tree to aim for.
  // `askedAt`: the change's event time; the status gives the time from it to the frame with the picture.
  async loadScene(askedAt = performance.now()) {
    if (this.loading) this.loading.abort();
    const loading = this.loading = new AbortController();
    const options = { view: 'tree', signal: loading.signal };
    this.section.dataset.state = 'loading';
    setStatus(this.status, 'rendering…');
    this.tree = null;
    this.nodes = [];
    this.diagram.replaceChildren();
    this.versus.replaceChildren();
    this.details.replaceChildren(el('p', { class: 'muted', text: 'No node selected.' }));
    document.getElementById('tree-marker').hidden = true;
    const get = prefix => Promise.all([api(`/api/${prefix}render`, this.settings(), 'blob', options), api(`/api/${prefix}scene`, this.settings(), 'json', options)]);
    let blob, geometry, yoursError = null;
    try {
      [blob, geometry] = await get('');
    } catch (e) {
      if (e.cancelled) return;
      yoursError = e;
    }
    try {
      if (yoursError && this.reference && yoursError.notImplemented) [blob, geometry] = await get('reference/');
    } catch (e) {
      if (e.cancelled) return;
    }
    if (loading.signal.aborted) return;
    this.drawnBy = yoursError ? (blob ? 'reference' : null) : 'yours';
    this.section.dataset.drawnBy = this.drawnBy || 'nothing';
    this.imageNote.hidden = !yoursError;
    this.imageNote.textContent = !yoursError ? '' : blob
      ? `Your evaluate cannot draw this yet (${yoursError.message}): this is the reference's picture; click a pixel for the reference's tree.`
      : `Nothing to draw yet: ${yoursError.message}`;
    this.imageNote.classList.toggle('error', Boolean(yoursError));
    this.image.hidden = !blob;
    if (!blob) {  // no picture and no 3D view to click on: say why in both places, no broken image
      this.geometry = null;
      this.message3d(`No scene to draw: ${yoursError.message}`);
      this.section.dataset.state = 'error';
      setStatus(this.status, yoursError.message, true);
      return;
    }
    try {
      if (this.imageUrl) URL.revokeObjectURL(this.imageUrl);
      this.imageUrl = URL.createObjectURL(blob);
      await new Promise((resolve, reject) => { this.image.onload = resolve; this.image.onerror = reject; this.image.src = this.imageUrl; });
      this.geometry = geometry;
      this.kinds = [];
      for (const o of geometry.objects) this.kinds[o.index] = o.kind;
      await this.buildScene(geometry);
      const ms = await afterNextFrame() - askedAt;
      setStatus(this.status, 'preparing the 3D view…');
      await this.warmUp();
      if (loading.signal.aborted) return;
      setStatus(this.status, `${geometry.scene}: ${this.drawnBy === 'reference' ? "the reference's picture, " : ''}` +
        `${geometry.camera.width} × ${geometry.camera.height}, on the screen ${Math.round(ms)} ms after it was asked for; click a pixel`);
      this.section.dataset.state = 'ready';
    } catch (e) {
      this.section.dataset.state = 'error';
      setStatus(this.status, e.message, true);
    }
  }

  // A message over the 3D view instead of its picture (null: the picture again).
  message3d(text) {
    for (const m of this.holder.querySelectorAll('.message')) m.remove();
    if (text) this.holder.append(el('div', { class: 'message', text }));
  }

  async buildScene(g) {
    const three = await this.threeReady;
    if (!three) { threeMissing(this.holder, this.info); this.viewer = null; return; }
    this.message3d(null);
    const { THREE, LineSegments2, LineSegmentsGeometry } = three;
    if (!this.viewer) {
      this.viewer = new Viewer(this.holder, three, { antialias: false, overlay: true });
      // The rays' materials and objects, made once and refilled on every click: a new material is
      // a new shader program, compiled again (hundreds of milliseconds on a CPU's WebGL).
      const v = this.viewer;
      this.materials = {
        solid: v.lineMaterial({ linewidth: 3, vertexColors: true, depthTest: false, transparent: true }),
        dashed: v.lineMaterial({ linewidth: 3, vertexColors: true, depthTest: false, transparent: true, dashed: true }),
        selected: v.lineMaterial({ linewidth: 6, color: new THREE.Color(...SELECTED), depthTest: false, transparent: true }),
        reference: v.lineMaterial({ linewidth: 2, color: REFERENCE_GREY, depthTest: false, transparent: true, dashed: true }),
        dot: new THREE.MeshBasicMaterial({ depthTest: false }),
      };
      this.lines = {};
      for (const [name, order] of [['reference', 9], ['solid', 10], ['dashed', 10], ['selected', 11]]) {
        this.lines[name] = new LineSegments2(new LineSegmentsGeometry(), this.materials[name]);
        this.lines[name].renderOrder = order;
        this.lines[name].frustumCulled = false;
      }
      this.dotGeometry = new THREE.SphereGeometry(1, 10, 8);
    }
    const v = this.viewer;
    v.scene.clear();
    const lo = g.bounds ? g.bounds.lo : [-1, -1, -1], hi = g.bounds ? g.bounds.hi : [1, 1, 1];
    this.size = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1;
    this.materials.dashed.dashSize = this.materials.reference.dashSize = this.size * 0.015;
    this.materials.dashed.gapSize = this.materials.reference.gapSize = this.size * 0.008;
    v.scene.add(new THREE.AmbientLight(0xffffff, 1.2));
    const sun = new THREE.DirectionalLight(0xffffff, 1.6);
    sun.position.set(...(g.lights.length && g.lights[0].position ? g.lights[0].position : g.camera.eye));
    v.scene.add(sun);
    const world = new THREE.Group();
    for (const o of g.objects) {
      const colour = new THREE.Color().setRGB(...o.colour, THREE.SRGBColorSpace);
      const material = new THREE.MeshLambertMaterial({ color: colour, side: THREE.DoubleSide,
        transparent: o.transparency > 0, opacity: o.transparency > 0 ? 1 - 0.75 * o.transparency : 1, depthWrite: !(o.transparency > 0) });
      let object = null;
      if (o.sphere) {
        object = new THREE.Mesh(new THREE.SphereGeometry(o.sphere.radius, 48, 32), material);
        object.position.set(...o.sphere.centre);
      } else if (o.loops) {
        object = new THREE.Mesh(polygonGeometry(THREE, o.loops), material);
      } else if (o.mesh) {
        const geometry = new THREE.BufferGeometry();
        geometry.setAttribute('position', new THREE.Float32BufferAttribute(o.mesh.positions, 3));
        geometry.setIndex(o.mesh.indices);
        geometry.computeVertexNormals();
        object = new THREE.Mesh(geometry, material);
      } else if (o.points) {
        const geometry = new THREE.BufferGeometry();
        geometry.setAttribute('position', new THREE.Float32BufferAttribute(o.points.positions, 3));
        object = new THREE.Points(geometry, new THREE.PointsMaterial({ color: colour, size: this.size * 0.004 }));
      }
      if (object) { object.name = o.name; world.add(object); }
    }
    v.scene.add(world);
    // The point lights and the eye as dots a few pixels across, whatever their distance: a ball the
    // size of the scene's hundredth, near the viewer, covered the primary ray and the glass ball.
    const dot = (position, colour, pixels, name) => {
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.Float32BufferAttribute(position, 3));
      const p = new THREE.Points(geometry, new THREE.PointsMaterial({ color: colour, size: pixels, sizeAttenuation: false }));
      p.name = name;
      return p;
    };
    for (const l of g.lights) {
      if (l.kind === 'point') v.scene.add(dot(l.position, 0xffd400, 10, 'light'));
      else v.scene.add(new THREE.Mesh(polygonGeometry(THREE, [l.polygon]),
        new THREE.MeshBasicMaterial({ color: 0xffe680, side: THREE.DoubleSide })));
    }
    this.eye = dot(g.camera.eye, 0xffffff, 7, 'eye');
    v.scene.add(this.eye);
    this.dots = null;
    this.nodes = [];
    v.overlay.clear();
    for (const line of Object.values(this.lines)) v.overlay.add(line);
    this.updateRays();  // (no rays: makes the dots' mesh)
    for (const line of Object.values(this.lines)) {  // one short segment each, for the shaders below
      line.geometry.setPositions([0, 0, 0, 0, 0, 1e-9]);
      if (line.material.vertexColors) line.geometry.setColors([0, 0, 0, 0, 0, 0]);
      if (line.material.dashed) line.computeLineDistances();
      line.visible = true;
    }
    this.cameraView();
    // Every shader now, and a first frame (a CPU's WebGL compiles a shader at its first draw), not
    // at the first click.
    v.overlayRenderer.compile(v.overlay, v.camera);
    v.drawNow();
    for (const line of Object.values(this.lines)) line.visible = false;
  }

  cameraView() {
    if (!this.viewer || !this.geometry) return;
    const c = this.geometry.camera;
    // A little behind the scene's own eye, so that the primary ray is seen leaving it.
    const eye = c.eye.map((e, i) => e + (e - c.target[i]) * 0.25);
    this.viewer.look(eye, c.target, c.up, c.vertical_fov_degrees * 1.15, this.size);
  }

  clicked(event) {
    if (!this.geometry || this.section.dataset.state === 'loading') return;
    const rect = this.image.getBoundingClientRect();
    const w = this.image.naturalWidth, h = this.image.naturalHeight;
    const x = Math.min(w - 1, Math.max(0, Math.floor((event.clientX - rect.left) / rect.width * w)));
    const y = Math.min(h - 1, Math.max(0, Math.floor((event.clientY - rect.top) / rect.height * h)));
    const marker = document.getElementById('tree-marker');
    marker.style.left = `${(x + 0.5) / w * 100}%`;
    marker.style.top = `${(y + 0.5) / h * 100}%`;
    marker.hidden = false;
    return this.trace(x, y, event.timeStamp);
  }

  // The tree of pixel (x, y), drawn; `clickedAt` is the click event's time (performance.now's
  // clock): the time shown is from it to the frame with the tree on the screen.
  // `warm`: the warm-up's (warmUp), which says nothing. Returns whether a tree was drawn.
  async trace(x, y, clickedAt = performance.now(), warm = false) {
    if (this.tracing) this.tracing.abort();
    const tracing = this.tracing = new AbortController();
    const options = { view: 'tree', signal: tracing.signal };
    if (!warm) this.section.dataset.state = 'tracing';
    const params = { ...this.settings(), x, y };
    const [yours, reference] = await Promise.allSettled([api('/api/trace', params, 'json', options),
      this.reference ? api('/api/reference/trace', params, 'json', options) : Promise.resolve(null)]);
    if (tracing.signal.aborted) return false;
    const failed = yours.status === 'rejected' ? yours.reason : null;
    const tree = failed ? (reference.value || null) : yours.value;
    if (!tree) {
      if (warm) return false;
      this.section.dataset.state = 'error';
      setStatus(this.status, (failed || reference.reason).message, true);
      return false;
    }
    this.tree = tree;
    this.treeOwner = failed ? 'reference' : 'yours';
    this.nodes = flatten(tree);
    this.shown = null;
    this.selected = tree.tree ? 0 : -1;
    this.comparison = null;
    if (this.reference) {
      if (reference.status === 'fulfilled') {
        this.comparison = compareTrees(failed ? null : yours.value, reference.value, this.kinds);
        showTreeComparison(this.versus, this.comparison, { yoursError: failed && failed.message, onSelect: id => this.select(id) });
      } else {
        this.versus.replaceChildren(el('p', { class: 'error', text: `The reference could not trace this pixel: ${reference.reason.message}` }));
      }
    }
    document.getElementById('tree-diagram-caption').textContent = this.treeOwner === 'yours' ? 'Your tree' : "The reference's tree (yours is not written yet)";
    this.drawDiagram();
    this.select(this.selected, false);
    this.showDepth(null, false);
    const k = tree.rays_by_kind;
    document.getElementById('tree-pixel').textContent =
      `pixel (${x}, ${y}): colour ${displayColour(tree.color)}; ${tree.nodes} nodes from ${tree.rays} rays ` +
      `(primary ${k.primary}, shadow ${k.shadow}, reflection ${k.reflection}, refraction ${k.refraction}); ` +
      `depth limit ${tree.depth_limit}${tree.depth_limit < tree.depth_requested ? ` (the plan cut ${tree.depth_requested})` : ''}`;
    // The rays drawn in the next frame, with the diagram (the scene's geometry under them is not
    // drawn again); the time is taken once that frame is out.
    if (this.viewer) await new Promise(resolve => requestAnimationFrame(() => { this.updateRays(); this.viewer.drawOverlay(); resolve(); }));
    const shownAt = await afterNextFrame();
    if (tracing.signal.aborted) return false;
    if (warm) return true;
    const ms = shownAt - clickedAt;
    setStatus(this.status, `tree of pixel (${x}, ${y}) on the screen ${Math.round(ms)} ms after the click`);
    this.section.dataset.pixel = `${x},${y}`;
    this.section.dataset.clickMs = ms.toFixed(1);
    this.section.dataset.state = 'drawn';
    document.dispatchEvent(new CustomEvent('lab:tree-drawn', { detail: { x, y, ms } }));
    return true;
  }

  // A CPU's WebGL (Chromium's SwiftShader) prepares each kind of draw the first time it is made,
  // and the page lays out its diagram and tables the first time: the first clicks took 0.4 to 0.9 s
  // on a loaded machine, the later ones a tenth of that. Two pixels are traced and drawn as a click
  // would, while the scene loads, then cleared.
  async warmUp() {
    if (!this.viewer) return;
    const c = this.geometry.camera;
    const marker = document.getElementById('tree-marker');
    for (const [fx, fy] of [[0.5, 0.5], [0.35, 0.6]]) {
      marker.style.left = `${fx * 100}%`, marker.style.top = `${fy * 100}%`, marker.hidden = false;
      if (!await this.trace(Math.floor(fx * c.width), Math.floor(fy * c.height), performance.now(), true)) return;
    }
    marker.hidden = true;
    this.nodes = [];
    this.tree = this.comparison = null;
    this.diagram.replaceChildren();
    this.versus.replaceChildren();
    this.details.replaceChildren(el('p', { class: 'muted', text: 'No node selected.' }));
    document.getElementById('tree-pixel').textContent = '';
    this.updateRays();
    this.viewer.drawOverlay();
  }

  // Each node's pieces: a shadow ray's segments, or one ray to its hit (or far off when it missed).
  pieces(n) {
    if (n.kind === 'shadow')
      return n.segments.map((s, i) => ({ a: s.origin, b: s.end,
        colour: n.stop.reason === 'blocked' && i === n.segments.length - 1 ? KIND_COLOUR.blocked : KIND_COLOUR.shadow }));
    const far = this.size * 1.5;
    const b = n.hit ? n.hit.point : n.origin.map((o, i) => o + far * n.direction[i]);
    return [{ a: n.origin, b, colour: KIND_COLOUR[n.kind] }];
  }

  // The rays of the nodes shown (the depth shown), the selected one thicker, and, where the
  // reference's tree differs from yours, the reference's rays in grey: a handful of objects,
  // refilled on every click, never a new material.
  updateRays() {
    if (!this.viewer) return;
    const THREE = this.viewer.THREE;
    const fill = (line, pieces, coloured) => {
      line.visible = pieces.length > 0;
      if (!pieces.length) return;
      line.geometry.setPositions(pieces.flatMap(p => [...p.a, ...p.b]));
      if (coloured) line.geometry.setColors(pieces.flatMap(p => { const c = new THREE.Color(p.colour); return [c.r, c.g, c.b, c.r, c.g, c.b]; }));
      if (line.material.dashed) line.computeLineDistances();
    };
    const visible = this.nodes.filter(n => this.shown === null || n.depth <= this.shown);
    const solid = [], dashed = [], selected = [], ends = [];
    for (const n of visible) {
      const pieces = this.pieces(n);
      (n.kind === 'shadow' ? dashed : solid).push(...pieces);
      if (n.id === this.selected) selected.push(...pieces);
      if (n.kind === 'shadow' || n.hit) ends.push(...pieces.map(p => ({ at: p.b, colour: p.colour, r: n.kind === 'shadow' ? 0.004 : 0.006 })));
    }
    const ghost = [];
    if (this.comparison && this.treeOwner === 'yours')
      for (const row of this.comparison.rows)
        if (row.reference && row.fields.size && (this.shown === null || row.reference.depth <= this.shown)) ghost.push(...this.pieces(row.reference));
    if (!this.nodes.length) ends.push({ at: [0, 0, 0], colour: 0, r: 0 });  // (the first build: one dot for the shader)
    fill(this.lines.solid, solid, true);
    fill(this.lines.dashed, dashed, true);
    fill(this.lines.selected, selected, false);
    fill(this.lines.reference, ghost, false);
    // Where each piece ends (a hit, a surface a shadow ray crosses, its light): one instanced mesh.
    const v = this.viewer;
    if (!this.dots || this.dots.instanceMatrix.count < ends.length) {
      if (this.dots) v.overlay.remove(this.dots), this.dots.dispose();
      this.dots = new THREE.InstancedMesh(this.dotGeometry, this.materials.dot, Math.max(64, 2 * ends.length));
      this.dots.renderOrder = 12;
      this.dots.frustumCulled = false;
      v.overlay.add(this.dots);
    }
    const m = new THREE.Matrix4(), c = new THREE.Color();
    ends.forEach((e, i) => {
      const r = this.size * e.r;
      this.dots.setMatrixAt(i, m.makeScale(r, r, r).setPosition(...e.at));
      this.dots.setColorAt(i, c.set(e.colour));
    });
    this.dots.count = ends.length;
    this.dots.instanceMatrix.needsUpdate = true;
    if (this.dots.instanceColor) this.dots.instanceColor.needsUpdate = true;
    this.holder.dataset.drawnRays = String(visible.length);
    this.holder.dataset.drawnSegments = String(solid.length + dashed.length);
    this.holder.dataset.referenceSegments = String(ghost.length);
  }

  nodeLines(n) {
    const lines = [`${n.kind} (depth ${n.depth})`];
    if (n.kind === 'shadow') {
      lines.push(`to ${n.light_name}`);
      n.segments.slice(0, -1).forEach(s => lines.push(`through ${s.hit.primitive}: ${displayColour(s.transmission)}`));
      lines.push(n.stop.reason === 'blocked' ? `blocked by ${n.hit ? n.hit.primitive : 'a surface'}` : `reached it: ${displayColour(n.transmission)}`);
    } else if (n.hit) {
      lines.push(`hit ${n.hit.primitive}`, `t = ${displayNumber(n.hit.t)} (${n.hit.front_face ? 'front' : 'back'})`,
        `I_own ${displayColour(n.local)}`);
      if (n.stop.reason !== 'continues') lines.push(`stops: ${n.stop.reason.replaceAll('_', ' ')}`);
    } else {
      lines.push('missed: background', displayColour(n.color));
    }
    lines.push(`weight ${displayColour(n.weight)}`);
    return lines.flatMap(line => wrap(line, 176));
  }

  // A tidy tree: each box as wide as its longest line, a parent centred over its children; the
  // whole drawing scaled to the pane's width (down to 0.6, then the pane scrolls sideways).
  drawDiagram() {
    this.diagram.replaceChildren();
    this.diagramNodes = new Map();
    if (!this.nodes.length) return;
    const gapX = 12, gapY = 34, lineH = 13;
    const boxes = new Map(this.nodes.map(n => {
      const lines = this.nodeLines(n);
      return [n.id, { lines, w: Math.ceil(Math.max(...lines.map(textWidth))) + 14, h: 8 + lineH * lines.length }];
    }));
    const levelHeight = [];
    for (const n of this.nodes) levelHeight[n.level] = Math.max(levelHeight[n.level] || 0, boxes.get(n.id).h);
    const stubs = [];
    for (const n of this.nodes)
      for (const b of (n.branches || []).filter(b => STUB_REASON[b.fate])) {
        const lines = [`no ${b.kind} ray:`, STUB_REASON[b.fate]];
        stubs.push({ parent: n, branch: b, level: n.level + 1, lines, w: Math.ceil(Math.max(...lines.map(textWidth))) + 10, h: 32 });
        levelHeight[n.level + 1] = Math.max(levelHeight[n.level + 1] || 0, 32);
      }
    const levelY = [0];
    for (let i = 1; i < levelHeight.length; ++i) levelY[i] = levelY[i - 1] + levelHeight[i - 1] + gapY;
    let cursor = 0;
    // Places n's subtree from `cursor` rightwards and returns its boxes: a leaf (or stub) takes the
    // next place, a parent is centred over its children, and a parent wider than its children
    // takes its own width, its children moved to its middle (else it would cover a neighbour).
    const place = n => {
      const box = boxes.get(n.id), own = stubs.filter(s => s.parent === n), start = cursor;
      if (!n.children.length && !own.length) { box.x = cursor; cursor += box.w + gapX; return [box]; }
      const placed = n.children.flatMap(place);
      for (const s of own) { s.x = cursor; cursor += s.w + gapX; placed.push(s); }
      const span = cursor - gapX - start;
      if (box.w > span) {
        for (const b of placed) b.x += (box.w - span) / 2;
        cursor = start + box.w + gapX;
      }
      const spans = n.children.map(c => boxes.get(c.id)).concat(own).map(b => [b.x, b.x + b.w]);
      box.x = (Math.min(...spans.map(s => s[0])) + Math.max(...spans.map(s => s[1]))) / 2 - box.w / 2;
      return placed.concat([box]);
    };
    place(this.nodes[0]);
    const left = Math.min(0, ...[...boxes.values()].map(b => b.x)), right = Math.max(cursor - gapX, ...[...boxes.values()].map(b => b.x + b.w));
    const width = right - left, height = levelY[levelY.length - 1] + levelHeight[levelHeight.length - 1];
    const scale = Math.max(0.6, Math.min(1, (this.diagram.clientWidth - 12) / width));
    const root = svg('svg', { width: Math.ceil(width * scale) + 8, height: Math.ceil(height * scale) + 8, viewBox: `${left - 4} -4 ${width + 8} ${height + 8}` });
    const byId = new Map(this.nodes.map(n => [n.id, n]));
    const bottom = n => [boxes.get(n.id).x + boxes.get(n.id).w / 2, levelY[n.level] + boxes.get(n.id).h];
    for (const n of this.nodes) {
      if (n.parentId < 0) continue;
      const [x1, y1] = bottom(byId.get(n.parentId)), x2 = boxes.get(n.id).x + boxes.get(n.id).w / 2, y2 = levelY[n.level];
      root.append(svg('path', { d: `M${x1},${y1} C${x1},${y1 + gapY / 2} ${x2},${y2 - gapY / 2} ${x2},${y2}`, fill: 'none', stroke: '#888',
        'stroke-dasharray': n.kind === 'shadow' ? '4 3' : '' }));
      root.append(svg('text', { x: (x1 + x2) / 2 + 3, y: (y1 + y2) / 2, fill: '#666', text: EDGE_LABEL[n.kind] }));
    }
    for (const s of stubs) {
      const [x1, y1] = bottom(s.parent), x2 = s.x + s.w / 2, y2 = levelY[s.level];
      root.append(svg('path', { d: `M${x1},${y1} L${x2},${y2}`, fill: 'none', stroke: '#aaa', 'stroke-dasharray': '1 3' }));
      const g = svg('g', { class: 'stub', 'data-parent': s.parent.id, 'data-kind': s.branch.kind, 'data-fate': s.branch.fate });
      s.lines.forEach((line, i) => g.append(svg('text', { x: s.x + 4, y: y2 + 12 + 13 * i, text: line })));
      root.append(g);
    }
    const differing = new Set();
    if (this.comparison && this.treeOwner === 'yours')
      for (const row of this.comparison.rows) if (row.yours && row.fields.size) differing.add(row.yours.id);
    const first = this.comparison && this.comparison.first && this.treeOwner === 'yours' && this.comparison.first.row.yours;
    for (const n of this.nodes) {
      const box = boxes.get(n.id);
      const fill = n.kind === 'shadow' && n.stop.reason === 'blocked' ? KIND_FILL.blocked : KIND_FILL[n.kind];
      const g = svg('g', { class: `tree-node${differing.has(n.id) ? ' differs' : ''}${first && first.id === n.id ? ' first-difference' : ''}`,
        'data-id': n.id, 'data-kind': n.kind, 'data-depth': n.depth,
        'data-stop': n.stop.reason, 'data-primitive': n.hit ? n.hit.primitive : '', 'data-t': n.hit ? n.hit.t : '',
        'data-segments': n.segments ? n.segments.length : 0, transform: `translate(${box.x},${levelY[n.level]})` });
      g.append(svg('rect', { width: box.w, height: box.h, rx: 6, fill, 'stroke-dasharray': n.kind === 'shadow' ? '4 3' : '' }));
      box.lines.forEach((line, i) => g.append(svg('text', { x: 7, y: 15 + i * lineH, text: line })));
      g.append(svg('title', { text: box.lines.join('\n') + (n.stop.text ? `\n${n.stop.text}` : '') }));
      g.addEventListener('click', () => this.select(n.id));
      root.append(g);
      this.diagramNodes.set(n.id, g);
    }
    this.diagram.append(root);
    this.diagram.dataset.scale = scale.toFixed(3);
    // The root in view when the tree is still wider than the pane.
    this.diagram.scrollLeft = Math.max(0, (boxes.get(this.nodes[0].id).x - left) * scale - this.diagram.clientWidth / 2);
  }

  select(id, redraw = true) {
    this.selected = id;
    for (const [nid, g] of this.diagramNodes || []) g.classList.toggle('selected', nid === id);
    if (redraw && this.viewer) { this.updateRays(); this.viewer.drawOverlay(); }
    const n = this.nodes && this.nodes.find(m => m.id === id);
    if (!n) { this.details.replaceChildren(el('p', { class: 'muted', text: 'No node selected.' })); return; }
    const rows = [['ray', `${n.kind}, depth ${n.depth}${n.rays.length > 1 ? `, ${n.rays.length} segments` : ''}`],
      ['origin', displayColour(n.origin)], ['direction', displayColour(n.direction)]];
    if (n.kind === 'shadow') {
      rows.push(['light', n.light_name]);
      n.segments.forEach((s, i) => rows.push([`segment ${i + 1}`, s.hit
        ? `to ${s.hit.primitive} (${s.hit.material}) at t = ${displayNumber(s.hit.t)}: transmission ${displayColour(s.transmission)}`
        : `to the light: transmission ${displayColour(s.transmission)}`]));
    } else if (n.hit) {
      rows.push(['hit', `${n.hit.primitive} (${n.hit.front_face ? 'front' : 'back'} face)`], ['t', displayNumber(n.hit.t)],
        ['point', displayColour(n.hit.point)], ['material', n.hit.material], ['local colour I_own', displayColour(n.local)]);
    } else {
      rows.push(['hit', 'nothing: the background']);
    }
    rows.push(['weight', displayColour(n.weight)], ['returns', displayColour(n.color)]);
    for (const b of n.branches || [])
      rows.push([`${b.kind} (k = ${displayColour(b.factor)})`, b.fate.replaceAll('_', ' ')]);
    rows.push(['why it stops', n.stop.reason === 'continues' ? (n.stop.text || 'it goes on') : `${n.stop.reason.replaceAll('_', ' ')}: ${n.stop.text}`]);
    this.details.replaceChildren(el('h3', { text: `${this.treeOwner === 'reference' ? "The reference's node" : 'Node'} ${n.id}` }),
      el('table', {}, ...rows.map(([k, v]) => el('tr', {}, el('th', { text: k }), el('td', { text: v })))));
  }

  maxDepth() { return this.nodes && this.nodes.length ? Math.max(0, ...this.nodes.map(n => n.depth)) : 0; }

  showDepth(d, redraw = true) {
    if (!this.nodes) return;
    const max = this.maxDepth();
    this.shown = d === null || d >= max ? null : Math.max(0, d);
    document.getElementById('tree-depth-shown').textContent = this.shown === null ? `all (to depth ${max})` : `depth ≤ ${this.shown}`;
    for (const n of this.nodes) {
      const visible = this.shown === null || n.depth <= this.shown;
      if (this.diagramNodes && this.diagramNodes.get(n.id)) this.diagramNodes.get(n.id).classList.toggle('hidden-depth', !visible);
    }
    this.section.dataset.shownDepth = this.shown === null ? 'all' : String(this.shown);
    if (redraw && this.viewer) { this.updateRays(); this.viewer.drawOverlay(); }
  }
}

// The tree's nodes in preorder, each with its parent's id and its level in the tree.
function flatten(tree) {
  const nodes = [];
  const walk = (n, parent, level) => { n.parentId = parent; n.level = level; nodes.push(n); n.children.forEach(c => walk(c, n.id, level + 1)); };
  if (tree.tree) walk(tree.tree, -1, 0);
  return nodes;
}

// A polygon with holes, triangulated in its own plane (three's ShapeUtils).
function polygonGeometry(THREE, loops) {
  const outer = loops[0];
  const n = [0, 0, 0];  // Newell's normal
  for (let i = 0; i < outer.length; ++i) {
    const a = outer[i], b = outer[(i + 1) % outer.length];
    n[0] += (a[1] - b[1]) * (a[2] + b[2]); n[1] += (a[2] - b[2]) * (a[0] + b[0]); n[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  const normal = new THREE.Vector3(...n).normalize();
  const u = new THREE.Vector3().crossVectors(Math.abs(normal.x) < 0.9 ? new THREE.Vector3(1, 0, 0) : new THREE.Vector3(0, 1, 0), normal).normalize();
  const v = new THREE.Vector3().crossVectors(normal, u);
  const flat = loop => loop.map(p => new THREE.Vector2(u.dot(new THREE.Vector3(...p)), v.dot(new THREE.Vector3(...p))));
  const triangles = THREE.ShapeUtils.triangulateShape(flat(outer), loops.slice(1).map(flat));
  const positions = loops.flat().flat();
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
  geometry.setIndex(triangles.flat());
  geometry.computeVertexNormals();
  return geometry;
}
