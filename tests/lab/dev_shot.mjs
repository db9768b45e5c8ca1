// development helper (not committed): screenshots of each tab
import puppeteer from 'puppeteer-core';
import fs from 'node:fs'; import os from 'node:os'; import path from 'node:path';
const url = process.argv[2];
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'h27-chr-'));
const browser = await puppeteer.launch({executablePath: '/usr/bin/chromium', args: ['--headless','--no-sandbox','--disable-gpu','--no-first-run','--disable-background-networking','--disable-component-update','--disable-sync', `--user-data-dir=${dir}`]});
try {
const page = await browser.newPage();
await page.setViewport({width: 1400, height: 1100});
page.on('console', m => console.log('console:', m.type(), m.text()));
page.on('pageerror', e => console.log('pageerror:', e.message));
page.on('requestfailed', r => console.log('failed:', r.url()));
await page.goto(url + '#tree');
await page.waitForSelector('#tab-tree[data-state="ready"]', {timeout: 20000});
const box = await page.$eval('#tree-image', img => { const r = img.getBoundingClientRect(); return {x: r.left, y: r.top, w: r.width, nw: img.naturalWidth, h: r.height, nh: img.naturalHeight}; });
await page.mouse.click(box.x + (285.5) * box.w / box.nw, box.y + 173.5 * box.h / box.nh);
await page.waitForSelector('#tab-tree[data-state="drawn"]', {timeout: 20000});
console.log(await page.$eval('#tab-tree', s => s.dataset.clickMs + ' ' + s.dataset.pixel), await page.$eval('#tree-status', s => s.textContent));
await page.screenshot({path: '/tmp/h27-shot-tree.png', fullPage: true});
await page.click('button[data-tab="radiosity"]');
await page.waitForSelector('#tab-radiosity[data-state="ready"]', {timeout: 30000});
await page.click('#rad-step-10');
await page.waitForFunction(() => document.querySelector('#tab-radiosity').dataset.steps === '10', {timeout: 30000});
console.log(await page.$eval('#rad-status', s => s.textContent));
await page.screenshot({path: '/tmp/h27-shot-rad.png', fullPage: true});
await page.click('button[data-tab="hemicube"]');
await page.waitForSelector('#tab-hemicube[data-state="drawn"]', {timeout: 30000});
console.log(await page.$eval('#hc-status', s => s.textContent));
await page.screenshot({path: '/tmp/h27-shot-hc.png', fullPage: true});
await page.click('button[data-tab="compare"]');
await page.waitForFunction(() => ['compared','missing','error'].includes(document.querySelector('#tab-compare').dataset.state), {timeout: 30000});
console.log(await page.$eval('#cmp-verdict', s => s.textContent));
await page.screenshot({path: '/tmp/h27-shot-cmp.png', fullPage: true});
} finally { await browser.close(); fs.rmSync(dir, {recursive: true, force: true}); }
