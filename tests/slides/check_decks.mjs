#!/usr/bin/env node
// The slide test: opens each built deck in headless Chromium and fails on
//   - a KaTeX error (a .katex-error element, or "ParseError" text on a slide),
//   - an image that does not load (naturalWidth 0 once the page has loaded),
//     including Marp background images,
//   - a resource fetched from the network (decks must work offline) or a local
//     resource (a font, a script) that fails to load,
//   - a script error on the page,
//   - a deck with no slides,
//   - an image without a size (Marp's w:/h:) outside a column: its file's size
//     differs between the quick run the test sees and the full run,
//   - content that does not fit its slide: taller or wider than the slide's
//     content box (the slide less its padding, where the footer and the page
//     number sit), or a code block or table wider than its own box. The page
//     is opened at the deck's size (the slides' viewBox, 1280x720 for 16:9)
//     and the message names the overflow in px and the element that sticks out.
//     The page is measured once its layout has settled (Marp's script fits
//     wide code a frame or more after 'load'; see settledInspection).
//
//   node tests/slides/check_decks.mjs [--timeout SECONDS] PATH...
//
// PATH is a built deck (.html) or a folder of them (out/slides). Exit codes:
// 0 every deck is fine; 1 problems found (one line each: deck, slide, reason);
// 2 the checker could not run (no Chromium, no puppeteer-core, no decks).
//
// Chromium is Debian's /usr/bin/chromium (override with ILLUM_CHROMIUM), run
// with flags that keep it from reaching for the network, and a fresh profile.
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import { keepOffline, startChromium } from '../../tools/browser/chromium.mjs';

function fatal(message) {
  console.error(`check_decks: cannot run: ${message}`);
  process.exit(2);
}

function parseArgs(argv) {
  const options = { timeout: 60, paths: [] };
  for (let i = 0; i < argv.length; ++i) {
    const a = argv[i];
    if (a === '--timeout') options.timeout = Number(argv[++i]);
    else if (a === '-h' || a === '--help') {
      console.log('usage: node tests/slides/check_decks.mjs [--timeout SECONDS] DECK.html|FOLDER...');
      process.exit(0);
    } else if (a.startsWith('-')) fatal(`unknown option ${a}`);
    else options.paths.push(a);
  }
  if (!options.paths.length) fatal('no decks given (pass built .html decks or a folder of them)');
  if (!(options.timeout > 0)) fatal('--timeout needs a positive number of seconds');
  return options;
}

function findDecks(paths) {
  const decks = [];
  for (const p of paths) {
    if (!fs.existsSync(p)) fatal(`${p} does not exist (were the decks built? tools/main_job.py --only slides)`);
    if (fs.statSync(p).isDirectory()) {
      for (const f of fs.readdirSync(p).sort())
        if (/^\d\d_.*\.html$/.test(f)) decks.push(path.resolve(p, f));
    } else decks.push(path.resolve(p));
  }
  if (!decks.length) fatal(`no decks (NN_*.html) in ${paths.join(', ')}`);
  return decks;
}

const DEFAULT_SIZE = { width: 1280, height: 720 };  // Marp's 16:9

// Runs in the page: the size of the deck's slides, from the first slide's viewBox.
function slideSize() {
  const svg = document.querySelector('svg[data-marpit-svg]');
  const box = svg && svg.viewBox && svg.viewBox.baseVal;
  return box && box.width > 0 ? { width: Math.round(box.width), height: Math.round(box.height) } : null;
}

