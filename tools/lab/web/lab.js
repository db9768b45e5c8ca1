// The lab's page (docs/lab.md): five views of the build that serves it.
// Everything it loads comes from that build (GET /assets/..., /api/...).
import { api, el } from './lab_util.js';
import { TreeView } from './lab_tree.js';
import { RadiosityView } from './lab_radiosity.js';
import { HemicubeView } from './lab_hemicube.js';
import { CompareView } from './lab_compare.js';
import { HierarchyView } from './lab_hierarchy.js';

async function main() {
  let info;
  try {
    info = await api('/api/info');
  } catch (e) {
    document.getElementById('build').textContent = `The lab did not answer: ${e.message}`;
    return;
  }
  const whose = info.exercises
    ? `your code for lesson${info.exercises.includes(',') ? 's' : ''} ${info.exercises.split(',').join(', ')}, the reference for the rest`
    : 'the reference code';
  document.getElementById('build').textContent =
    `${info.version}${info.student_edition ? ', student edition' : ''}: this build runs ${whose}.`;
  if (!info.three) {
    const notice = document.getElementById('notice');
    notice.hidden = false;
    notice.textContent = 'This build was made without three.js (node_modules/three was missing): the 3D views are off. ' +
      'Run tools/install-deps (it runs npm ci), then build again; the images, diagrams and charts work meanwhile.';
  }
  const views = { tree: new TreeView(info), radiosity: new RadiosityView(info), hemicube: new HemicubeView(info), hierarchy: new HierarchyView(info), compare: new CompareView(info) };
  const started = new Set();
  const open = name => {
    for (const b of document.querySelectorAll('#tabs button')) b.setAttribute('aria-selected', String(b.dataset.tab === name));
    for (const s of document.querySelectorAll('section.tab')) s.hidden = s.id !== `tab-${name}`;
    if (!started.has(name)) {
      started.add(name);
      if (name === 'tree') views.tree.loadScene();
      if (name === 'radiosity') views.radiosity.start();
      if (name === 'hemicube') views.hemicube.show();
      if (name === 'hierarchy') views.hierarchy.solve();
      if (name === 'compare') views.compare.load();
    }
    if (location.hash !== `#${name}`) history.replaceState(null, '', `#${name}`);
  };
  for (const b of document.querySelectorAll('#tabs button')) b.addEventListener('click', () => open(b.dataset.tab));
  window.lab = { info, views, open };  // for the browser tests and the curious
  const first = location.hash.slice(1);
  open(views[first] ? first : 'tree');
  document.body.dataset.ready = 'true';
}

main();
