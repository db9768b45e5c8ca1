#!/usr/bin/env node
// The page test: opens rendered texts (OUT/pages/…/*.html, tools/gallery/render_texts.mjs)
// in headless Chromium and fails on
//   - a formula KaTeX could not render (a .katex-error element), or fewer
//     rendered formulas than --min-maths;
//   - KaTeX's fonts not loaded (the maths would show in a fallback font);
//   - an image that does not load (naturalWidth 0), or fewer than --min-images;
//   - a local link whose file does not exist, or an anchor (#id) the page
//     it names does not have;
//   - a resource fetched from the network (pages work offline) or a local
//     one (a style sheet, a font) that fails to load; a script error.
//
//   node tests/texts/check_pages.mjs [--min-maths N] [--min-images N] [--screenshot FILE.png] PAGE.html...
//
// Exit codes: 0 every page is fine; 1 problems (one line each); 2 the checker
// could not run (no Chromium, no puppeteer-core, no such page).
// Chromium is Debian's /usr/bin/chromium (override with ILLUM_CHROMIUM).
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL, fileURLToPath } from 'node:url';
import { keepOffline, startChromium } from '../../tools/browser/chromium.mjs';

function fatal(message) {
  console.error(`check_pages: cannot run: ${message}`);
  process.exit(2);
}

function parseArgs(argv) {
  const options = { minMaths: 0, minImages: 0, screenshot: null, pages: [], timeout: 60 };
  for (let i = 0; i < argv.length; ++i) {
    const a = argv[i];
    if (a === '--min-maths') options.minMaths = Number(argv[++i]);
    else if (a === '--min-images') options.minImages = Number(argv[++i]);
    else if (a === '--screenshot') options.screenshot = argv[++i];
    else if (a === '--timeout') options.timeout = Number(argv[++i]);
    else if (a === '-h' || a === '--help') {
      console.log('usage: node tests/texts/check_pages.mjs [--min-maths N] [--min-images N] [--screenshot FILE] PAGE...');
      process.exit(0);
    } else if (a.startsWith('-')) fatal(`unknown option ${a}`);
    else options.pages.push(path.resolve(a));
  }
  if (!options.pages.length) fatal('no pages given');
  for (const p of options.pages) if (!fs.existsSync(p)) fatal(`${p} does not exist (run the main job's texts step)`);
  return options;
}

// Runs in the page: what it shows.
function inspect() {
  const imgs = [...document.querySelectorAll('img')];
  return {
    maths: document.querySelectorAll('.katex').length,
    errors: [...document.querySelectorAll('.katex-error')].map((e) => e.getAttribute('title') || e.textContent),
    images: imgs.map((img) => ({ src: img.getAttribute('src'), ok: img.complete && img.naturalWidth > 0 })),
    links: [...document.querySelectorAll('a[href]')].map((a) => a.href),
    ids: [...document.querySelectorAll('[id]')].map((e) => e.id),
    // A face of KaTeX's own fonts loaded (document.fonts.check is true when no face is declared).
    katexFont: [...document.fonts].some((f) => /KaTeX_Main/.test(f.family) && f.status === 'loaded'),
  };
}

const idCache = new Map();
function idsOf(file) {
  if (!idCache.has(file)) {
    const text = fs.readFileSync(file, 'utf8');
    idCache.set(file, new Set([...text.matchAll(/\bid="([^"]+)"/g)].map((m) => m[1])));
  }
  return idCache.get(file);
}

async function checkPage(browser, file, options) {
  const problems = [];
  const add = (reason) => problems.push(`${file}: ${reason}`);
  const page = await browser.newPage();
  try {
    await page.setViewport({ width: 1100, height: 900 });
    await keepOffline(page, add, 'a page');
    await page.goto(pathToFileURL(file).href, { waitUntil: 'load', timeout: options.timeout * 1000 });
    await page.evaluate(() => document.fonts.ready.then(() => true));
    const seen = await page.evaluate(inspect);
    for (const e of seen.errors) add(`KaTeX could not render a formula: ${String(e).slice(0, 160)}`);
    if (seen.maths < options.minMaths) add(`${seen.maths} rendered formula(s), expected at least ${options.minMaths}`);
    if (seen.maths > 0 && !seen.katexFont) add("KaTeX's fonts did not load (the maths shows in a fallback font)");
    const loaded = seen.images.filter((i) => i.ok).length;
    for (const img of seen.images) if (!img.ok) add(`image failed to load: ${img.src}`);
    if (loaded < options.minImages) add(`${loaded} image(s) loaded, expected at least ${options.minImages}`);
    const own = new Set(seen.ids);
    for (const href of seen.links) {
      if (!href.startsWith('file:')) continue;
      const url = new URL(href);
      const target = fileURLToPath(url);
      const fragment = decodeURIComponent(url.hash.slice(1));
      if (!fs.existsSync(target)) {
        add(`link to a missing file: ${href}`);
        continue;
      }
      if (!fragment || /^L\d+$/.test(fragment)) continue;
      const ids = target === file ? own : target.endsWith('.html') ? idsOf(target) : null;
      if (ids && !ids.has(fragment)) add(`link to a missing anchor: ${href}`);
    }
    if (options.screenshot) await page.screenshot({ path: options.screenshot, fullPage: false });
    return { problems, maths: seen.maths, images: loaded };
  } finally {
    await page.close().catch(() => {});
  }
}

async function main() {
  const options = parseArgs(process.argv.slice(2));
  const { browser, close } = await startChromium(fatal, {
    extraArgs: ['--allow-file-access-from-files'], timeout: options.timeout,
  });
  const all = [];
  try {
    for (const file of options.pages) {
      let result;
      try {
        result = await checkPage(browser, file, options);
      } catch (e) {
        result = { problems: [`${file}: could not open: ${e.message.split('\n')[0]}`], maths: 0, images: 0 };
      }
      const name = path.relative(process.cwd(), file);
      console.log(`${result.problems.length ? 'FAIL' : 'ok  '} ${name}: ${result.maths} formula(s), ` +
                  `${result.images} image(s)`);
      all.push(...result.problems);
    }
  } finally {
    await close();
  }
  if (all.length) {
    console.log(`\ncheck_pages: ${all.length} problem(s):`);
    for (const p of all) console.log(`  ${p}`);
    process.exit(1);
  }
}

main();
