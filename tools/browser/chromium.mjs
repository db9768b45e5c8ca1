// Headless Chromium for illum's browser checks (the deck test, the page test, the lab's
// test, benchmark and screenshots): one home for how Chromium is found, started and kept
// off the network.
//
// Chromium is Debian's /usr/bin/chromium (override with ILLUM_CHROMIUM), driven through
// puppeteer-core (npm ci), with a fresh profile that is deleted on close.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

export const INSTALL_HINT = 'run tools/install-deps (Debian packages chromium, nodejs, npm; then npm ci)';
export const CHROMIUM = process.env.ILLUM_CHROMIUM || '/usr/bin/chromium';
// Headless, no GPU, and nothing that reaches for the network on its own (updates, sync, QUIC).
export const CHROMIUM_ARGS = [
  '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync',
];

// Starts Chromium; `fatal(message)` is called (and must not return) when it cannot.
//   extraArgs   flags after CHROMIUM_ARGS;  timeout  seconds for the start;
//   launch      more puppeteer.launch options (defaultViewport, ...).
// Returns { browser, close }: close() stops the browser and deletes its profile.
export async function startChromium(fatal, { extraArgs = [], timeout = 60, launch = {} } = {}) {
  let puppeteer;
  try {
    puppeteer = (await import('puppeteer-core')).default;
  } catch (e) {
    fatal(`puppeteer-core is not installed: ${INSTALL_HINT}\n  (${e.message.split('\n')[0]})`);
  }
  if (!fs.existsSync(CHROMIUM)) fatal(`Chromium is not installed at ${CHROMIUM}: ${INSTALL_HINT}`);
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'illum-chromium-'));
  const removeProfile = () => fs.rmSync(profile, { recursive: true, force: true });
  let browser;
  try {
    browser = await puppeteer.launch({
      executablePath: CHROMIUM, headless: true, args: [...CHROMIUM_ARGS, ...extraArgs], userDataDir: profile,
      timeout: timeout * 1000, ...launch,
    });
  } catch (e) {
    removeProfile();
    fatal(`Chromium (${CHROMIUM}) did not start: ${e.message.split('\n')[0]}\n  ${INSTALL_HINT}`);
  }
  const close = async () => {
    await browser.close().catch(() => {});
    removeProfile();
  };
  return { browser, close };
}

// Keeps a page offline: every request that is not file:, data:, blob: or about: is aborted
// and reported through add(reason); a local resource that fails to load (not an image: the
// callers report images with their place) is reported too, and so is a script error.
export async function keepOffline(page, add, what) {
  await page.setRequestInterception(true);
  page.on('request', (request) => {
    const url = request.url();
    if (/^(file|data|blob|about):/.test(url)) request.continue();
    else {
      add(`fetches ${url} from the network (${what} must work offline)`);
      request.abort();
    }
  });
  page.on('requestfailed', (request) => {
    const url = request.url();
    if (url.startsWith('file:') && request.resourceType() !== 'image')
      add(`${request.resourceType()} failed to load: ${url} (${request.failure()?.errorText})`);
  });
  page.on('pageerror', (error) => add(`script error: ${error.message.split('\n')[0]}`));
}
