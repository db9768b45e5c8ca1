// View 4: your picture against the reference (GET /api/compare, /api/compare/stats,
// /api/compare/image): the lesson text's kept figure, the same file as your
// build's lesson program drew it, a difference map and one number.
import { api, displayNumber, el, setStatus } from './lab_util.js';

export class CompareView {
  constructor(info) {
    this.info = info;
    this.section = document.getElementById('tab-compare');
    this.lessonSelect = document.getElementById('cmp-lesson');
    this.imageSelect = document.getElementById('cmp-image');
    this.verdict = document.getElementById('cmp-verdict');
    this.lessonSelect.addEventListener('change', () => this.fillImages());
    this.imageSelect.addEventListener('change', () => this.show());
    this.loaded = false;
  }

  async load() {
    if (this.loaded) return;
    this.loaded = true;
    try {
      this.list = await api('/api/compare');
      const have = this.list.lessons.map(l => l.images.filter(i => i.yours).length).reduce((a, b) => a + b, 0);
      document.getElementById('cmp-intro').textContent =
        `The reference images are the lesson texts' kept figures in ${this.list.source}/lessons/NN_topic/figures; ` +
        `yours are the same files in ${this.list.out}/lessonNN, drawn by your build's lesson programs ` +
        `(you have ${have} of them). One number per pair: the share of pixels that differ by more than 4 levels of 255 ` +
        `in some channel; at most 0.1% is a match (the rule tools/figures.py keeps the texts' figures by).`;
      for (const l of this.list.lessons)
        this.lessonSelect.append(el('option', { value: l.lesson, text: `${l.topic} (${l.images.filter(i => i.yours).length}/${l.images.length})` }));
      const first = this.list.lessons.find(l => l.images.some(i => i.yours)) || this.list.lessons[0];
      if (first) this.lessonSelect.value = first.lesson;
      this.fillImages();
    } catch (e) {
      setStatus(this.verdict, e.message, true);
    }
  }

  fillImages() {
    const lesson = this.list.lessons.find(l => l.lesson === this.lessonSelect.value);
    this.imageSelect.replaceChildren(...lesson.images.map(i => el('option', { value: i.name,
      text: `${i.name}${i.plot ? ' (plot)' : ''}${i.lab_screenshot ? ' (a screenshot of the lab)' : ''}${i.yours ? '' : ' — not drawn yet'}` })));
    const image = lesson.images.find(i => i.yours && !i.plot && !i.lab_screenshot) || lesson.images[0];
    this.imageSelect.value = image.name;
    this.show();
  }

  async show() {
    const lesson = this.list.lessons.find(l => l.lesson === this.lessonSelect.value);
    const name = this.imageSelect.value;
    const params = { lesson: lesson.lesson, name };
    const url = which => `/api/compare/image?${new URLSearchParams({ ...params, which })}`;
    this.section.dataset.state = 'loading';
    delete this.section.dataset.sizes;
    document.getElementById('cmp-reference').src = url('reference');
    const yours = document.getElementById('cmp-yours'), difference = document.getElementById('cmp-difference');
    try {
      const s = await api('/api/compare/stats', params);
      if (!s.have_yours) {
        yours.removeAttribute('src'), difference.removeAttribute('src');
        this.verdict.replaceChildren(`You have no ${s.yours} yet: run `, el('code', { text: lesson.command.replace(/^lesson/, 'build/student/bin/lesson') }),
          ' (or your build\'s bin/ folder), then choose the image again.');
        this.section.dataset.state = 'missing';
        return;
      }
      yours.src = url('yours');
      if (!s.same_size) {
        difference.removeAttribute('src');
        const [rw, rh] = s.reference_size, [yw, yh] = s.yours_size;
        const sizes = `The sizes differ: the reference is ${rw} × ${rh}, yours ${yw} × ${yh}`;
        // Why, from what the program wrote: a diagram's size follows its content; a smaller picture of
        // the same shape is what --quick draws; anything else has another shape.
        this.verdict.textContent = s.diagram
          ? `${sizes}. This is a drawing of a diagram (the program wrote ${name.replace(/\.png$/, '.dot')} beside it), and its size follows what it ` +
            'shows: yours holds other nodes or other labels than the reference\'s. Compare the two pictures below, or click the same pixel in the ray-tree view.'
          : yw < rw && Math.abs(yw / yh - rw / rh) < 0.02 * (rw / rh)
            ? `${sizes}, the same shape, smaller: a --quick run draws smaller images; run the program without --quick to compare.`
            : `${sizes}, another shape: compare the two pictures below.`;
        this.section.dataset.state = 'compared';
        this.section.dataset.matches = 'false';
        this.section.dataset.sizes = s.diagram ? 'diagram' : yw < rw && Math.abs(yw / yh - rw / rh) < 0.02 * (rw / rh) ? 'quick' : 'shape';
        return;
      }
      difference.src = url('difference');
      await Promise.all([yours.decode(), difference.decode(), document.getElementById('cmp-reference').decode()]).catch(() => {});
      const percent = 100 * s.differing_share;
      this.verdict.replaceChildren(el('strong', { id: 'cmp-number', 'data-share': String(s.differing_share), text: `${displayNumber(percent)}%` }),
        ` of the pixels differ by more than 4 levels (${s.differing_pixels} of ${s.pixels}; largest difference ${s.largest_difference} levels, ` +
        `RMS ${displayNumber(s.rms_levels)}): ${s.matches ? 'your image matches the reference.' : 'your image does not match the reference.'}`);
      this.section.dataset.state = 'compared';
      this.section.dataset.matches = String(s.matches);
    } catch (e) {
      this.section.dataset.state = 'error';
      setStatus(this.verdict, e.message, true);
    }
  }
}
