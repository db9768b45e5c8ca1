import { startChromium } from '../browser/chromium.mjs';
const [url] = process.argv.slice(2);
const { browser, close } = await startChromium(m => { console.error(m); process.exit(2); }, {
  extraArgs: ['--enable-unsafe-swiftshader'], launch: { defaultViewport: { width: 1400, height: 1000 } } });
const page = await browser.newPage();
page.on('pageerror', e => console.log('pageerror', e.message));
page.on('console', m => m.type() === 'error' && console.log('console', m.text()));
await page.goto(url + '#tree', { waitUntil: 'load' });
await page.waitForSelector('body[data-ready="true"]');
await page.waitForFunction(() => ['ready', 'error'].includes(document.querySelector('#tab-tree').dataset.state), { timeout: 60000 });
console.log('tree:', await page.$eval('#tab-tree', s => s.dataset.state + ' ' + s.dataset.drawnBy), await page.$eval('#tree-image-note', p => p.hidden + ' ' + p.textContent), await page.$eval('#tree-status', p => p.textContent));
const box = await page.$eval('#tree-image', img => { const r = img.getBoundingClientRect(); return { left: r.left, top: r.top, width: r.width, height: r.height, w: img.naturalWidth, h: img.naturalHeight }; });
if (box.w) {
  await page.mouse.click(box.left + 285.5 * box.width / box.w, box.top + 173.5 * box.height / box.h);
  await page.waitForFunction(() => ['drawn', 'error'].includes(document.querySelector('#tab-tree').dataset.state), { polling: 'mutation' });
  console.log('versus:', await page.$eval('#tree-versus', d => d.dataset.first + ' | ' + (d.querySelector('#versus-summary') || {}).textContent));
  console.log('rows', await page.$eval('#tree-versus', d => d.dataset.rows), 'ghost', await page.$eval('#tree-3d', d => d.dataset.referenceSegments));
}
await page.screenshot({ path: '/tmp/probe/versus.png', fullPage: true });
await page.$eval('button[data-tab="radiosity"]', b => b.click());
await page.waitForFunction(() => ['ready', 'error'].includes(document.querySelector('#tab-radiosity').dataset.state), { timeout: 60000 });
for (let k = 0; k < 3; ++k) {
  await page.$eval('#rad-step-1', b => b.click());
  await page.waitForFunction(n => document.querySelector('#tab-radiosity').dataset.steps === String(n) && ['ready', 'error'].includes(document.querySelector('#tab-radiosity').dataset.state), { polling: 'mutation' }, k + 1);
}
console.log('radiosity:', await page.$eval('#tab-radiosity', s => s.dataset.versus), await page.$eval('#rad-versus-text', d => d.textContent), await page.$eval('#rad-status', d => d.textContent));
await page.screenshot({ path: '/tmp/probe/rad.png', fullPage: true });
await close();
