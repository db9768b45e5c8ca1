#!/usr/bin/env node
// The slide test: opens each built deck in headless Chromium and fails on
//   - a KaTeX error (a .katex-error element, or "ParseError" text on a slide),
//   - an image that does not load (naturalWidth 0 once the page has loaded),
//     including Marp background images,
//   - a resource fetched from the network (decks must work offline) or a local
//     resource (a font, a script) that fails to load,
//   - a script error on the page,
//   - a deck with no slides.
// Content taller than its slide is printed as a warning (it does not fail).
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
import os from 'node:os';
import path from 'node:path';
import { pathToFileURL, fileURLToPath } from 'node:url';

const INSTALL_HINT = 'run tools/install-deps (Debian packages chromium, nodejs, npm; then npm ci)';
const CHROMIUM = process.env.ILLUM_CHROMIUM || '/usr/bin/chromium';
const CHROMIUM_ARGS = [
  '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync',
];

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

// Runs in the page: the problems Marp's rendered slides show on their own.
function inspectPage() {
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
    // Content taller than the slide is cut off when presenting: a warning, not a failure.
    const section = slide.querySelector('section');
    if (section && section.scrollHeight > section.clientHeight + 2)
      problems.push({ slide: where, warning: true,
        reason: `content overflows the slide by ${section.scrollHeight - section.clientHeight}px` });
    for (const img of slide.querySelectorAll('img')) {
      if (!img.complete || img.naturalWidth === 0)
        problems.push({ slide: where, reason: `image failed to load: ${img.getAttribute('src')}` });
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

async function checkDeck(browser, deck, timeoutMs) {
  const problems = [];
  const warnings = [];
  const add = (slide, reason) => problems.push({ deck, slide, reason });
  const page = await browser.newPage();
  try {
    await page.setRequestInterception(true);
    page.on('request', (request) => {
      const url = request.url();
      if (/^(file|data|blob|about):/.test(url)) request.continue();
      else {
        add('-', `fetches ${url} from the network (a deck must work offline)`);
        request.abort();
      }
    });
    page.on('requestfailed', (request) => {
      const url = request.url();
      // Images are reported with their slide below; network requests above.
      if (url.startsWith('file:') && request.resourceType() !== 'image')
        add('-', `${request.resourceType()} failed to load: ${url} (${request.failure()?.errorText})`);
    });
    page.on('pageerror', (error) => add('-', `script error: ${error.message.split('\n')[0]}`));
    await page.goto(pathToFileURL(deck).href, { waitUntil: 'load', timeout: timeoutMs });
    const { count, problems: found, backgrounds } = await page.evaluate(inspectPage);
    if (count === 0) add('-', 'the deck has no slides (is it a Marp deck with `marp: true`?)');
    for (const p of found) {
      if (p.warning) warnings.push({ deck, slide: p.slide, reason: p.reason });
      else add(p.slide, p.reason);
    }
    for (const b of await page.evaluate(loadBackgrounds, backgrounds))
      add(b.slide, `background image failed to load: ${b.src}`);
    return { slides: count, problems, warnings };
  } finally {
    await page.close().catch(() => {});
  }
}

async function main() {
  const options = parseArgs(process.argv.slice(2));
  const decks = findDecks(options.paths);
  if (!fs.existsSync(CHROMIUM)) fatal(`Chromium not found at ${CHROMIUM}: ${INSTALL_HINT}`);
  let puppeteer;
  try {
    puppeteer = (await import('puppeteer-core')).default;
  } catch (e) {
    const here = path.dirname(fileURLToPath(import.meta.url));
    fatal(`puppeteer-core is not installed (node_modules missing next to ${path.resolve(here, '../..')}): ` +
          `${INSTALL_HINT}\n  (${e.message.split('\n')[0]})`);
  }
  const watchdog = setTimeout(() => fatal(`gave up after ${options.timeout * (decks.length + 1)} s ` +
      '(Chromium hung? it must run headless with the network flags)'), options.timeout * 1000 * (decks.length + 1));
  watchdog.unref();

  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'illum-chromium-'));
  let browser;
  const all = [];
  try {
    try {
      browser = await puppeteer.launch({
        executablePath: CHROMIUM, headless: true, args: CHROMIUM_ARGS, userDataDir: profile,
        timeout: options.timeout * 1000,
      });
    } catch (e) {
      fatal(`Chromium (${CHROMIUM}) did not start: ${e.message.split('\n')[0]}\n  ${INSTALL_HINT}`);
    }
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
      for (const w of result.warnings || []) console.log(`  warning: ${name} slide ${w.slide}: ${w.reason}`);
    }
  } finally {
    if (browser) await browser.close().catch(() => {});
    fs.rmSync(profile, { recursive: true, force: true });
  }
  if (all.length) {
    console.log(`\ncheck_decks: ${all.length} problem(s):`);
    for (const p of all) console.log(`  ${path.basename(p.deck)} slide ${p.slide}: ${p.reason}`);
    process.exit(1);
  }
  console.log(`check_decks: ${decks.length} deck(s) fine`);
}

main().catch((e) => fatal(e.stack || String(e)));
