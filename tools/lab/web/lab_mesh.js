// A radiosity mesh (GET /api/radiosity/mesh) as a three.js mesh: each patch a
// fan of triangles over its own corners (one colour per corner), and the
// patch of each triangle for picking. Shared by the radiosity and hemicube views.

export class PatchMesh {
  constructor(THREE, mesh) {
    this.THREE = THREE;
    this.data = mesh;
    const n = mesh.patches;
    this.first = new Int32Array(n + 1);  // first corner of each patch in mesh.vertices
    for (let i = 0; i < n; ++i) this.first[i + 1] = this.first[i] + mesh.vertex_counts[i];
    // Fan triangles (0, k, k + 1) indexing the corners: a corner is drawn once however many
    // triangles share it (a CPU's WebGL pays for every vertex it shades).
    const index = [], patchOfTriangle = [];
    for (let i = 0; i < n; ++i)
      for (let k = 1; k + 1 < mesh.vertex_counts[i]; ++k) {
        index.push(this.first[i], this.first[i] + k, this.first[i] + k + 1);
        patchOfTriangle.push(i);
      }
    this.patchOfTriangle = Int32Array.from(patchOfTriangle);
    this.geometry = new THREE.BufferGeometry();
    this.geometry.setAttribute('position', new THREE.BufferAttribute(Float32Array.from(mesh.vertices), 3));
    this.geometry.setIndex(index);
    this.colours = new Float32Array(mesh.vertices.length);
    this.geometry.setAttribute('color', new THREE.BufferAttribute(this.colours, 3));
    // Both sides: the meshers do not keep every patch's corners in one turning sense (the triangles
    // along the red wall's diagonal), so culling back faces left holes.
    this.object = new THREE.Mesh(this.geometry, new THREE.MeshBasicMaterial({ vertexColors: true, side: THREE.DoubleSide }));
    this.object.frustumCulled = false;  // the whole mesh is in view: no bounding sphere to test every frame
    this.outline = null;
    // The scene's extent, for the cameras.
    let lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (let j = 0; j < mesh.vertices.length; j += 3)
      for (let k = 0; k < 3; ++k) lo[k] = Math.min(lo[k], mesh.vertices[j + k]), hi[k] = Math.max(hi[k], mesh.vertices[j + k]);
    this.lo = lo, this.hi = hi;
    this.size = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1;
    this.centre = lo.map((l, k) => (l + hi[k]) / 2);
  }

  // One linear RGB colour per patch.
  paintPatches(colourOf) {
    for (let i = 0; i + 1 < this.first.length; ++i) {
      const c = colourOf(i);
      for (let j = this.first[i]; j < this.first[i + 1]; ++j)
        this.colours[3 * j] = c[0], this.colours[3 * j + 1] = c[1], this.colours[3 * j + 2] = c[2];
    }
    this.geometry.attributes.color.needsUpdate = true;
  }

  // One linear RGB colour per corner: corner c of the mesh's vertex list, on patch i.
  paintCorners(colourOfCorner) {
    for (let i = 0; i + 1 < this.first.length; ++i)
      for (let j = this.first[i]; j < this.first[i + 1]; ++j) {
        const c = colourOfCorner(j, i);
        this.colours[3 * j] = c[0], this.colours[3 * j + 1] = c[1], this.colours[3 * j + 2] = c[2];
      }
    this.geometry.attributes.color.needsUpdate = true;
  }

  // A magenta outline of patch i (none for i < 0), lifted off its plane.
  outlinePatch(scene, i) {
    const THREE = this.THREE;
    if (!this.outline) {  // one loop, refilled: a material made per shot was a new one per shot
      this.outline = new THREE.LineLoop(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0xff33cc, depthTest: false }));
      this.outline.renderOrder = 10;
      this.outline.frustumCulled = false;
    }
    if (this.outline.parent !== scene) scene.add(this.outline);
    this.outline.visible = i >= 0;
    if (i < 0) return;
    const m = this.data, points = [];
    const lift = this.size * 0.002;
    for (let c = this.first[i]; c < this.first[i + 1]; ++c)
      points.push(new THREE.Vector3(m.vertices[3 * c] + lift * m.normal[3 * i], m.vertices[3 * c + 1] + lift * m.normal[3 * i + 1],
        m.vertices[3 * c + 2] + lift * m.normal[3 * i + 2]));
    this.outline.geometry.dispose();
    this.outline.geometry = new THREE.BufferGeometry().setFromPoints(points);
  }

  // The scene's camera when it has one, else a view of the whole mesh.
  cameraView(viewer) {
    const c = this.data.camera;
    if (c) viewer.look(c.eye, c.target, c.up, c.vertical_fov_degrees, this.size);
    else viewer.look(this.centre.map((x, k) => x + (k === 2 ? -1.6 * this.size : 0)), this.centre, [0, 1, 0], 40, this.size);
  }

  surfaceOf(i) {
    for (const s of this.data.surfaces) if (i >= s.first && i < s.first + s.count) return s.name;
    return '?';
  }
}

// Log-scale heat of a factor in [1e-6, 1]: dark blue to yellow (a viridis-like ramp), linear RGB.
export function heat(value) {
  if (!(value > 0)) return [0.02, 0.02, 0.03];
  const t = Math.min(1, Math.max(0, (Math.log10(value) + 6) / 6));
  const stops = [[0.267, 0.005, 0.329], [0.229, 0.322, 0.546], [0.128, 0.567, 0.551], [0.369, 0.789, 0.383], [0.993, 0.906, 0.144]];
  const x = t * (stops.length - 1), k = Math.min(stops.length - 2, Math.floor(x)), f = x - k;
  const srgb = stops[k].map((a, j) => a + f * (stops[k + 1][j] - a));
  return srgb.map(c => (c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4));
}

// An exposure that maps the 95th percentile of the non-emitting patches'
// brightest channel to 0.85, as lesson 11's pictures do.
export function exposureFor(mesh, radiosity) {
  const values = [];
  for (let i = 0; i < mesh.patches; ++i) {
    if (mesh.emission[3 * i] + mesh.emission[3 * i + 1] + mesh.emission[3 * i + 2] > 0) continue;
    values.push(Math.max(radiosity[3 * i], radiosity[3 * i + 1], radiosity[3 * i + 2]));
  }
  values.sort((a, b) => a - b);
  const p95 = values.length ? values[Math.min(values.length - 1, Math.floor(0.95 * values.length))] : 0;
  return p95 > 0 ? 0.85 / p95 : 1;
}
