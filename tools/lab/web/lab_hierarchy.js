// View 4: lesson 14's hierarchy (GET /api/hierarchy): the leaf elements
// coloured by their radiosity and outlined; a click on one draws the links it
// gathers on, its own and its ancestors' (push-pull hands those down to it),
// as lines to the elements at their other ends.
import { api, displayNumber, el, loadThree, plural, setStatus, threeMissing, Viewer } from './lab_util.js';
import { exposureFor, PatchMesh } from './lab_mesh.js';

const OWN = 0xffd21f, ANCESTOR = 0x3d8bff, SELECTED = 0xff33cc, EDGES = 0x000000;

export class HierarchyView {
  constructor(info) {
    this.info = info;
    this.section = document.getElementById('tab-hierarchy');
    this.status = document.getElementById('hr-status');
    this.holder = document.getElementById('hr-3d');
    this.details = document.getElementById('hr-details');
    this.sceneSelect = document.getElementById('hr-scene');
    // Lesson 14's two scenes, where the build has them (a scene of spheres has no polygons to split).
    for (const s of info.scenes.filter(s => s === 'room' || s === 'cornell')) this.sceneSelect.append(el('option', { value: s, text: s }));
    this.sceneSelect.value = info.scenes.includes('room') ? 'room' : this.sceneSelect.value;
    for (const id of ['hr-scene', 'hr-epsilon-f', 'hr-epsilon-bf', 'hr-min-edge'])
      document.getElementById(id).addEventListener('change', () => this.solve());
    document.getElementById('hr-solve').addEventListener('click', () => this.solve());
    this.threeReady = info.three ? loadThree().catch(() => null) : Promise.resolve(null);
    this.busy = Promise.resolve();
  }

  params() {
    const value = id => document.getElementById(id).value;
    return { scene: this.sceneSelect.value, epsilon_f: value('hr-epsilon-f'), epsilon_bf: value('hr-epsilon-bf'), min_edge: value('hr-min-edge') };
  }

  solve() { return this.queue(() => this.solveNow()); }
  select(element) { return this.queue(() => this.selectNow(element)); }
  queue(task) { this.busy = this.busy.then(task, task); return this.busy; }

  async solveNow() {
    this.section.dataset.state = 'solving';
    setStatus(this.status, 'solving the hierarchy…');
    try {
      const h = await api('/api/hierarchy', this.params(), 'json', { view: 'hierarchy' });
      this.h = h;
      this.selected = null;
      await this.drawLeaves();
      this.section.dataset.elements = String(h.elements);
      this.section.dataset.links = String(h.links);
      setStatus(this.status, `${h.name}: ${h.roots} input patches → ${plural(h.elements, 'element')}, ${h.patches} ${h.patches === 1 ? 'leaf' : 'leaves'}, ` +
        `${plural(h.links, 'link')} (n² of the leaves: ${h.patches * h.patches}); ${h.refinement_passes} BF ${h.refinement_passes === 1 ? 'pass' : 'passes'}, ` +
        `${plural(h.sweeps, 'sweep')}, ${displayNumber(h.seconds)} s. Click an element for its links.`);
      this.details.replaceChildren(el('p', { class: 'muted', text: 'No element selected.' }));
      this.section.dataset.state = 'drawn';
    } catch (e) {
      this.section.dataset.state = 'error';
      setStatus(this.status, e.message, true);
    }
  }

  async drawLeaves() {
    const h = this.h, three = await this.threeReady;
    if (!three) { threeMissing(this.holder, this.info); this.viewer = null; this.patchMesh = null; return; }
    const { THREE } = three;
    if (!this.viewer) {
      this.viewer = new Viewer(this.holder, three, { antialias: false });
      this.viewer.renderer.domElement.addEventListener('click', e => {
        if (!this.patchMesh) return;
        const hit = this.viewer.pick(e, [this.patchMesh.object]);
        if (hit) this.select(this.h.element[this.patchMesh.patchOfTriangle[hit.faceIndex]]);
      });
    }
    this.viewer.scene.clear();
    this.patchMesh = new PatchMesh(THREE, h);
    const exposure = exposureFor(h, h.radiosity);
    this.patchMesh.paintPatches(i => [0, 1, 2].map(k => Math.min(1, exposure * h.radiosity[3 * i + k])));
    this.viewer.scene.add(this.patchMesh.object);
    // Every leaf's outline, lifted off its plane so the depth test keeps it in front of its own face.
    const lift = this.patchMesh.size * 0.001, edges = [];
    for (let i = 0; i < h.patches; ++i) {
      const first = this.patchMesh.first[i], n = h.vertex_counts[i];
      for (let c = 0; c < n; ++c)
        for (const j of [first + c, first + (c + 1) % n])
          for (let k = 0; k < 3; ++k) edges.push(h.vertices[3 * j + k] + lift * h.normal[3 * i + k]);
    }
    const outline = new THREE.BufferGeometry();
    outline.setAttribute('position', new THREE.Float32BufferAttribute(edges, 3));
    this.viewer.scene.add(new THREE.LineSegments(outline, new THREE.LineBasicMaterial({ color: EDGES, transparent: true, opacity: 0.35 })));
    this.links = new THREE.Group();
    this.viewer.scene.add(this.links);
    if (this.cameraScene !== h.scene) this.patchMesh.cameraView(this.viewer), this.cameraScene = h.scene;  // a new ε keeps the view
    this.viewer.draw();
  }

