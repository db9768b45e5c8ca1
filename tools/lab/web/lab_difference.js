// Yours against the reference (docs/lab.md, "The reference beside yours"):
// a pixel's two ray trees node by node, and a radiosity shot's shooter, row
// and update. Each comparison finds the first difference in the order the
// code computes things, so that it names the first function that went wrong,
// and says why it differs with both values.
import { displayColour, displayNumber, el } from './lab_util.js';

// Equal within 10⁻⁶ relative (10⁻⁹ absolute): a correct implementation that
// adds in another order agrees far closer; a wrong one does not.
export function close(a, b) {
  if (Array.isArray(a) && Array.isArray(b)) return a.length === b.length && a.every((v, i) => close(v, b[i]));
  if (typeof a === 'number' && typeof b === 'number')
    return a === b || Math.abs(a - b) <= 1e-9 + 1e-6 * Math.max(Math.abs(a), Math.abs(b));
  return a === b;
}

// Which lesson's exercise intersects each kind of primitive (the kinds of /api/scene).
const INTERSECTION = { sphere: "lesson 01's sphere", polygon: "lessons 02 and 03's polygon", triangle: "lesson 03's triangle",
  mesh: "lesson 03's triangle", csg: "lesson 04's CSG", bilinear_patch: "lesson 05's patch", implicit: "lesson 05's implicit surface" };
const FATE = { cast: 'cast', zero_factor: 'not cast: its k is 0', depth_limit: 'not cast: the depth limit', pruned: 'pruned (lesson 07)',
  total_internal_reflection: 'total internal reflection', not_cast: 'not cast', plan_off: 'not cast: the plan turns it off' };

const hitText = h => h ? `${h.primitive} at t = ${displayNumber(h.t)} (${h.front_face ? 'front' : 'back'} face)` : 'nothing (the background)';
const fateText = f => FATE[f] || (f || '').replaceAll('_', ' ');

// A node's children keyed by kind (and light, for shadow rays) and their order among such siblings,
// so that the same ray is found in both trees even when one has a child the other lacks.
function keyed(node) {
  const seen = {};
  return (node ? node.children : []).map(c => {
    const k = c.kind === 'shadow' ? `shadow to light ${c.light}` : c.kind;
    seen[k] = (seen[k] || 0) + 1;
    return [seen[k] > 1 ? `${k} #${seen[k]}` : k, c];
  });
}