// Runs in the page: the problems Marp's rendered slides show on their own.
function inspectPage() {
  const TOLERANCE = 2;  // px: sub-pixel rounding of line boxes and fonts
  // A short name for the element that sticks out furthest, so the author knows what to shrink.
  const describe = (el) => {
    const img = el.tagName === 'IMG' ? el : el.querySelector('img');
    if (img) return `image ${img.getAttribute('src')}`;
    const text = (el.textContent || '').replace(/\s+/g, ' ').trim();
    return `<${el.tagName.toLowerCase()}> ${JSON.stringify(text.slice(0, 40))}`;
  };
  // The slide's layout is measured in its own CSS px: the SVG may scale the
  // rendered slide, so rectangles are divided by that scale.
  const overflowOf = (section) => {
    const reasons = [];
    const style = getComputedStyle(section);
    const box = section.getBoundingClientRect();
    const scale = box.height / section.offsetHeight || 1;
    const bottomLimit = section.clientHeight - parseFloat(style.paddingBottom);
    const rightLimit = section.clientWidth - parseFloat(style.paddingRight);
    let lowest = null, widest = null;
    for (const el of section.querySelectorAll('*')) {
      const pos = getComputedStyle(el).position;
      // Marp's header and footer sit in the padding on purpose.
      if (pos === 'absolute' || pos === 'fixed' || el.closest('header, footer')) continue;
      // KaTeX: measure the rendered pieces of a formula (.base), not its hidden
      // MathML copy nor the wide SVG strokes it clips (a root sign is 400em wide).
      if (el.closest('.katex') && !(el.classList.contains('base') && el.parentElement.classList.contains('katex-html')))
        continue;
      if (el instanceof SVGElement) continue;
      const r = el.getBoundingClientRect();
      if (r.width === 0 && r.height === 0) continue;
      const bottom = (r.bottom - box.top) / scale;
      const right = (r.right - box.left) / scale;
      if (!lowest || bottom > lowest.at) lowest = { el, at: bottom };
      if (!widest || right > widest.at) widest = { el, at: right };
    }
    const tall = Math.max(section.scrollHeight - section.clientHeight, lowest ? lowest.at - bottomLimit : 0);
    if (tall > TOLERANCE)
      reasons.push(`content overflows the slide by ${Math.round(tall)}px at the bottom ` +
                   `(lowest: ${lowest ? describe(lowest.el) : 'the section'})`);
    const wide = Math.max(section.scrollWidth - section.clientWidth, widest ? widest.at - rightLimit : 0);
    if (wide > TOLERANCE)
      reasons.push(`content overflows the slide by ${Math.round(wide)}px on the right ` +
                   `(widest: ${widest ? describe(widest.el) : 'the section'})`);
    // A box that cuts off its own content (a code block's scroll box, a wide table).
    for (const el of section.querySelectorAll('pre, table')) {
      const cut = el.scrollWidth - el.clientWidth;
      if (cut > TOLERANCE) reasons.push(`${describe(el)} is ${cut}px wider than its box (it scrolls or is cut)`);
    }
    return reasons;
  };
  const problems = [];
  const slides = Array.from(document.querySelectorAll('svg[data-marpit-svg]'));
  const backgrounds = [];
  slides.forEach((slide, i) => {
    const where = i + 1;
    for (const err of slide.querySelectorAll('.katex-error')) {
      const why = (err.getAttribute('title') || 'KaTeX error').replace(/\s+/g, ' ');
      problems.push({ slide: where, reason: `${why} in ${JSON.stringify(err.textContent.trim().slice(0, 80))}` });
    }
    // An undefined command (\ovrline) is not a ParseError for KaTeX when
    // throwOnError is off: it is drawn as red text. Catch that too.
    for (const el of slide.querySelectorAll('.katex-html .mord.text')) {
      const name = (el.textContent || '').trim();
      if (/^\\[A-Za-z@]+$/.test(name) && /#cc0000|rgb\(204, ?0, ?0\)/i.test(el.getAttribute('style') || ''))
        problems.push({ slide: where, reason: `KaTeX: undefined command ${name}` });
    }
    const text = slide.textContent || '';
    if (!slide.querySelector('.katex-error') && /ParseError/.test(text)) {
      const at = text.indexOf('ParseError');
      problems.push({ slide: where, reason: `KaTeX text: ${JSON.stringify(text.slice(at, at + 120))}` });
    }
    // Content that does not fit is cut off (or covers the footer) when presenting.
    const section = slide.querySelector('section');
    if (section) for (const reason of overflowOf(section)) problems.push({ slide: where, reason });
    for (const img of slide.querySelectorAll('img')) {
      if (!img.complete || img.naturalWidth === 0)
        problems.push({ slide: where, reason: `image failed to load: ${img.getAttribute('src')}` });
      // The test sees the quick run's images, the audience the full run's: an
      // image sized by its file would fit one and not the other.
      else if (!img.style.width && !img.style.height && !img.closest('.cols, .cols3'))
        problems.push({ slide: where, reason: `image ${img.getAttribute('src')} has no size: write ` +
                        '![h:N](…) or ![w:N](…), or put it in a <div class="cols"> column' });
    }
    for (const el of slide.querySelectorAll('[style*="background-image"]')) {
      const m = /url\((["']?)(.*?)\1\)/.exec(el.style.backgroundImage || '');
      if (m && m[2]) backgrounds.push({ slide: where, src: m[2] });
    }
  });
  return { count: slides.length, problems, backgrounds };
}

// Runs in the page: loads each background image and reports the ones that fail.
async function loadBackgrounds(backgrounds) {
  const results = await Promise.all(backgrounds.map((b) => new Promise((resolve) => {
    const img = new Image();
    img.onload = () => resolve(img.naturalWidth > 0 ? null : b);
    img.onerror = () => resolve(b);
    img.src = b.src;
  })));
  return results.filter(Boolean);
}

// Runs in the page: resolves after `frames` animation frames have been drawn.
function afterFrames(frames) {
  return new Promise((resolve) => {
    const step = (left) => (left === 0 ? resolve(true) : requestAnimationFrame(() => step(left - 1)));
    step(frames);
    setTimeout(() => resolve(false), 2000);  // a page that draws no frames is measured as it is
  });
}

// Marp's own script fits wide code blocks and headings to their slide: its
// <marp-auto-scaling> elements resize an SVG from a ResizeObserver, which runs
// only when a frame is drawn, one frame or more after 'load'. Measured before
// that, a code line a slide shows whole sticks out by hundreds of px (CI saw
// it on the first deck a cold Chromium opened). So the page is measured after
// a few frames, and again until two measurements agree.
const SETTLE_FRAMES = 3;
const SETTLE_TRIES = 20;

async function settledInspection(page) {
  let last = null;
  for (let attempt = 0; attempt < SETTLE_TRIES; ++attempt) {
    await page.evaluate(afterFrames, SETTLE_FRAMES);
    const now = await page.evaluate(inspectPage);
    if (last && JSON.stringify(now) === JSON.stringify(last)) return now;
    last = now;
  }
  return last;  // still moving after SETTLE_TRIES rounds: report the last layout seen
}

async function checkDeck(browser, deck, timeoutMs) {
  const problems = [];
  const add = (slide, reason) => problems.push({ deck, slide, reason });
  const page = await browser.newPage();
  try {
    // Images are reported with their slide below.
    await keepOffline(page, (reason) => add('-', reason), 'a deck');
    await page.setViewport(DEFAULT_SIZE);
    await page.goto(pathToFileURL(deck).href, { waitUntil: 'load', timeout: timeoutMs });
    // Open the deck at its own size (the slides' viewBox), so one slide fills the window unscaled.
    const size = await page.evaluate(slideSize);
    if (size && (size.width !== DEFAULT_SIZE.width || size.height !== DEFAULT_SIZE.height))
      await page.setViewport(size);
    await page.evaluate(() => document.fonts.ready.then(() => true));
    const { count, problems: found, backgrounds } = await settledInspection(page);
    if (count === 0) add('-', 'the deck has no slides (is it a Marp deck with `marp: true`?)');
    for (const p of found) add(p.slide, p.reason);
    for (const b of await page.evaluate(loadBackgrounds, backgrounds))
      add(b.slide, `background image failed to load: ${b.src}`);
    return { slides: count, problems };
  } finally {
    await page.close().catch(() => {});
  }
}

async function main() {
  const options = parseArgs(process.argv.slice(2));
  const decks = findDecks(options.paths);
  const watchdog = setTimeout(() => fatal(`gave up after ${options.timeout * (decks.length + 1)} s ` +
      '(Chromium hung? it must run headless with the network flags)'), options.timeout * 1000 * (decks.length + 1));
  watchdog.unref();

  const { browser, close } = await startChromium(fatal, { timeout: options.timeout });
  const all = [];
  try {
    for (const deck of decks) {
      let result;
      try {
        result = await checkDeck(browser, deck, options.timeout * 1000);
      } catch (e) {
        result = { slides: 0, problems: [{ deck, slide: '-', reason: `could not open: ${e.message.split('\n')[0]}` }] };
      }
      const name = path.basename(deck);
      if (result.problems.length) console.log(`FAIL ${name}: ${result.slides} slides, ${result.problems.length} problem(s)`);
      else console.log(`ok   ${name}: ${result.slides} slides`);
      all.push(...result.problems);
    }
  } finally {
    await close();
  }
  if (all.length) {
    console.log(`\ncheck_decks: ${all.length} problem(s):`);
    for (const p of all) console.log(`  ${path.basename(p.deck)} slide ${p.slide}: ${p.reason}`);
    process.exit(1);
  }
  console.log(`check_decks: ${decks.length} deck(s) fine`);
}

main().catch((e) => fatal(e.stack || String(e)));
