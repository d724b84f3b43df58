// Opens a plumekit report.html in headless Chromium and checks that it works (tests/browser/README.md).
//
//   node tests/browser/report_test.mjs --report DIR/report.html --screenshot OUT.png [--chromium PATH]
//        [--tunnel]
//
// --tunnel: the page of `evaluate tunnel --replays`, whose replays show the tunnel from the side.
// Prints a line per check and exits 1 at the first that fails (or 2 on a usage error).
import fs from 'node:fs';
import path from 'node:path';
import {pathToFileURL} from 'node:url';
import {chromium} from 'playwright-core';

function usage(message) {
  if (message) console.error('report_test: ' + message);
  console.error('usage: node tests/browser/report_test.mjs --report REPORT.html --screenshot OUT.png ' +
                '[--chromium /usr/bin/chromium] [--tunnel]');
  process.exit(2);
}

const args = {chromium: '/usr/bin/chromium'};
for (let k = 2; k < process.argv.length; ++k) {
  const a = process.argv[k];
  if (a === '--tunnel') {  // a tunnel evaluation's page: its replays have a view from the side
    args.tunnel = true;
    continue;
  }
  const m = /^--(report|screenshot|chromium)(?:=(.*))?$/.exec(a);
  if (!m) usage('unknown argument ' + a);
  args[m[1]] = m[2] !== undefined ? m[2] : process.argv[++k];
  if (args[m[1]] === undefined) usage(a + ' needs a value');
}
if (!args.report || !args.screenshot) usage('--report and --screenshot are required');
const reportPath = path.resolve(args.report);
if (!fs.existsSync(reportPath)) usage('no such report: ' + reportPath);
if (!fs.existsSync(args.chromium)) usage('no Chromium at ' + args.chromium + ' (--chromium PATH)');
const reportUrl = pathToFileURL(reportPath).href;

const TIMEOUT = 15000;
let browser = null;

class CheckFailed extends Error {}

const started = Date.now();

function ok(what) {
  console.log('ok   ' + what + (process.env.REPORT_TEST_TIMES ? ' [' + (Date.now() - started) + ' ms]' : ''));
}

function fail(what) {
  throw new CheckFailed(what);
}

function expect(cond, what, detail) {
  if (!cond) fail(what + (detail ? ': ' + detail : ''));
  ok(what);
}

// Everything the page said or asked for, across every page opened.
const problems = [];

function watch(page, label) {
  page.on('console', (msg) => {
    if (msg.type() === 'error' || msg.type() === 'warning') {
      problems.push(label + ': console ' + msg.type() + ': ' + msg.text());
    }
  });
  page.on('pageerror', (err) => problems.push(label + ': page error: ' + (err.stack || err.message)));
  page.on('request', (req) => {
    if (!req.url().startsWith('file://')) problems.push(label + ': request to ' + req.url());
  });
  page.on('requestfailed', (req) => {
    problems.push(label + ': request failed: ' + req.url() + ' (' + (req.failure() || {}).errorText + ')');
  });
}

function noProblems(when) {
  expect(problems.length === 0, 'no console errors or warnings, page errors or non-file requests ' + when,
         '\n  ' + problems.join('\n  '));
}

// Waits for a selector; on a timeout, fails saying what was expected and what the page said.
async function waitFor(page, selector, what, timeout) {
  try {
    await page.waitForSelector(selector, {timeout: timeout || TIMEOUT});
  } catch (err) {
    fail(what + ': no ' + selector + ' after ' + (timeout || TIMEOUT) / 1000 + ' s' +
         (problems.length ? '; the page said:\n  ' + problems.join('\n  ') : ''));
  }
}

async function openReport(context, hash, label) {
  const page = await context.newPage();
  watch(page, label);
  await page.goto(reportUrl + (hash || ''), {waitUntil: 'load', timeout: TIMEOUT});
  try {
    await page.waitForFunction(() => document.body && document.body.dataset.ready === '1', null,
                               {timeout: TIMEOUT});
  } catch (err) {
    fail('the page sets document.body.dataset.ready = "1" after its first render (' + label + ')' +
         (problems.length ? ':\n  ' + problems.join('\n  ') : ''));
  }
  return page;
}