// The two trees' nodes aligned, each row {path, depth, yours, reference, fields}, and the first
// difference {path, field, yours, reference, why}, checked in evaluate's order: the ray and its hit,
// its shadow rays, I_own, its branches, its reflected and refracted rays, then what it returns.
// `kinds`: primitive index -> kind (from /api/scene), for naming the intersection code.
export function compareTrees(yours, reference, kinds = []) {
  const rows = [];
  let first = null;
  const differ = (row, field, y, r, why) => {
    row.fields.add(field);
    if (!first) first = { path: row.path, row, field, yours: y, reference: r, why };
  };
  const missing = (row, parentYours, parentReference) => {
    const there = row.yours || row.reference, mine = Boolean(row.yours);
    const other = mine ? parentReference : parentYours;
    const branch = other && (other.branches || []).find(b => b.kind === there.kind);
    let why;
    if (there.kind === 'shadow')
      why = `${mine ? 'Yours casts' : 'The reference casts'} a shadow ray to ${there.light_name} here and ${mine ? "the reference's" : 'yours'} does not: ` +
        'own_intensity casts one per light above the tangent plane (N·L > 0), none with the plan\'s shadows off (lesson 06, §5.2).';
    else if (branch && branch.fate === 'total_internal_reflection')
      why = `${mine ? "The reference's" : 'Your'} refract() reported total internal reflection where ${mine ? 'yours' : "the reference's"} refracts: ` +
        'check η_i/η_t (1/η entering through the front face, η leaving) and cos θ_i = −N·I.';
    else
      why = `${mine ? 'Yours casts' : 'The reference casts'} a ${there.kind} ray here and ${mine ? "the reference's" : 'yours'} does not` +
        (branch ? ` (${fateText(branch.fate)}, k = ${displayColour(branch.factor)})` : '') + ': evaluate spawns a child below the depth limit when the plan and its k allow (lesson 06, §5).';
    differ(row, 'exists', mine ? 'cast' : 'not cast', mine ? 'not cast' : 'cast', why);
  };
  const walk = (y, r, path, depth, parents) => {
    const row = { path, depth, yours: y, reference: r, fields: new Set() };
    rows.push(row);
    if (!y || !r) {
      missing(row, ...parents);
      for (const [k, c] of keyed(y || r)) walk(y ? c : null, y ? null : c, `${path}/${k}`, depth + 1, [y, r]);
      return;
    }
    const kind = r.kind;
    if (!close(y.origin, r.origin))
      differ(row, 'origin', displayColour(y.origin), displayColour(r.origin),
        'The ray starts elsewhere: a child starts at its parent\'s hit point, pushed off the surface (spawn_ray).');
    if (!close(y.direction, r.direction))
      differ(row, 'direction', displayColour(y.direction), displayColour(r.direction),
        kind === 'reflection' ? 'reflect(): R = I − 2(N·I)N with the hit\'s shading normal (lesson 06, optics.cpp).'
          : kind === 'refraction' ? 'refract(): T = (η_i/η_t)I + ((η_i/η_t)cos θ_i − cos θ_t)N, with η_i/η_t = 1/η entering (front face) and η leaving (back face) (lesson 06, optics.cpp).'
            : kind === 'shadow' ? 'The direction to the light: light_sample(scene, l, hit point).' : 'The primary ray through the pixel\'s centre.');
    const yh = y.hit, rh = r.hit;
    if (Boolean(yh) !== Boolean(rh) || (yh && (yh.primitive_index !== rh.primitive_index || !close(yh.t, rh.t)))) {
      const k = kinds[(rh || yh).primitive_index];
      differ(row, 'hit', hitText(yh), hitText(rh), `The nearest hit differs: ${k ? INTERSECTION[k] || k : 'the'} intersection, ` +
        'or the scene\'s structure that finds the nearest one (lesson 08\'s BVH).');
    } else if (yh && yh.front_face !== rh.front_face) {
      differ(row, 'hit', hitText(yh), hitText(rh), 'Front or back face: the hit\'s normal must face the ray that arrives (front_face, and the normal flipped for a back face).');
    }
    if (!close(y.weight, r.weight))
      differ(row, 'weight', displayColour(y.weight), displayColour(r.weight), 'The path weight, the product of the k_r and k_t from the eye, differs: the parent\'s factor for this child.');
    const yk = new Map(keyed(y)), rk = keyed(r), keys = rk.map(([k]) => k).concat([...yk.keys()].filter(k => !rk.some(([j]) => j === k)));
    const rmap = new Map(rk);
    const children = shadow => keys.filter(k => k.startsWith('shadow') === shadow)
      .forEach(k => walk(yk.get(k) || null, rmap.get(k) || null, `${path}/${k}`, depth + 1, [y, r]));
    children(true);
    if (kind !== 'shadow' && !close(y.local, r.local))
      differ(row, 'local', displayColour(y.local), displayColour(r.local),
        'I_own = k_a·I_a + emission + Σ_lights S_l·I_l·(k_d N·L + k_s (R·V)^n) differs while its shadow rays agree: own_intensity or phong_term (lesson 06).');
    for (const rb of r.branches || []) {
      const yb = (y.branches || []).find(b => b.kind === rb.kind);
      if (!yb || yb.fate !== rb.fate || !close(yb.factor, rb.factor))
        differ(row, 'branches', yb ? `${rb.kind}: k = ${displayColour(yb.factor)}, ${fateText(yb.fate)}` : `no ${rb.kind} branch`,
          `${rb.kind}: k = ${displayColour(rb.factor)}, ${fateText(rb.fate)}`,
          rb.kind === 'refraction' || (yb && yb.fate === 'total_internal_reflection')
            ? 'The refracted branch: k_t of the material, total internal reflection (which adds k_t to k_r) when refract() finds none, the depth limit and the plan.'
            : 'The reflected branch: k_r of the material (plus k_t under total internal reflection), the depth limit and the plan.');
    }
    children(false);
    if (y.stop.reason !== r.stop.reason)
      differ(row, 'stop', y.stop.reason.replaceAll('_', ' '), r.stop.reason.replaceAll('_', ' '), `Why it stops differs: the reference's ${r.stop.text || r.stop.reason}.`);
    if (kind === 'shadow' && !close(y.transmission, r.transmission))
      differ(row, 'transmission', displayColour(y.transmission), displayColour(r.transmission),
        'The light\'s transmission along the shadow ray, the product of the k_t of the surfaces it crosses (shadow_transmission), differs.');
    if (!close(y.color, r.color))
      differ(row, 'color', displayColour(y.color), displayColour(r.color), kind === 'shadow'
        ? 'What the shadow ray returns differs.' : 'The colour returned, I_own + k_r·I_r + k_t·I_t (eq. 6.9), differs while its parts agree.');
  };
  walk(yours && yours.tree, reference && reference.tree, 'primary', 0, [null, null]);
  return { rows, first };
}

// One line of a row: what the ray is and what it hit, with the fields that differ marked.
function cell(n, fields) {
  if (!n) return el('td', { class: 'absent', text: '—' });
  const mark = f => fields.has(f) ? 'differs' : '';
  return el('td', {},
    el('span', { class: mark('exists') || mark('direction') || mark('origin'), text: n.kind }), ' → ',
    el('span', { class: mark('hit'), text: n.kind === 'shadow' ? (n.stop.reason === 'blocked' ? `blocked by ${n.hit ? n.hit.primitive : 'a surface'}` : `reaches ${n.light_name}`) : n.hit ? `${n.hit.primitive}, t ${displayNumber(n.hit.t)}` : 'missed' }),
    ' · ', el('span', { class: mark('local') || mark('transmission'), text: n.kind === 'shadow' ? `S ${displayColour(n.transmission)}` : `I_own ${displayColour(n.local)}` }),
    ' · ', el('span', { class: mark('color'), text: `returns ${displayColour(n.color)}` }));
}

