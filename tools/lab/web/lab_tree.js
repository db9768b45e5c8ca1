// View 1: a pixel's ray tree. The image is rendered by the build's evaluate
// (GET /api/render); a click asks for that pixel's tree (GET /api/trace, the
// JSON `illum trace --pixel` writes) and draws it in 3D over the scene's
// geometry (GET /api/scene) and as a diagram, depth by depth.
import { api, displayColour, displayNumber, el, loadThree, setStatus, svg, threeMissing, Viewer } from './lab_util.js';

const KIND_COLOUR = { primary: 0xeeeeee, reflection: 0x22ccee, refraction: 0xff8c1a, shadow: 0xf2dc33, blocked: 0xff2a2a };
const KIND_FILL = { primary: '#e8e8e8', reflection: '#cdeff5', refraction: '#fde0c2', shadow: '#fbf3c0', blocked: '#f6c6c6' };
const EDGE_LABEL = { reflection: 'k_r', refraction: 'k_t', shadow: 'shadow' };
const STUB_REASON = { total_internal_reflection: 'total internal reflection', pruned: 'pruned', not_cast: 'missing (check evaluate)' };

export class TreeView {
  constructor(info) {
    this.info = info;
    this.section = document.getElementById('tab-tree');
    this.image = document.getElementById('tree-image');
    this.status = document.getElementById('tree-status');
    this.holder = document.getElementById('tree-3d');
    this.diagram = document.getElementById('tree-diagram');
    this.details = document.getElementById('tree-details');
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
      input.addEventListener('change', () => this.loadScene());
    this.image.addEventListener('click', e => this.clicked(e));
    document.getElementById('tree-camera-view').addEventListener('click', () => this.cameraView());
    document.getElementById('tree-depth-down').addEventListener('click', () => this.showDepth(this.shown === null ? this.maxDepth() - 1 : this.shown - 1));
    document.getElementById('tree-depth-up').addEventListener('click', () => this.showDepth(this.shown === null ? null : this.shown + 1));
    document.getElementById('tree-depth-all').addEventListener('click', () => this.showDepth(null));
    this.shown = null;
    this.tree = null;
    this.threeReady = info.three ? loadThree().catch(() => null) : Promise.resolve(null);
  }

  settings() {
    return { scene: this.sceneSelect.value, depth: this.depthInput.value, plan: this.planInput.checked ? 1 : 0,
      prune: this.pruneInput.value };
  }

  async loadScene() {
    this.section.dataset.state = 'loading';
    setStatus(this.status, 'rendering…');
    this.tree = null;
    this.diagram.replaceChildren();
    this.details.replaceChildren(el('p', { class: 'muted', text: 'No node selected.' }));
    document.getElementById('tree-marker').hidden = true;
    try {
      const started = performance.now();
      const [blob, geometry] = await Promise.all([api('/api/render', this.settings(), 'blob'), api('/api/scene', this.settings())]);
      if (this.imageUrl) URL.revokeObjectURL(this.imageUrl);
      this.imageUrl = URL.createObjectURL(blob);
      await new Promise((resolve, reject) => { this.image.onload = resolve; this.image.onerror = reject; this.image.src = this.imageUrl; });
      this.geometry = geometry;
      await this.buildScene(geometry);
      setStatus(this.status, `${geometry.scene}: rendered ${geometry.camera.width} × ${geometry.camera.height} in ${Math.round(performance.now() - started)} ms; click a pixel`);
      this.section.dataset.state = 'ready';
    } catch (e) {
      this.section.dataset.state = 'error';
      setStatus(this.status, e.message, true);
    }
  }