// The column (1-based) of a table's header cell with data-key `key`.
async function columnOf(table, key) {
  return table.evaluate((t, k) => {
    const ths = [...t.querySelectorAll('thead th')];
    return ths.findIndex((th) => th.dataset.key === k) + 1;
  }, key);
}

// The data-v values (null where empty) of a table's column, in row order.
async function columnValues(table, col) {
  return table.evaluate((t, c) => [...t.querySelectorAll('tbody tr')].map((tr) => {
    const td = tr.children[c - 1];
    return td && td.dataset.v !== undefined && td.dataset.v !== '' ? Number(td.dataset.v) : null;
  }), col);
}

function sortedProblem(values, dir) {
  const nums = [];
  let seenNull = false;
  for (const v of values) {
    if (v === null) {
      seenNull = true;
      continue;
    }
    if (seenNull) return 'a value after an empty one';
    nums.push(v);
  }
  for (let k = 1; k < nums.length; ++k) {
    if (dir * (nums[k] - nums[k - 1]) < 0) return 'row ' + (k + 1) + ': ' + nums[k - 1] + ' then ' + nums[k];
  }
  return null;
}

// Clicks a numeric header and checks the order, ascending then descending on a second click.
async function checkSorting(page, tableSel, key, what) {
  const table = page.locator(tableSel).first();
  const col = await columnOf(table, key);
  expect(col > 0, what + ': has a "' + key + '" column');
  const th = table.locator('thead th[data-key="' + key + '"]');
  for (const [dir, name] of [[1, 'ascending'], [-1, 'descending']]) {
    await th.click();
    const values = await columnValues(table, col);
    const distinct = new Set(values.filter((v) => v !== null)).size;
    const problem = sortedProblem(values, dir);
    const aria = await th.getAttribute('aria-sort');
    const arrow = (await th.locator('.arrow').textContent()).trim();
    expect(problem === null && aria === name && arrow !== '' && distinct >= 1,
           what + ': a click on "' + key + '" sorts ' + values.length + ' rows ' + name + ' (' + distinct +
           ' distinct values), with an arrow', problem || 'aria-sort ' + aria + ', arrow "' + arrow + '"');
  }
}

// The screenshot decoded in a blank page (a data: URL image is not tainted, so its pixels can be
// read): per region, the share of pixels unlike the background and the count near each colour.
async function pixelStats(context, png, regions) {
  const page = await context.newPage();
  try {
    return await page.evaluate(async ({b64, regions}) => {
      const img = new Image();
      img.src = 'data:image/png;base64,' + b64;
      await img.decode();
      const canvas = document.createElement('canvas');
      canvas.width = img.naturalWidth;
      canvas.height = img.naturalHeight;
      const ctx = canvas.getContext('2d');
      ctx.drawImage(img, 0, 0);
      const parse = (c) => (c.match(/[\d.]+/g) || []).slice(0, 3).map(Number);
      return regions.map((r) => {
        const x = Math.max(0, Math.floor(r.x));
        const y = Math.max(0, Math.floor(r.y));
        const w = Math.min(canvas.width - x, Math.floor(r.width));
        const h = Math.min(canvas.height - y, Math.floor(r.height));
        if (w <= 0 || h <= 0) return {pixels: 0, inked: 0, near: r.colours.map(() => 0)};
        const d = ctx.getImageData(x, y, w, h).data;
        const bg = parse(r.background);
        const cols = r.colours.map(parse);
        let inked = 0;
        const near = cols.map(() => 0);
        for (let k = 0; k < d.length; k += 4) {
          const p = [d[k], d[k + 1], d[k + 2]];
          if (Math.max(...p.map((v, j) => Math.abs(v - bg[j]))) > 24) ++inked;
          cols.forEach((c, j) => {
            if (Math.max(...p.map((v, i) => Math.abs(v - c[i]))) <= 36) ++near[j];
          });
        }
        return {pixels: w * h, inked, near};
      });
    }, {b64: png.toString('base64'), regions});
  } finally {
    await page.close();
  }
}