// The two trees side by side, row for row, and the first difference above them.
export function showTreeComparison(holder, result, { yoursError = null, onSelect = null } = {}) {
  const { rows, first } = result;
  const summary = el('div', { id: 'versus-summary' });
  if (yoursError) {
    summary.append(el('p', { class: 'error', text: `Yours: ${yoursError}. The reference's tree is on the right.` }));
  } else if (!first) {
    summary.append(el('p', { class: 'same', text: `Your tree is the reference's: the same ${rows.length} rays, every number within 10⁻⁶.` }));
  } else {
    summary.append(el('p', {}, el('strong', { text: 'First difference: ' }), `${first.path.replaceAll('/', ' → ')}, ${first.field === 'exists' ? 'the ray itself' : first.field}: `,
      el('span', { class: 'yours-value', text: `yours ${first.yours}` }), ', ', el('span', { class: 'reference-value', text: `the reference's ${first.reference}` }), '.'),
    el('p', { class: 'why', text: first.why }));
  }
  const body = rows.map(row => {
    const tr = el('tr', { 'data-path': row.path, class: row === (first && first.row) ? 'first-difference' : row.fields.size ? 'differs' : '' },
      el('th', { style: `padding-left: ${0.3 + 1.1 * row.depth}em`, text: row.path.split('/').pop() }),
      cell(row.yours, row.fields), cell(row.reference, row.fields));
    if (onSelect && row.yours) tr.addEventListener('click', () => onSelect(row.yours.id));
    return tr;
  });
  holder.replaceChildren(summary, el('table', { class: 'versus' },
    el('thead', {}, el('tr', {}, el('th', { text: 'ray' }), el('th', { text: 'yours' }), el('th', { text: "the reference's" }))),
    el('tbody', {}, ...body)));
  holder.dataset.first = first ? `${first.path}|${first.field}` : '';
  holder.dataset.rows = String(rows.length);
}

// A radiosity shot, yours against the reference's from the same state: which patch shoots
// (choose_shooter, Task 6b), the row its hemicube drew (lesson 10), what the shot added to every
// radiosity (shoot, Task 6c). Arrays are float32 (the page's copies): compared within 10⁻⁵.
export function compareShot(yours, reference, surfaceOf) {
  const largest = (a, b) => {
    let worst = -1, at = -1, scale = 0;
    for (let i = 0; i < a.length; ++i) scale = Math.max(scale, Math.abs(b[i]));
    for (let i = 0; i < a.length; ++i) {
      const d = Math.abs(a[i] - b[i]);
      if (d > worst) worst = d, at = i;
    }
    return { differs: worst > 1e-5 * scale + 1e-12, at, worst };
  };
  const patch = i => `patch ${i} (${surfaceOf(i)})`;
  if (yours.shooter !== reference.shooter)
    return { field: 'shooter', yours: patch(yours.shooter), reference: patch(reference.shooter),
      why: 'choose_shooter (Task 6b) picks the patch with the most unshot power, A_i·(ΔB_i,r + ΔB_i,g + ΔB_i,b): the area counts, not the radiosity alone.' };
  if (yours.row && reference.row) {
    const d = largest(yours.row, reference.row);
    if (d.differs)
      return { field: 'row', yours: `F = ${displayNumber(yours.row[d.at])} to ${patch(d.at)}`, reference: `F = ${displayNumber(reference.row[d.at])}`,
        why: 'The same shooter\'s form-factor row differs: its hemicube (lesson 10: the delta form factors of the top and side faces, eq. 10.2–10.5).' };
  }
  if (yours.update && reference.update) {
    const d = largest(yours.update, reference.update), at = Math.floor(d.at / 3);
    if (d.differs)
      return { field: 'update', yours: `${patch(at)} gains ${displayColour([0, 1, 2].map(k => yours.update[3 * at + k]))}`,
        reference: displayColour([0, 1, 2].map(k => reference.update[3 * at + k])),
        why: 'shoot (Task 6c) with the same shooter and row: ΔB_j = ρ_j·F_ij·(A_i/A_j)·ΔB_i (reciprocity, erratum 8), added to B_j and to the unshot ΔB_j; the shooter\'s unshot set to 0.' };
  }
  if (!close(yours.fraction, reference.fraction))
    return { field: 'unshot', yours: displayNumber(yours.fraction), reference: displayNumber(reference.fraction),
      why: 'The unshot power left differs while the shooter, row and update agree: the unshot bookkeeping of shoot (Task 6c).' };
  return null;
}