  async buildScene(g) {
    const three = await this.threeReady;
    if (!three) { threeMissing(this.holder, this.info); this.viewer = null; return; }
    const { THREE } = three;
    if (!this.viewer) this.viewer = new Viewer(this.holder, three);
    const v = this.viewer;
    v.scene.clear();
    const lo = g.bounds ? g.bounds.lo : [-1, -1, -1], hi = g.bounds ? g.bounds.hi : [1, 1, 1];
    this.size = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1;
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
    // The lights, and the eye the primary rays start from.
    const marker = (position, colour, radius) => {
      const m = new THREE.Mesh(new THREE.SphereGeometry(radius, 16, 12), new THREE.MeshBasicMaterial({ color: colour }));
      m.position.set(...position);
      return m;
    };
    for (const l of g.lights) {
      if (l.kind === 'point') v.scene.add(marker(l.position, 0xffd400, this.size * 0.012));
      else v.scene.add(new THREE.Mesh(polygonGeometry(THREE, [l.polygon]),
        new THREE.MeshBasicMaterial({ color: 0xffe680, side: THREE.DoubleSide })));
    }
    v.scene.add(marker(g.camera.eye, 0xffffff, this.size * 0.008));
    this.rays = new THREE.Group();
    v.scene.add(this.rays);
    this.cameraView();
  }

  cameraView() {
    if (!this.viewer || !this.geometry) return;
    const c = this.geometry.camera;
    // A little behind the scene's own eye, so that the primary ray is seen leaving it.
    const eye = c.eye.map((e, i) => e + (e - c.target[i]) * 0.25);
    this.viewer.look(eye, c.target, c.up, c.vertical_fov_degrees * 1.15, this.size);
  }

  async clicked(event) {
    if (!this.geometry) return;
    const rect = this.image.getBoundingClientRect();
    const w = this.image.naturalWidth, h = this.image.naturalHeight;
    const x = Math.min(w - 1, Math.max(0, Math.floor((event.clientX - rect.left) / rect.width * w)));
    const y = Math.min(h - 1, Math.max(0, Math.floor((event.clientY - rect.top) / rect.height * h)));
    const marker = document.getElementById('tree-marker');
    marker.style.left = `${(x + 0.5) / w * 100}%`;
    marker.style.top = `${(y + 0.5) / h * 100}%`;
    marker.hidden = false;
    await this.trace(x, y);
  }