async function main() {
  browser = await chromium.launch({executablePath: args.chromium, headless: true, args: ['--no-sandbox']});
  const context = await browser.newContext({viewport: {width: 1280, height: 900}});
  console.log('report: ' + reportPath);

  // ---- load
  const t0 = Date.now();
  const page = await openReport(context, '', 'load');
  ok('the page loads and renders (' + (Date.now() - t0) + ' ms)');
  const facts = await page.evaluate(() => {
    const d = JSON.parse(document.getElementById('plumekit-data').textContent);
    const cols = d.runs.columns;
    const mapCol = cols.indexOf('map');
    const rows = d.runs.rows;
    const replays = Array.isArray(d.replays) ? d.replays : [];
    const tracks = Array.isArray(d.tracks) ? d.tracks : [];
    const hasTrack = (i) => !!(tracks[i] && tracks[i].robots && tracks[i].robots.some((r) => r.path && r.path.length >= 4));
    const perMap = {};
    rows.forEach((r, i) => {
      const m = r[mapCol];
      if (Number.isInteger(m) && m >= 0 && m < d.maps.length) (perMap[m] = perMap[m] || []).push(i);
    });
    let linked = -1;
    for (let i = rows.length - 1; i >= 0; --i) if (hasTrack(i)) { linked = i; break; }
    return {
      format: d.format,
      methods: d.methods.map((m) => String(m.label || m.name)),
      runs: rows.length,
      maps: d.maps.length,
      perMap: Object.fromEntries(Object.entries(perMap).map(([k, v]) => [k, v.length])),
      firstMap: Object.keys(perMap).map(Number).sort((a, b) => a - b)[0],
      linked,
      replay: replays.findIndex((r) => typeof r === 'string' && r.length > 0),
      runRowsAtLoad: document.querySelectorAll('table.runs tbody tr').length,
    };
  });
  expect(facts.format === 'plumekit-report/1', 'the data is format plumekit-report/1', facts.format);
  console.log('     ' + facts.methods.length + ' methods, ' + facts.maps + ' maps, ' + facts.runs + ' runs');
  expect(facts.runRowsAtLoad === 0, 'no run table rows are made at load (they are made when a map opens)',
         facts.runRowsAtLoad + ' rows');
  noProblems('on load');

  // ---- summary table
  await page.selectOption('#summary-filter', 'all');
  const labels = await page.$$eval('#summary-table tbody tr td:first-child', (tds) => tds.map((t) => t.textContent));
  const missing = facts.methods.filter((m) => !labels.includes(m));
  expect(labels.length >= facts.methods.length && missing.length === 0,
         'the summary table has ' + labels.length + ' rows, at least one per method', 'missing ' + missing.join(', '));
  await checkSorting(page, '#summary-table', 'median_error_m', 'summary table');
  await checkSorting(page, '#summary-table', 'success_0_5m', 'summary table (an interval column)');

  // ---- box plots
  const boxes = await page.$$eval('#boxplots svg.boxplot', (s) => s.map((x) => x.querySelectorAll('rect.iqr').length));
  expect(boxes.length >= 3 && boxes.every((n) => n >= 1), 'box plots: ' + boxes.length + ' plots with boxes',
         JSON.stringify(boxes));

  let shotPage = page;  // the page to screenshot, with a run view open
  if (facts.runs === 0) {
    console.log('     (no runs: the map and run checks are skipped)');
  } else {
    // ---- a map's runs
    const mapSel = 'details.map-section[data-map="' + facts.firstMap + '"]';
    await page.click(mapSel + ' > summary');
    const rowsSel = mapSel + ' table.runs tbody tr[data-run]';
    await waitFor(page, rowsSel, 'opening map ' + facts.firstMap + ' renders its runs');
    const nRows = await page.locator(rowsSel).count();
    const want = Math.min(500, facts.perMap[facts.firstMap]);
    expect(nRows === want, 'opening map ' + facts.firstMap + ' renders its runs (' + nRows + ' rows)',
           'expected ' + want);
    await checkSorting(page, mapSel + ' table.runs', 'error_m', 'runs table');

    // ---- a run from its row
    const row = page.locator(rowsSel).first();
    const runIndex = Number(await row.getAttribute('data-run'));
    await row.click();
    await waitFor(page, '#run-view:not([hidden])', 'clicking a run\u2019s row opens the run view');
    const view = await page.evaluate(() => {
      const v = document.getElementById('run-view');
      return {run: v.dataset.run, tracks: v.querySelectorAll('svg.run-svg path.track').length,
              source: v.querySelectorAll('svg.run-svg .source-marker').length,
              estimate: v.querySelectorAll('svg.run-svg .estimate-marker').length, hash: location.hash};
    });
    const trackWanted = await page.evaluate((i) => {
      const d = JSON.parse(document.getElementById('plumekit-data').textContent);
      const t = (d.tracks || [])[i];
      return !!(t && t.robots && t.robots.some((r) => r.path && r.path.length >= 4));
    }, runIndex);
    expect(view.run === String(runIndex) && view.source === 1 && (!trackWanted || view.tracks >= 1),
           'clicking run ' + runIndex + '\u2019s row opens its view: ' + view.tracks + ' path(s), the source marker',
           JSON.stringify(view));
    expect(view.hash === '#run=' + runIndex, 'opening it sets the URL\u2019s hash to #run=' + runIndex, view.hash);
    await page.keyboard.press('Escape');
    const closed = await page.evaluate(() => ({hidden: document.getElementById('run-view').hidden, hash: location.hash}));
    expect(closed.hidden && closed.hash === '', 'Escape closes the run view and clears the hash', JSON.stringify(closed));
    noProblems('on sorting and opening runs');

    // ---- #run=N
    const linked = facts.linked >= 0 ? facts.linked : facts.runs - 1;
    const linkPage = await openReport(context, '#run=' + linked, '#run=' + linked);
    const lv = await linkPage.evaluate(() => {
      const v = document.getElementById('run-view');
      return {hidden: v.hidden, run: v.dataset.run, tracks: v.querySelectorAll('svg.run-svg path.track').length};
    });
    expect(!lv.hidden && lv.run === String(linked) && (facts.linked < 0 || lv.tracks >= 1),
           '#run=' + linked + ' in the URL opens run ' + linked, JSON.stringify(lv));
    shotPage = linkPage;
  }

  // ---- the replay player
  if (facts.replay >= 0) {
    const rp = await openReport(context, '#run=' + facts.replay, 'replay');
    shotPage = rp;
    await waitFor(rp, '#run-view .player[data-state="ready"], #run-view .player[data-state="error"]',
                  'the replay of run ' + facts.replay + ' loads');
    const state = await rp.getAttribute('#run-view .player', 'data-state');
    expect(state === 'ready', 'the replay of run ' + facts.replay + ' loads',
           state === 'ready' ? '' : await rp.evaluate(() => document.querySelector('.player .player-status').textContent));
    const before = await rp.evaluate(() => ({frame: document.querySelector('.player').dataset.frame,
                                              clock: document.querySelector('.player .clock').textContent,
                                              max: Number(document.querySelector('.player .slider').max)}));
    expect(before.frame === '0' && before.max >= 1, 'the player shows frame 0 of ' + (before.max + 1),
           JSON.stringify(before));
    const mid = Math.max(1, Math.round(before.max / 2));
    await rp.locator('#run-view .player .slider').fill(String(mid));
    const after = await rp.evaluate(() => ({frame: document.querySelector('.player').dataset.frame,
                                             clock: document.querySelector('.player .clock').textContent}));
    expect(after.frame === String(mid) && after.clock !== before.clock,
           'its slider moves it to frame ' + mid + ' ("' + after.clock + '")', JSON.stringify(after));
    await rp.click('#run-view .player .play');
    await rp.waitForFunction((m) => Number(document.querySelector('.player').dataset.frame) > m, mid,
                             {timeout: 5000}).catch(() => {});
    const playing = Number(await rp.getAttribute('#run-view .player', 'data-frame'));
    await rp.click('#run-view .player .play');
    expect(playing > mid, 'its play button plays on (frame ' + playing + ')');
    await rp.locator('#run-view .player .slider').fill(String(mid));
    // A tunnel run's replay (--tunnel) shows the tunnel from the side too, its gas painted.
    const side = rp.locator('#run-view .player canvas.world-side');
    const sides = await side.count();
    if (args.tunnel !== undefined) {
      expect(sides === 1, 'the tunnel\u2019s replay shows the view from the side', sides + ' side views');
      const box = await side.boundingBox();
      const [sideStats] = await pixelStats(context, await side.screenshot(),
                                           [{x: 0, y: 0, width: box.width, height: box.height,
                                             background: 'rgb(255, 255, 255)', colours: []}]);
      expect(sideStats.inked > 0.2 * sideStats.pixels,
             'the view from the side shows the gas (' + (100 * sideStats.inked / sideStats.pixels).toFixed(0) +
             ' % drawn)', JSON.stringify(sideStats));
    } else {
      expect(sides === 0, 'a 2-D replay has no view from the side', sides + ' side views');
    }
    noProblems('with the replay');
  }

  // ---- the screenshot, and what it shows
  if (facts.runs === 0) {
    console.log('     (no runs: no run view to screenshot)');
    noProblems('in the end');
    console.log('PASS');
    return;
  }
  await shotPage.evaluate(() => {
    window.scrollTo(0, 0);
    document.getElementById('run-view').scrollTop = 0;
  });
  await shotPage.waitForTimeout(200);
  const regions = await shotPage.evaluate(() => {
    const view = document.getElementById('run-view');
    const run = view.querySelector('svg.run-svg');
    const table = document.getElementById('summary-table');
    const track = run && run.querySelector('path.track');
    const source = run && run.querySelector('.source-marker');
    const viewRect = view.getBoundingClientRect();
    const r = (e) => {
      const b = e.getBoundingClientRect();
      return {x: b.left, y: b.top, width: b.width, height: b.height};
    };
    const t = r(table);
    // The part of the summary table left of the run view and inside the window.
    t.width = Math.min(t.x + t.width, viewRect.left) - t.x;
    t.height = Math.min(t.y + t.height, window.innerHeight) - t.y;
    return {
      run: Object.assign(r(run), {background: getComputedStyle(view).backgroundColor,
                                  colours: [getComputedStyle(track || run).stroke, getComputedStyle(source).fill]}),
      table: Object.assign(t, {background: getComputedStyle(document.body).backgroundColor, colours: []}),
    };
  });
  const png = await shotPage.screenshot();
  fs.mkdirSync(path.dirname(path.resolve(args.screenshot)), {recursive: true});
  fs.writeFileSync(args.screenshot, png);
  ok('screenshot written to ' + args.screenshot);
  const [runStats, tableStats] = await pixelStats(context, png, [regions.run, regions.table]);
  const share = (s) => (s.pixels ? s.inked / s.pixels : 0);
  expect(runStats.pixels > 10000 && share(runStats) > 0.01,
         'the screenshot\u2019s run view is not blank (' + (100 * share(runStats)).toFixed(1) + ' % drawn)',
         JSON.stringify(runStats));
  expect(runStats.near[0] >= 20, 'it shows the path\u2019s colour ' + regions.run.colours[0] + ' (' +
         runStats.near[0] + ' pixels)');
  expect(runStats.near[1] >= 20, 'it shows the source marker\u2019s red ' + regions.run.colours[1] + ' (' +
         runStats.near[1] + ' pixels)');
  expect(tableStats.pixels > 5000 && share(tableStats) > 0.01,
         'the screenshot\u2019s summary table is not blank (' + (100 * share(tableStats)).toFixed(1) + ' % drawn)',
         JSON.stringify(tableStats));
  noProblems('in the end');
  console.log('PASS');
}

main().then(async () => {
  await browser.close();
  process.exit(0);
}, async (err) => {
  console.log('FAIL ' + (err instanceof CheckFailed ? err.message : err.stack || err));
  if (!(err instanceof CheckFailed) && problems.length) console.log('the page said:\n  ' + problems.join('\n  '));
  if (browser) await browser.close().catch(() => {});
  process.exit(1);
});