  async selectNow(element) {
    this.section.dataset.state = 'selecting';
    try {
      const h = await api('/api/hierarchy', { ...this.params(), element }, 'json', { view: 'hierarchy' });
      const s = h.selected;
      this.selected = s;
      this.drawLinks(s);
      this.describe(s);
      this.section.dataset.element = String(s.element);
      this.section.dataset.selectedLinks = String(s.links_total);
      this.section.dataset.state = 'drawn';
    } catch (e) {
      this.section.dataset.state = 'error';
      setStatus(this.status, e.message, true);
    }
  }

  // Lines from the clicked element's centroid to each link's other element, and that element's outline:
  // yellow the element's own links, blue its ancestors'; the element itself outlined in magenta.
  drawLinks(s) {
    if (!this.viewer) return;
    const { THREE } = this.viewer;
    for (const child of this.links.children) child.geometry.dispose();
    this.links.clear();
    const lines = { own: [], ancestor: [] };
    const loop = (target, v) => {
      for (let c = 0; c < v.length / 3; ++c)
        for (const j of [c, (c + 1) % (v.length / 3)]) target.push(v[3 * j], v[3 * j + 1], v[3 * j + 2]);
    };
    for (const l of s.links) {
      const target = l.receiver === s.element ? lines.own : lines.ancestor;
      target.push(...s.centroid, ...l.centroid);
      loop(target, l.vertices);
    }
    const own = [];
    loop(own, s.chain[0].vertices);
    for (const [points, colour] of [[lines.ancestor, ANCESTOR], [lines.own, OWN], [own, SELECTED]]) {
      if (!points.length) continue;
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.Float32BufferAttribute(points, 3));
      const segments = new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color: colour, depthTest: false, transparent: true }));
      segments.renderOrder = 10;
      this.links.add(segments);
    }
    this.viewer.draw();
  }

  describe(s) {
    const own = s.links.filter(l => l.receiver === s.element).length;
    const chain = s.chain.map(c => `${c.element} (level ${c.level}, area ${displayNumber(c.area)})`).join(' ← ');
    const rows = s.links.slice(0, 40).map(l => el('tr', { class: l.receiver === s.element ? 'own' : 'ancestor' },
      el('td', { text: l.receiver }), el('td', { text: l.level }), el('td', { text: `${l.source} (${l.source_surface}, level ${l.source_level})` }),
      el('td', { text: displayNumber(l.form_factor) }), el('td', { text: displayNumber(l.estimate) }),
      el('td', { text: displayNumber(Math.max(...l.brings)) })));
    this.details.replaceChildren(
      el('p', {}, el('strong', { text: `Element ${s.element}` }), ` on the ${s.surface}${s.leaf ? ', a leaf' : ''}; up to its root: ${chain}.`),
      el('p', { id: 'hr-link-count', text: `It gathers on ${plural(own, 'link')} of its own and ${plural(s.links_total - own, 'link')} of its ancestors` +
        (s.links_shown < s.links_total ? ` (the first ${s.links_shown} drawn).` : '.') }),
      el('table', { class: 'numbers' },
        el('tr', {}, ...['receiver', 'level', 'source', 'link F (sampled)', 'oracle estimate', 'brings (max channel)'].map(t => el('th', { text: t }))),
        ...rows),
      s.links.length > 40 ? el('p', { class: 'muted', text: `the first 40 of ${s.links_shown} listed` }) : '');
  }
}