  async trace(x, y) {
    const started = performance.now();
    this.section.dataset.state = 'tracing';
    try {
      const tree = await api('/api/trace', { ...this.settings(), x, y });
      this.tree = tree;
      this.nodes = [];
      const walk = (n, parent, level) => { n.parentId = parent; n.level = level; this.nodes.push(n); n.children.forEach(c => walk(c, n.id, level + 1)); };
      if (tree.tree) walk(tree.tree, -1, 0);
      this.shown = null;
      this.drawRays();
      this.drawDiagram();
      this.select(tree.tree ? 0 : -1);
      this.showDepth(null);
      if (this.viewer) this.viewer.drawNow();
      const ms = performance.now() - started;
      const k = tree.rays_by_kind;
      document.getElementById('tree-pixel').textContent =
        `pixel (${x}, ${y}): colour ${displayColour(tree.color)}; ${tree.nodes} nodes from ${tree.rays} rays ` +
        `(primary ${k.primary}, shadow ${k.shadow}, reflection ${k.reflection}, refraction ${k.refraction}); ` +
        `depth limit ${tree.depth_limit}${tree.depth_limit < tree.depth_requested ? ` (the plan cut ${tree.depth_requested})` : ''}`;
      setStatus(this.status, `tree of pixel (${x}, ${y}) drawn ${Math.round(ms)} ms after the click`);
      this.section.dataset.pixel = `${x},${y}`;
      this.section.dataset.clickMs = ms.toFixed(1);
      this.section.dataset.state = 'drawn';
      document.dispatchEvent(new CustomEvent('lab:tree-drawn', { detail: { x, y, ms } }));
    } catch (e) {
      this.section.dataset.state = 'error';
      setStatus(this.status, e.message, true);
    }
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

  drawRays() {
    if (!this.viewer) return;
    const v = this.viewer, THREE = v.THREE, { LineSegments2, LineSegmentsGeometry } = v.three;
    for (const m of v.lineMaterials) m.dispose();
    v.lineMaterials.clear();
    this.rays.clear();
    this.rayObjects = new Map();
    for (const n of this.nodes) {
      const group = new THREE.Group();
      const pieces = this.pieces(n);
      const geometry = new LineSegmentsGeometry();
      geometry.setPositions(pieces.flatMap(p => [...p.a, ...p.b]));
      const colours = pieces.flatMap(p => { const c = new THREE.Color(p.colour); return [c.r, c.g, c.b, c.r, c.g, c.b]; });
      geometry.setColors(colours);
      const material = v.lineMaterial({ linewidth: 3, vertexColors: true, depthTest: false, transparent: true,
        dashed: n.kind === 'shadow', dashSize: this.size * 0.015, gapSize: this.size * 0.008 });
      const line = new LineSegments2(geometry, material);
      if (n.kind === 'shadow') line.computeLineDistances();
      line.renderOrder = 10;
      line.userData.colours = colours;
      group.add(line);
      // Where each piece ends: a surface hit, a surface a shadow ray crosses, or its light.
      for (const p of pieces) {
        if (n.kind !== 'shadow' && !n.hit) continue;
        const dot = new THREE.Mesh(new THREE.SphereGeometry(this.size * (n.kind === 'shadow' ? 0.004 : 0.006), 10, 8),
          new THREE.MeshBasicMaterial({ color: p.colour, depthTest: false }));
        dot.position.set(...p.b);
        dot.renderOrder = 11;
        group.add(dot);
      }
      group.userData.id = n.id;
      this.rays.add(group);
      this.rayObjects.set(n.id, group);
    }
    this.holder.dataset.drawnRays = String(this.nodes.length);
    this.holder.dataset.drawnSegments = String(this.nodes.reduce((s, n) => s + this.pieces(n).length, 0));
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
    return lines;
  }

  drawDiagram() {
    this.diagram.replaceChildren();
    if (!this.nodes.length) return;
    const W = 168, gapX = 14, gapY = 34, lineH = 13;
    // Tidy layout: a leaf takes one slot, a parent is centred over its children.
    const heightOf = n => 8 + lineH * this.nodeLines(n).length;
    const levelHeight = [];
    for (const n of this.nodes) levelHeight[n.level] = Math.max(levelHeight[n.level] || 0, heightOf(n));
    const levelY = [0];
    for (let i = 1; i < levelHeight.length; ++i) levelY[i] = levelY[i - 1] + levelHeight[i - 1] + gapY;
    let slot = 0;
    const stubs = [];
    const place = n => {
      const extra = (n.branches || []).filter(b => STUB_REASON[b.fate]);
      if (!n.children.length && !extra.length) { n.x = slot++ * (W + gapX); return; }
      n.children.forEach(place);
      for (const b of extra) { const s = { parent: n, branch: b, x: slot++ * (W + gapX), level: n.level + 1 }; stubs.push(s); }
      const xs = n.children.map(c => c.x).concat(stubs.filter(s => s.parent === n).map(s => s.x));
      n.x = (Math.min(...xs) + Math.max(...xs)) / 2;
    };
    place(this.nodes[0]);
    const width = slot * (W + gapX), height = levelY[levelY.length - 1] + levelHeight[levelHeight.length - 1] + 40;
    const root = svg('svg', { width, height: height + 10, viewBox: `-4 -4 ${width + 8} ${height + 14}` });
    const byId = new Map(this.nodes.map(n => [n.id, n]));
    for (const n of this.nodes) {
      if (n.parentId < 0) continue;
      const p = byId.get(n.parentId);
      const x1 = p.x + W / 2, y1 = levelY[p.level] + heightOf(p), x2 = n.x + W / 2, y2 = levelY[n.level];
      root.append(svg('path', { d: `M${x1},${y1} C${x1},${y1 + gapY / 2} ${x2},${y2 - gapY / 2} ${x2},${y2}`, fill: 'none', stroke: '#888',
        'stroke-dasharray': n.kind === 'shadow' ? '4 3' : '' }));
      root.append(svg('text', { x: (x1 + x2) / 2 + 3, y: (y1 + y2) / 2, fill: '#666', text: EDGE_LABEL[n.kind] }));
    }
    for (const s of stubs) {
      const p = s.parent, x1 = p.x + W / 2, y1 = levelY[p.level] + heightOf(p), x2 = s.x + W / 2, y2 = levelY[s.level];
      root.append(svg('path', { d: `M${x1},${y1} L${x2},${y2}`, fill: 'none', stroke: '#aaa', 'stroke-dasharray': '1 3' }));
      const g = svg('g', { class: 'stub', 'data-parent': p.id, 'data-kind': s.branch.kind, 'data-fate': s.branch.fate });
      g.append(svg('text', { x: s.x + 4, y: y2 + 12, text: `no ${s.branch.kind} ray:` }));
      g.append(svg('text', { x: s.x + 4, y: y2 + 25, text: STUB_REASON[s.branch.fate] }));
      root.append(g);
    }
    this.diagramNodes = new Map();
    for (const n of this.nodes) {
      const lines = this.nodeLines(n);
      const fill = n.kind === 'shadow' && n.stop.reason === 'blocked' ? KIND_FILL.blocked : KIND_FILL[n.kind];
      const g = svg('g', { class: 'tree-node', 'data-id': n.id, 'data-kind': n.kind, 'data-depth': n.depth,
        'data-stop': n.stop.reason, 'data-primitive': n.hit ? n.hit.primitive : '', 'data-t': n.hit ? n.hit.t : '',
        'data-segments': n.segments ? n.segments.length : 0, transform: `translate(${n.x},${levelY[n.level]})` });
      g.append(svg('rect', { width: W, height: heightOf(n), rx: 6, fill, 'stroke-dasharray': n.kind === 'shadow' ? '4 3' : '' }));
      lines.forEach((line, i) => g.append(svg('text', { x: 6, y: 15 + i * lineH, text: line.length > 27 ? line.slice(0, 26) + '…' : line })));
      g.append(svg('title', { text: lines.join('\n') + (n.stop.text ? `\n${n.stop.text}` : '') }));
      g.addEventListener('click', () => this.select(n.id));
      root.append(g);
      this.diagramNodes.set(n.id, g);
    }
    this.diagram.append(root);
    // The root in view: a wide tree scrolls sideways.
    this.diagram.scrollLeft = Math.max(0, this.nodes[0].x + W / 2 - this.diagram.clientWidth / 2);
  }

  select(id) {
    this.selected = id;
    for (const [nid, g] of this.diagramNodes || []) g.classList.toggle('selected', nid === id);
    if (this.rayObjects)
      for (const [nid, group] of this.rayObjects)
        for (const o of group.children)
          if (o.userData.colours) {
            o.geometry.setColors(nid === id ? o.userData.colours.map((c, i) => [1, 0.2, 0.8][i % 3]) : o.userData.colours);
            o.material.linewidth = nid === id ? 5 : 3;
          }
    if (this.viewer) this.viewer.draw();
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
    this.details.replaceChildren(el('h3', { text: `Node ${n.id}` }),
      el('table', {}, ...rows.map(([k, v]) => el('tr', {}, el('th', { text: k }), el('td', { text: v })))));
  }

  maxDepth() { return this.nodes ? Math.max(0, ...this.nodes.map(n => n.depth)) : 0; }

  showDepth(d) {
    if (!this.nodes) return;
    const max = this.maxDepth();
    this.shown = d === null || d >= max ? null : Math.max(0, d);
    document.getElementById('tree-depth-shown').textContent = this.shown === null ? `all (to depth ${max})` : `depth ≤ ${this.shown}`;
    for (const n of this.nodes) {
      const visible = this.shown === null || n.depth <= this.shown;
      if (this.rayObjects) this.rayObjects.get(n.id).visible = visible;
      if (this.diagramNodes) this.diagramNodes.get(n.id).classList.toggle('hidden-depth', !visible);
    }
    this.section.dataset.shownDepth = this.shown === null ? 'all' : String(this.shown);
    if (this.viewer) this.viewer.draw();
  }
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
