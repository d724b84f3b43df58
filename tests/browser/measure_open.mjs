// How long a plumekit report.html takes to open in headless Chromium, for the docs' figures (not a test).
//
//   node tests/browser/measure_open.mjs REPORT.html [--runs 5] [--chromium /usr/bin/chromium]
//
// Each of --runs fresh loads (a new browser context each) is timed from the navigation's start
// until report.js sets document.body.dataset.ready = "1" (its first render done); prints JSON:
// {"median_open_s", "size_bytes", "runs", "open_s": [...], "median_first_paint_s"}.
import fs from 'node:fs';
import path from 'node:path';
import {pathToFileURL} from 'node:url';
import {chromium} from 'playwright-core';

function usage(message) {
  if (message) console.error('measure_open: ' + message);
  console.error('usage: node tests/browser/measure_open.mjs REPORT.html [--runs N] [--chromium PATH]');
  process.exit(2);
}

let report = null;
let runs = 5;
let executable = '/usr/bin/chromium';
for (let k = 2; k < process.argv.length; ++k) {
  const a = process.argv[k];
  if (a === '--runs') runs = Number(process.argv[++k]);
  else if (a === '--chromium') executable = process.argv[++k];
  else if (a.startsWith('--')) usage('unknown option ' + a);
  else if (report === null) report = a;
  else usage('one report only');
}
if (!report) usage('no report given');
if (!(Number.isInteger(runs) && runs >= 1)) usage('--runs takes a whole number >= 1');
const file = path.resolve(report);
if (!fs.existsSync(file)) usage('no such file: ' + file);

function median(xs) {
  const a = xs.slice().sort((x, y) => x - y);
  const h = Math.floor(a.length / 2);
  return a.length % 2 ? a[h] : (a[h - 1] + a[h]) / 2;
}

const browser = await chromium.launch({executablePath: executable, headless: true, args: ['--no-sandbox']});
const open = [];
const paint = [];
try {
  for (let k = 0; k < runs; ++k) {
    const context = await browser.newContext({viewport: {width: 1280, height: 900}});
    // Before any of the page's own script: note the moment body's data-ready turns "1".
    await context.addInitScript(() => {
      new MutationObserver((records, observer) => {
        if (document.body && document.body.dataset.ready === '1') {
          window.__plumekitReadyAt = performance.now();
          observer.disconnect();
        }
      }).observe(document, {subtree: true, attributes: true, attributeFilter: ['data-ready']});
    });
    const page = await context.newPage();
    await page.goto(pathToFileURL(file).href, {waitUntil: 'load', timeout: 60000});
    await page.waitForFunction(() => window.__plumekitReadyAt !== undefined, null, {timeout: 60000});
    // performance.now() counts from the navigation's start (the time origin).
    const t = await page.evaluate(() => new Promise((resolve) => requestAnimationFrame(() => setTimeout(() => {
      const fcp = performance.getEntriesByName('first-contentful-paint')[0];
      resolve({ready: window.__plumekitReadyAt, paint: fcp ? fcp.startTime : null});
    }, 50))));
    open.push(t.ready / 1000);
    if (t.paint !== null) paint.push(t.paint / 1000);
    await context.close();
  }
} finally {
  await browser.close();
}
const round = (v) => Math.round(v * 1000) / 1000;
console.log(JSON.stringify({
  median_open_s: round(median(open)),
  size_bytes: fs.statSync(file).size,
  runs,
  open_s: open.map(round),
  median_first_paint_s: paint.length ? round(median(paint)) : null,
}));
