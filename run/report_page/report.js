// plumekit's report.html: the page that browses one `plumekit evaluate` (format plumekit-report/1).
// The C++ side (run/evaluation_html.cpp) writes this file verbatim into the page after a
// <script type="application/json" id="plumekit-data"> holding the evaluation; this script builds
// the whole page from it. Plain ES2020, no libraries, no requests but the replays' own files
// (<folder>/replay.js through a script element and its two PNG film strips through img elements: the
// page is opened from file://, where fetch and XHR of local files are refused). Pixels are never
// read back from a canvas (a file:// image taints it). Tested by tests/browser/report_test.mjs.
(function () {
  'use strict';

  const SVGNS = 'http://www.w3.org/2000/svg';
  const DASH = '\u2013';
  const collator = new Intl.Collator('en', {numeric: true, sensitivity: 'base'});
  // Robots' colours (a team's robots in this order); the source, start and estimate markers.
  const ROBOT_COLOURS = ['#1f5fbf', '#e07a10', '#7a3fb0', '#138a7e', '#8c5a2b', '#c2407f'];
  const SOURCE_COLOUR = '#d7191c';
  const START_COLOUR = '#1a9641';
  const ESTIMATE_COLOUR = '#b01fb5';
  // Colour maps, level 0 .. 255 in 32 steps, as run/replay_render.cpp draws them: the gas is
  // matplotlib's inferno reversed, the belief viridis reversed on a square-root scale; both fade in
  // from white (no gas, no belief).
  const GAS_TABLE = [[255, 255, 255], [251, 252, 213], [249, 245, 188], [250, 235, 158],
    [251, 222, 127], [252, 205, 94], [253, 186, 60], [252, 165, 29], [249, 140, 10], [246, 126, 20],
    [241, 113, 31], [235, 100, 41], [227, 89, 51], [218, 78, 60], [208, 69, 69], [198, 61, 77],
    [186, 54, 85], [176, 49, 91], [163, 44, 97], [151, 39, 102], [138, 34, 106], [125, 30, 109],
    [113, 25, 110], [100, 21, 110], [87, 16, 110], [74, 12, 107], [61, 9, 101], [47, 10, 91],
    [33, 12, 74], [21, 11, 55], [11, 7, 36], [4, 3, 18], [0, 0, 4]];
  const BELIEF_TABLE = [[255, 255, 255], [214, 241, 192], [184, 231, 187], [154, 220, 180],
    [124, 207, 173], [97, 193, 166], [73, 177, 158], [52, 162, 150], [33, 144, 141], [35, 137, 142],
    [38, 130, 142], [41, 123, 142], [43, 117, 142], [46, 111, 142], [48, 105, 142], [51, 99, 141],
    [54, 93, 141], [56, 88, 140], [59, 82, 139], [61, 77, 138], [63, 71, 136], [66, 65, 134],
    [68, 59, 132], [69, 53, 129], [71, 47, 125], [71, 42, 122], [72, 36, 117], [72, 31, 112],
    [72, 26, 108], [71, 19, 101], [71, 13, 96], [70, 7, 90], [68, 1, 84]];
  const GAS_FILTER_ID = 'plumekit-gas-colours';
  const BELIEF_FILTER_ID = 'plumekit-belief-colours';

  // ---------------------------------------------------------------- small helpers

  function el(tag, attrs, ...children) {
    const e = document.createElement(tag);
    setAttrs(e, attrs);
    for (const c of children) if (c !== null && c !== undefined) e.append(c);
    return e;
  }

  function svg(tag, attrs, ...children) {
    const e = document.createElementNS(SVGNS, tag);
    setAttrs(e, attrs);
    for (const c of children) if (c !== null && c !== undefined) e.append(c);
    return e;
  }

  function setAttrs(e, attrs) {
    if (!attrs) return;
    for (const k of Object.keys(attrs)) {
      const v = attrs[k];
      if (v === null || v === undefined || v === false) continue;
      if (k === 'text') e.textContent = v;
      else e.setAttribute(k, v === true ? '' : String(v));
    }
  }

  function isNum(v) {
    return typeof v === 'number' && Number.isFinite(v);
  }

  function num(v) {
    return isNum(v) ? v : null;
  }

  function fixed(v, digits) {
    return isNum(v) ? v.toFixed(digits) : DASH;
  }

  // A median of counts: whole, or one decimal when it falls between two.
  function count(v) {
    if (!isNum(v)) return DASH;
    return Number.isInteger(v) ? String(v) : v.toFixed(1);
  }

  function plural(n, word) {
    return n + ' ' + word + (n === 1 ? '' : 's');
  }

  function percent(v) {
    return isNum(v) ? (v * 100).toFixed(0) + ' %' : DASH;
  }

  // Two significant digits for a legend's label (0.37, 12, 5900).
  function short(v) {
    if (!isNum(v)) return DASH;
    if (v === 0) return '0';
    const a = Math.abs(v);
    if (a >= 100) return String(Math.round(v / Math.pow(10, Math.floor(Math.log10(a)) - 1)) *
                               Math.pow(10, Math.floor(Math.log10(a)) - 1));
    return String(Number(v.toPrecision(2)));
  }

  function point(x, y) {
    return isNum(x) && isNum(y) ? '(' + x.toFixed(2) + ', ' + y.toFixed(2) + ')' : DASH;
  }

  function rgb(c) {
    return 'rgb(' + c[0] + ',' + c[1] + ',' + c[2] + ')';
  }

  // A colour table's colour at t in [0, 1], interpolated.
  function tableColour(table, t) {
    const x = Math.min(1, Math.max(0, isNum(t) ? t : 0)) * (table.length - 1);
    const i = Math.min(table.length - 2, Math.floor(x));
    const f = x - i;
    const a = table[i];
    const b = table[i + 1];
    return [0, 1, 2].map((k) => Math.round(a[k] + (b[k] - a[k]) * f));
  }

  function gradientCss(table) {
    const stops = table.map((c, i) => rgb(c) + ' ' + ((100 * i) / (table.length - 1)).toFixed(1) + '%');
    return 'linear-gradient(to right, ' + stops.join(', ') + ')';
  }

  // Quartiles by linear interpolation (R's type 7) of an ascending array.
  function quantile(sorted, p) {
    const h = (sorted.length - 1) * p;
    const i = Math.floor(h);
    return i + 1 < sorted.length ? sorted[i] + (h - i) * (sorted[i + 1] - sorted[i]) : sorted[i];
  }

  // About n round ticks over [lo, hi], and the step between them.
  function niceTicks(lo, hi, n) {
    if (!(hi > lo)) hi = lo + 1;
    const raw = (hi - lo) / n;
    const mag = Math.pow(10, Math.floor(Math.log10(raw)));
    const f = raw / mag;
    const step = (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10) * mag;
    const ticks = [];
    for (let t = Math.ceil(lo / step - 1e-9) * step; t <= hi + step * 1e-9; t += step) {
      ticks.push(Number(t.toPrecision(12)));
    }
    return {ticks, step};
  }

  function tickLabel(v, step) {
    const digits = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
    return v.toFixed(digits);
  }

  // A deterministic jitter in [-1, 1] for dot i.
  function jitter(i) {
    const s = Math.sin(i * 12.9898 + 78.233) * 43758.5453;
    return 2 * (s - Math.floor(s)) - 1;
  }

  // Report a section's failure in the page and the console (the browser test fails on it).
  function failIn(container, what, err) {
    container.append(el('p', {class: 'error', text: 'Could not show ' + what + ': ' +
                                                  (err && err.message ? err.message : String(err))}));
    console.error('plumekit report: ' + what + ':', err);
  }

  // ---------------------------------------------------------------- the data

  let D;
  try {
    D = JSON.parse(document.getElementById('plumekit-data').textContent);
    if (!D || typeof D !== 'object') throw new Error('not a JSON object');
  } catch (err) {
    const page = el('main', {class: 'page'}, el('h1', {text: 'plumekit report'}));
    document.body.append(page);
    failIn(page, 'the report: its data cannot be read', err);
    return;
  }

  const methods = Array.isArray(D.methods) ? D.methods : [];
  const maps = Array.isArray(D.maps) ? D.maps : [];
  const runTable = D.runs && typeof D.runs === 'object' ? D.runs : {};
  const columns = Array.isArray(runTable.columns) ? runTable.columns : [];
  const rows = Array.isArray(runTable.rows) ? runTable.rows.map((r) => (Array.isArray(r) ? r : [])) : [];
  const tracks = Array.isArray(D.tracks) ? D.tracks : [];
  const replays = Array.isArray(D.replays) ? D.replays : [];
  const COL = {};
  for (const name of ['method', 'map', 'source', 'run', 'seed', 'error_m', 'samples', 'distance_m',
                      'mission_s', 'stopped_by', 'source_x', 'source_y', 'start_x', 'start_y',
                      'estimate_x', 'estimate_y']) {
    COL[name] = columns.indexOf(name);
  }

  function value(i, name) {
    const k = COL[name];
    return k >= 0 ? rows[i][k] : undefined;
  }

  function methodOf(i) {
    const m = value(i, 'method');
    return Number.isInteger(m) ? m : -1;
  }

  function mapOf(i) {
    const m = value(i, 'map');
    return Number.isInteger(m) ? m : -1;
  }

  function methodLabel(m) {
    const x = methods[m];
    if (!x) return 'method #' + m + ' (not in the report)';
    return String(x.label || x.name || 'method ' + m);
  }

  function mapName(m) {
    const x = maps[m];
    if (!x) return 'map #' + m + ' (not in the report)';
    return String(x.name || 'map ' + m);
  }

  function replayOf(i) {
    const r = replays[i];
    return typeof r === 'string' && r.length > 0 ? r : null;
  }

  function trackOf(i) {
    const t = tracks[i];
    return t && Array.isArray(t.robots) ? t.robots : null;
  }

  function runName(i) {
    const parts = [methodLabel(methodOf(i)), mapName(mapOf(i))];
    const s = value(i, 'source');
    const r = value(i, 'run');
    if (isNum(s)) parts.push('source ' + s);
    if (isNum(r)) parts.push('run ' + r);
    return parts.join(' \u00b7 ');
  }

  // ---------------------------------------------------------------- sortable tables

  // A table whose rows (any records) sort by a column when its header is clicked (again: the
  // other way). columns: {key, label, unit, title, num (right-aligned, numeric sort)};
  // sortValue(rec, col): number, string or null (nulls last either way); fill(td, rec, col);
  // setupRow(tr, rec); limit: rows shown before a "show all" button.
  function sortableTable(opts) {
    const table = el('table', {class: 'data ' + (opts.className || ''), id: opts.id || null});
    const headRow = el('tr');
    for (const c of opts.columns) {
      const button = el('button', {type: 'button'}, c.label);
      if (c.unit) button.append(el('span', {class: 'unit', text: '\u00a0' + c.unit}));
      button.append(el('span', {class: 'arrow', 'aria-hidden': 'true'}));
      headRow.append(el('th', {scope: 'col', 'data-key': c.key, class: c.num ? 'num' : null,
                               title: c.title || null}, button));
    }
    const tbody = el('tbody');
    const tfoot = el('tfoot');
    table.append(el('thead', null, headRow), tbody, tfoot);
    let records = [];
    let order = [];
    let sortKey = null;
    let dir = 1;
    let shown = opts.limit || Infinity;

    function sort() {
      order = records.slice();
      if (sortKey === null) return;
      const col = opts.columns.find((c) => c.key === sortKey);
      const keyed = order.map((rec, k) => ({rec, k, v: opts.sortValue(rec, col)}));
      keyed.sort((a, b) => {
        const an = a.v === null || a.v === undefined || (typeof a.v === 'number' && !isNum(a.v));
        const bn = b.v === null || b.v === undefined || (typeof b.v === 'number' && !isNum(b.v));
        if (an || bn) return an === bn ? a.k - b.k : an ? 1 : -1;
        const c = typeof a.v === 'number' && typeof b.v === 'number' ? a.v - b.v
                                                                     : collator.compare(String(a.v), String(b.v));
        return c !== 0 ? dir * c : a.k - b.k;
      });
      order = keyed.map((x) => x.rec);
    }

    function render() {
      const frag = document.createDocumentFragment();
      const n = Math.min(shown, order.length);
      for (let r = 0; r < n; ++r) {
        const rec = order[r];
        const tr = document.createElement('tr');
        for (const c of opts.columns) {
          const td = document.createElement('td');
          if (c.num) {
            td.className = 'num';
            const v = opts.sortValue(rec, c);
            if (isNum(v)) td.dataset.v = String(v);
          }
          opts.fill(td, rec, c);
          tr.append(td);
        }
        if (opts.setupRow) opts.setupRow(tr, rec);
        frag.append(tr);
      }
      tbody.replaceChildren(frag);
      tfoot.replaceChildren();
      if (order.length === 0 && opts.emptyText) {
        tfoot.append(el('tr', null, el('td', {colspan: opts.columns.length, class: 'empty',
                                              text: opts.emptyText})));
      } else if (order.length > n) {
        const more = el('button', {type: 'button', class: 'more',
                                   text: 'Show all ' + order.length + ' rows (' + n + ' shown)'});
        more.addEventListener('click', () => {
          shown = Infinity;
          render();
        });
        tfoot.append(el('tr', null, el('td', {colspan: opts.columns.length}, more)));
      }
      for (const th of headRow.children) {
        const on = th.dataset.key === sortKey;
        th.classList.toggle('sorted', on);
        if (on) th.setAttribute('aria-sort', dir > 0 ? 'ascending' : 'descending');
        else th.removeAttribute('aria-sort');
        th.querySelector('.arrow').textContent = on ? (dir > 0 ? '\u00a0\u25b2' : '\u00a0\u25bc') : '';
      }
      if (opts.onRender) opts.onRender(tbody);
    }

    headRow.addEventListener('click', (e) => {
      const th = e.target.closest('th');
      if (!th) return;
      if (sortKey === th.dataset.key) dir = -dir;
      else {
        sortKey = th.dataset.key;
        dir = 1;
      }
      sort();
      render();
    });

    return {
      table,
      tbody,
      setRecords(recs) {
        records = recs;
        shown = opts.limit || Infinity;
        sort();
        render();
      },
    };
  }

  // ---------------------------------------------------------------- geometry drawing

  // A projection of the arena rectangle [x0, x1] x [y0, y1] (metres, y up) onto an SVG or canvas
  // of `width` units (y down), `pad` units around it.
  function projection(ext, width, pad) {
    const w = Math.max(ext.x1 - ext.x0, 1e-6);
    const h = Math.max(ext.y1 - ext.y0, 1e-6);
    const s = (width - 2 * pad) / w;
    return {
      s,
      width,
      height: h * s + 2 * pad,
      x: (x) => pad + (x - ext.x0) * s,
      y: (y) => pad + (ext.y1 - y) * s,
    };
  }

  function mapExtent(map) {
    if (map && isNum(map.width) && isNum(map.height) && map.width > 0 && map.height > 0) {
      return {x0: 0, y0: 0, x1: map.width, y1: map.height};
    }
    return null;
  }

  // The smallest extent holding `ext` (or nothing) and every point.
  function extendExtent(ext, pts) {
    let e = ext ? Object.assign({}, ext) : null;
    for (const p of pts) {
      if (!p || !isNum(p[0]) || !isNum(p[1])) continue;
      if (!e) e = {x0: p[0], y0: p[1], x1: p[0], y1: p[1]};
      e.x0 = Math.min(e.x0, p[0]);
      e.y0 = Math.min(e.y0, p[1]);
      e.x1 = Math.max(e.x1, p[0]);
      e.y1 = Math.max(e.y1, p[1]);
    }
    if (!e) e = {x0: 0, y0: 0, x1: 1, y1: 1};
    if (!ext) {
      const m = Math.max(0.5, 0.05 * Math.max(e.x1 - e.x0, e.y1 - e.y0));
      e = {x0: e.x0 - m, y0: e.y0 - m, x1: e.x1 + m, y1: e.y1 + m};
    }
    return e;
  }

  function pathData(pr, flat, stride) {
    let d = '';
    for (let k = 0; k + 1 < flat.length; k += stride) {
      const x = flat[k];
      const y = flat[k + 1];
      if (!isNum(x) || !isNum(y)) continue;
      d += (d ? 'L' : 'M') + pr.x(x).toFixed(1) + ' ' + pr.y(y).toFixed(1);
    }
    return d;
  }

  // The arena and its obstacles into an SVG group.
  function drawMap(g, map, pr, ext) {
    if (mapExtent(map)) {
      g.append(svg('rect', {class: 'arena', x: pr.x(0), y: pr.y(map.height),
                            width: map.width * pr.s, height: map.height * pr.s}));
    } else {
      g.append(svg('rect', {class: 'arena unknown', x: pr.x(ext.x0), y: pr.y(ext.y1),
                            width: (ext.x1 - ext.x0) * pr.s, height: (ext.y1 - ext.y0) * pr.s}));
    }
    if (map && Array.isArray(map.obstacles)) {
      for (const poly of map.obstacles) {
        if (!Array.isArray(poly) || poly.length < 6) continue;
        const d = pathData(pr, poly, 2);
        if (d) g.append(svg('path', {class: 'obstacle', d: d + 'Z'}));
      }
    }
  }

  function cross(x, y, r, attrs) {
    return svg('path', Object.assign({d: 'M' + (x - r) + ' ' + (y - r) + 'L' + (x + r) + ' ' + (y + r) +
                                         'M' + (x - r) + ' ' + (y + r) + 'L' + (x + r) + ' ' + (y - r)},
                                     attrs));
  }

  // ---------------------------------------------------------------- page skeleton

  const main = el('main', {class: 'page'});
  document.body.append(main);

  function section(id, title) {
    const s = el('section', {id, class: 'section'}, el('h2', {text: title}));
    main.append(s);
    return s;
  }

  function buildHeader() {
    const header = el('header', {class: 'top'});
    header.append(el('h1', {text: String(D.title || 'plumekit evaluation')}));
    const n = rows.length;
    const nReplays = replays.filter((r) => typeof r === 'string').length;
    header.append(el('p', {class: 'meta', text:
      methods.length + (methods.length === 1 ? ' method' : ' methods') + ' \u00b7 ' + maps.length +
      (maps.length === 1 ? ' map' : ' maps') + ' \u00b7 ' + n + (n === 1 ? ' run' : ' runs') +
      (nReplays ? ' \u00b7 ' + nReplays + ' with a replay' : '')}));
    const settings = D.settings && typeof D.settings === 'object' ? D.settings : {};
    const keys = Object.keys(settings);
    const details = el('details', {class: 'settings', id: 'settings'},
                       el('summary', {text: 'How it was run (' + keys.length + ' settings)'}));
    const dl = el('dl', {class: 'settings-list'});
    for (const k of keys) {
      const v = settings[k];
      dl.append(el('dt', {text: k}),
                el('dd', {text: v === null ? DASH : typeof v === 'object' ? JSON.stringify(v) : String(v)}));
    }
    details.append(dl);
    header.append(details);
    header.append(el('nav', {class: 'toc'}, el('a', {href: '#summary', text: 'Summary'}),
                     el('a', {href: '#distributions', text: 'Distributions'}),
                     el('a', {href: '#maps', text: 'Maps and runs'})));
    main.append(header);
    // In-page links must not clobber #run=N handling: scroll instead of navigating.
    header.querySelector('nav').addEventListener('click', (e) => {
      const a = e.target.closest('a');
      if (!a) return;
      const target = document.getElementById(a.getAttribute('href').slice(1));
      if (target) {
        e.preventDefault();
        target.scrollIntoView({behavior: 'smooth', block: 'start'});
      }
    });
  }

  // ---------------------------------------------------------------- summary table

  const SUMMARY_COLUMNS = [
    {key: 'method', label: 'Method'},
    {key: 'map', label: 'Map'},
    {key: 'runs', label: 'Runs', num: true, show: count},
    {key: 'median_error_m', label: 'Median error', unit: 'm', num: true, show: (v) => fixed(v, 2),
     title: 'median distance from the estimate to the true source'},
    {key: 'mean_error_m', label: 'Mean error', unit: 'm', num: true, show: (v) => fixed(v, 2)},
    {key: 'success_0_5m', label: 'Within 0.5\u00a0m', num: true, ci: true,
     title: 'runs whose estimate is within 0.5 m of the source (95 % interval)'},
    {key: 'success_1_0m', label: 'Within 1\u00a0m', num: true, ci: true,
     title: 'runs whose estimate is within 1 m of the source (95 % interval)'},
    {key: 'median_samples', label: 'Samples', num: true, show: count, title: 'median stops'},
    {key: 'median_distance_m', label: 'Distance', unit: 'm', num: true, show: (v) => fixed(v, 1),
     title: 'median distance driven'},
    {key: 'median_mission_s', label: 'Mission', unit: 's', num: true, show: (v) => fixed(v, 1),
     title: 'median mission time'},
    {key: 'median_time_to_1m_s', label: 'Time to\u00a01\u00a0m', unit: 's', num: true, show: (v) => fixed(v, 1),
     title: 'median time until the estimate is within 1 m (of the runs that got there)'},
    {key: 'gsl_bench_success', label: 'GSL\u2011Bench', num: true, ci: true,
     title: 'GSL-Bench success: the robot ends within 0.5 m of the source (95 % interval)'},
  ];
  // A plume tracker's "reached the source" rate, when some method has one.
  const REACHED_KEYS = ['reached', 'reached_source_box'];

  function summaryField(s, key) {
    if (!s || typeof s !== 'object') return null;
    if (key === 'reached') {
      for (const k of REACHED_KEYS) if (isNum(s[k])) return {v: s[k], ci: s[k + '_ci95']};
      return null;
    }
    return {v: num(s[key]), ci: s[key + '_ci95']};
  }

  function buildSummary() {
    const sec = section('summary', 'Summary');
    const summaryRows = [];
    const mapNames = [];
    methods.forEach((m, mi) => {
      const s = m && m.summary && typeof m.summary === 'object' ? m.summary : {};
      summaryRows.push({mi, overall: true, map: 'all maps', s: s.overall || {}});
      for (const ms of Array.isArray(s.maps) ? s.maps : []) {
        if (!ms || typeof ms !== 'object') continue;
        const name = String(ms.map === undefined ? '?' : ms.map);
        if (!mapNames.includes(name)) mapNames.push(name);
        summaryRows.push({mi, overall: false, map: name, s: ms});
      }
    });
    const cols = SUMMARY_COLUMNS.slice();
    if (summaryRows.some((r) => summaryField(r.s, 'reached'))) {
      cols.push({key: 'reached', label: 'Reached', num: true, ci: true,
                 title: 'plume trackers: runs whose robot reached the source (95 % interval)'});
    }
    const filter = el('select', {id: 'summary-filter'});
    filter.append(el('option', {value: 'overall', text: 'Each method overall'}),
                  el('option', {value: 'all', text: 'Overall and every map'}));
    for (const name of mapNames) filter.append(el('option', {value: 'map:' + name, text: 'Map ' + name}));
    sec.append(el('div', {class: 'controls'}, el('label', null, 'Rows ', filter),
                  el('span', {class: 'hint', text: 'Click a column\u2019s header to sort by it.'})));

    const t = sortableTable({
      id: 'summary-table',
      className: 'summary',
      columns: cols,
      sortValue(rec, c) {
        if (c.key === 'method') return methodLabel(rec.mi);
        if (c.key === 'map') return rec.overall ? '' : rec.map;
        const f = summaryField(rec.s, c.key);
        return f ? f.v : null;
      },
      fill(td, rec, c) {
        if (c.key === 'method') {
          td.textContent = methodLabel(rec.mi);
          const m = methods[rec.mi];
          if (m && m.name) td.title = m.name;
          return;
        }
        if (c.key === 'map') {
          td.textContent = rec.map;
          return;
        }
        const f = summaryField(rec.s, c.key);
        if (c.ci) {
          td.textContent = percent(f ? f.v : null);
          const ci = f && Array.isArray(f.ci) ? f.ci : null;
          if (ci && isNum(ci[0]) && isNum(ci[1])) {
            td.append(el('span', {class: 'ci', text: ' (' + (ci[0] * 100).toFixed(0) + DASH +
                                                      (ci[1] * 100).toFixed(0) + ')'}));
          }
        } else {
          td.textContent = c.show(f ? f.v : null);
        }
      },
      setupRow(tr, rec) {
        if (rec.overall) tr.className = 'overall';
      },
    });
    sec.append(el('div', {class: 'table-wrap'}, t.table));
    function apply() {
      const v = filter.value;
      t.table.classList.toggle('mixed', v === 'all');
      t.setRecords(summaryRows.filter((r) => v === 'all' || (v === 'overall' ? r.overall
                                                                            : !r.overall && 'map:' + r.map === v)));
    }
    filter.addEventListener('change', apply);
    apply();
  }

  // ---------------------------------------------------------------- box plots

  const BOX_METRICS = [
    {key: 'error_m', label: 'Error', unit: 'm'},
    {key: 'samples', label: 'Samples', unit: 'stops'},
    {key: 'mission_s', label: 'Mission', unit: 's'},
  ];

  function boxStats(values) {
    const a = Float64Array.from(values, (v) => v[0]).sort();  // a typed array sorts numerically, fast
    const q1 = quantile(a, 0.25);
    const med = quantile(a, 0.5);
    const q3 = quantile(a, 0.75);
    const iqr = q3 - q1;
    let lo = a[0];
    let hi = a[a.length - 1];
    for (const v of a) if (v >= q1 - 1.5 * iqr) { lo = v; break; }
    for (let k = a.length - 1; k >= 0; --k) if (a[k] <= q3 + 1.5 * iqr) { hi = a[k]; break; }
    return {q1, med, q3, lo, hi, n: a.length, min: a[0], max: a[a.length - 1]};
  }

  function boxPlot(metric, mapFilter, allDots) {
    // Per method: [value, run index] of its runs (on the chosen map).
    const per = methods.map(() => []);
    for (let i = 0; i < rows.length; ++i) {
      const m = methodOf(i);
      if (m < 0 || m >= methods.length) continue;
      if (mapFilter >= 0 && mapOf(i) !== mapFilter) continue;
      const v = value(i, metric.key);
      if (isNum(v)) per[m].push([v, i]);
    }
    let max = 0;
    let min = 0;
    for (const vs of per) for (const v of vs) {
      max = Math.max(max, v[0]);
      min = Math.min(min, v[0]);
    }
    const {ticks, step} = niceTicks(min, max > min ? max : min + 1, 5);
    const lo = Math.min(min, ticks[0]);
    const hi = Math.max(ticks[ticks.length - 1], max);
    const labelWidth = Math.min(200, Math.max(70, 7 * Math.max(...methods.map((m, k) => methodLabel(k).length))));
    const W = 420;
    const rowH = 26;
    const top = 6;
    const plotW = W - labelWidth - 16;
    const H = top + rowH * Math.max(1, methods.length) + 38;
    const X = (v) => labelWidth + ((v - lo) / (hi - lo || 1)) * plotW;
    const root = svg('svg', {viewBox: '0 0 ' + W + ' ' + H, class: 'boxplot', role: 'img',
                             'aria-label': metric.label + ' per method'});
    const axisY = top + rowH * Math.max(1, methods.length);
    const grid = svg('g', {class: 'grid'});
    for (const t of ticks) {
      const x = X(t).toFixed(1);
      grid.append(svg('line', {x1: x, x2: x, y1: top, y2: axisY}));
      grid.append(svg('text', {x, y: axisY + 14, class: 'tick', text: tickLabel(t, step)}));
    }
    grid.append(svg('line', {class: 'axis', x1: labelWidth, x2: labelWidth + plotW, y1: axisY, y2: axisY}));
    grid.append(svg('text', {x: labelWidth + plotW / 2, y: axisY + 32, class: 'axis-label',
                             text: metric.label + ' (' + metric.unit + ')'}));
    root.append(grid);
    per.forEach((vs, m) => {
      const cy = top + rowH * m + rowH / 2;
      const g = svg('g', {class: 'box', 'data-method': m});
      g.append(svg('text', {x: labelWidth - 8, y: cy + 4, class: 'label', text: methodLabel(m)}));
      if (vs.length === 0) {
        g.append(svg('text', {x: labelWidth + 6, y: cy + 4, class: 'none', text: 'no runs'}));
        root.append(g);
        return;
      }
      const b = boxStats(vs);
      // Dots as markup, many at once; their tooltips are made when hovered.
      let dotsMarkup = '';
      for (const [v, i] of vs) {
        if (allDots) {
          dotsMarkup += '<circle class="dot all" cx="' + X(v).toFixed(1) + '" cy="' + (cy + jitter(i) * 7).toFixed(1) +
                        '" r="1.8" data-run="' + i + '"/>';
        } else if (v < b.lo || v > b.hi) {
          dotsMarkup += '<circle class="dot outlier" cx="' + X(v).toFixed(1) + '" cy="' + cy +
                        '" r="2.6" data-run="' + i + '"/>';
        }
      }
      const dotsGroup = svg('g', {class: 'dots'});
      if (allDots) {
        dotsGroup.innerHTML = dotsMarkup;
        g.append(dotsGroup);
      }
      g.append(svg('line', {class: 'whisker', x1: X(b.lo), x2: X(b.q1), y1: cy, y2: cy}));
      g.append(svg('line', {class: 'whisker', x1: X(b.q3), x2: X(b.hi), y1: cy, y2: cy}));
      g.append(svg('line', {class: 'whisker', x1: X(b.lo), x2: X(b.lo), y1: cy - 5, y2: cy + 5}));
      g.append(svg('line', {class: 'whisker', x1: X(b.hi), x2: X(b.hi), y1: cy - 5, y2: cy + 5}));
      g.append(svg('rect', {class: 'iqr', x: X(b.q1), y: cy - 8, width: Math.max(1, X(b.q3) - X(b.q1)), height: 16},
                   svg('title', {text: methodLabel(m) + ': median ' + short(b.med) + ', quartiles ' +
                                         short(b.q1) + DASH + short(b.q3) + ', ' + b.n + ' runs'})));
      g.append(svg('line', {class: 'median', x1: X(b.med), x2: X(b.med), y1: cy - 8, y2: cy + 8}));
      if (!allDots) {
        dotsGroup.innerHTML = dotsMarkup;
        g.append(dotsGroup);
      }
      root.append(g);
    });
    root.addEventListener('mouseover', (e) => {
      const dot = e.target.closest('circle[data-run]');
      if (!dot || dot.firstChild) return;
      const i = Number(dot.getAttribute('data-run'));
      dot.append(svg('title', {text: 'run ' + i + ': ' + short(value(i, metric.key)) + ' ' + metric.unit + ', ' +
                                     methodLabel(methodOf(i)) + ', ' + mapName(mapOf(i)) + ' (click to open)'}));
    });
    root.addEventListener('click', (e) => {
      const dot = e.target.closest('[data-run]');
      if (dot) openRun(Number(dot.getAttribute('data-run')));
    });
    return root;
  }

  function buildBoxPlots() {
    const sec = section('distributions', 'Distributions');
    const mapSel = el('select', {id: 'box-map'}, el('option', {value: '-1', text: 'All maps'}));
    maps.forEach((m, k) => mapSel.append(el('option', {value: String(k), text: mapName(k)})));
    const dots = el('input', {type: 'checkbox', id: 'box-dots'});
    sec.append(el('div', {class: 'controls'}, el('label', null, 'Map ', mapSel),
                  el('label', null, dots, ' every run as a dot'),
                  el('span', {class: 'hint', text: 'Boxes: quartiles and median; whiskers: 1.5 \u00d7 the ' +
                                                   'interquartile range; dots: runs beyond them (click one to open it).'})));
    const grid = el('div', {class: 'boxplots', id: 'boxplots'});
    sec.append(grid);
    function draw() {
      const figs = BOX_METRICS.map((metric) => {
        const fig = el('figure', {class: 'boxplot-figure', 'data-metric': metric.key},
                       el('figcaption', {text: metric.label + ' (' + metric.unit + ')'}));
        try {
          fig.append(boxPlot(metric, Number(mapSel.value), dots.checked));
        } catch (err) {
          failIn(fig, 'the box plot of ' + metric.label, err);
        }
        return fig;
      });
      grid.replaceChildren(...figs);
    }
    mapSel.addEventListener('change', draw);
    dots.addEventListener('change', draw);
    draw();
  }

  // ---------------------------------------------------------------- maps and their runs

  const RUN_COLUMNS = [
    {key: 'index', label: '#', num: true, title: 'the run\u2019s number in this report (#run=N links to it)'},
    {key: 'method', label: 'Method'},
    {key: 'source', label: 'Source', num: true},
    {key: 'run', label: 'Run', num: true},
    {key: 'seed', label: 'Seed', num: true},
    {key: 'error_m', label: 'Error', unit: 'm', num: true, show: (v) => fixed(v, 2)},
    {key: 'samples', label: 'Samples', num: true, show: count},
    {key: 'distance_m', label: 'Distance', unit: 'm', num: true, show: (v) => fixed(v, 1)},
    {key: 'mission_s', label: 'Mission', unit: 's', num: true, show: (v) => fixed(v, 1)},
    {key: 'stopped_by', label: 'Stopped by'},
    {key: 'replay', label: 'Replay', title: 'whether the run\u2019s replay was recorded'},
  ];

  function runSortValue(i, c) {
    switch (c.key) {
      case 'index': return i;
      case 'method': return methodLabel(methodOf(i));
      case 'replay': return replayOf(i) ? 'replay' : null;
      case 'stopped_by': {
        const v = value(i, 'stopped_by');
        return v === null || v === undefined ? null : String(v);
      }
      default: return num(value(i, c.key));
    }
  }

  function fillRunCell(td, i, c) {
    const v = runSortValue(i, c);
    if (c.key === 'index' || c.key === 'source' || c.key === 'run' || c.key === 'seed') td.textContent = isNum(v) ? String(v) : DASH;
    else if (c.show) td.textContent = c.show(v);
    else if (c.key === 'replay') td.textContent = v ? '\u25b6' : '';
    else td.textContent = v === null ? DASH : v;
  }

  let currentRun = -1;

  function markCurrent(tbody) {
    const old = tbody.querySelector('tr.current');
    if (old) old.classList.remove('current');
    if (currentRun >= 0) {
      const tr = tbody.querySelector('tr[data-run="' + currentRun + '"]');
      if (tr) tr.classList.add('current');
    }
  }

  const runTables = [];

  function runsTable(indices) {
    const t = sortableTable({
      className: 'runs',
      columns: RUN_COLUMNS,
      limit: 500,
      emptyText: 'No runs.',
      sortValue: runSortValue,
      fill: fillRunCell,
      setupRow(tr, i) {
        tr.dataset.run = String(i);
        tr.tabIndex = 0;
      },
      onRender: markCurrent,
    });
    t.tbody.addEventListener('click', (e) => {
      const tr = e.target.closest('tr[data-run]');
      if (tr) openRun(Number(tr.dataset.run));
    });
    t.tbody.addEventListener('keydown', (e) => {
      if (e.key !== 'Enter' && e.key !== ' ') return;
      const tr = e.target.closest('tr[data-run]');
      if (tr) {
        e.preventDefault();
        openRun(Number(tr.dataset.run));
      }
    });
    t.setRecords(indices);
    runTables.push(t);
    return t;
  }

  function mapPicture(map, onSource) {
    const ext = extendExtent(mapExtent(map), Array.isArray(map.sources) ? map.sources : []);
    const pr = projection(ext, 480, 10);
    const root = svg('svg', {class: 'map-svg', viewBox: '0 0 ' + pr.width + ' ' + pr.height.toFixed(1),
                             role: 'img', 'aria-label': 'map ' + (map.name || '')});
    const g = svg('g');
    drawMap(g, map, pr, ext);
    (Array.isArray(map.sources) ? map.sources : []).forEach((p, k) => {
      if (!Array.isArray(p) || !isNum(p[0]) || !isNum(p[1])) return;
      const x = pr.x(p[0]);
      const y = pr.y(p[1]);
      const s = svg('g', {class: 'map-source', 'data-source': k},
                    svg('circle', {cx: x.toFixed(1), cy: y.toFixed(1), r: 5}),
                    svg('text', {x: (x + 7).toFixed(1), y: (y + 4).toFixed(1), text: String(k)}),
                    svg('title', {text: 'source ' + k + ' ' + point(p[0], p[1]) + ': show its runs'}));
      g.append(s);
    });
    root.append(g);
    root.addEventListener('click', (e) => {
      const s = e.target.closest('[data-source]');
      if (s) onSource(Number(s.getAttribute('data-source')));
    });
    return root;
  }

  function buildMaps() {
    const sec = section('maps', 'Maps and runs');
    sec.append(el('p', {class: 'hint', text: 'Open a map to list its runs; click a run to see it.'}));
    const perMap = maps.map(() => []);
    const orphans = [];
    for (let i = 0; i < rows.length; ++i) {
      const m = mapOf(i);
      if (m >= 0 && m < maps.length) perMap[m].push(i);
      else orphans.push(i);
    }
    const list = el('div', {class: 'map-list', id: 'map-list'});
    sec.append(list);
    const groups = maps.map((map, k) => ({map: map || {}, k, runs: perMap[k]}));
    if (orphans.length) groups.push({map: {name: 'runs on maps not in the report'}, k: -1, runs: orphans});
    for (const grp of groups) {
      const map = grp.map;
      const bits = [];
      if (isNum(map.width) && isNum(map.height)) {
        bits.push(Number(map.width.toFixed(2)) + ' \u00d7 ' + Number(map.height.toFixed(2)) + ' m');
      }
      if (Array.isArray(map.obstacles)) bits.push(plural(map.obstacles.length, 'obstacle'));
      if (Array.isArray(map.sources)) bits.push(plural(map.sources.length, 'source'));
      bits.push(plural(grp.runs.length, 'run'));
      const details = el('details', {class: 'map-section', 'data-map': grp.k},
                         el('summary', null, el('span', {class: 'map-name', text: String(map.name || 'map ' + grp.k)}),
                            el('span', {class: 'meta', text: bits.join(' \u00b7 ')})));
      list.append(details);
      let built = false;
      details.addEventListener('toggle', () => {
        if (!details.open || built) return;
        built = true;
        const body = el('div', {class: 'map-body'});
        details.append(body);
        try {
          buildMapBody(body, grp);
        } catch (err) {
          failIn(body, 'this map\u2019s runs', err);
        }
      });
    }
  }

  function buildMapBody(body, grp) {
    const methodSel = el('select', {class: 'run-method'}, el('option', {value: '-1', text: 'All methods'}));
    methods.forEach((m, k) => methodSel.append(el('option', {value: String(k), text: methodLabel(k)})));
    const sourceSel = el('select', {class: 'run-source'}, el('option', {value: '-1', text: 'All sources'}));
    const sources = Array.isArray(grp.map.sources) ? grp.map.sources : [];
    sources.forEach((p, k) => sourceSel.append(el('option', {value: String(k),
                                                            text: 'Source ' + k + ' ' + point(p && p[0], p && p[1])})));
    const side = el('div', {class: 'map-side'});
    if (grp.k >= 0) {
      side.append(mapPicture(grp.map, (s) => {
        sourceSel.value = String(s);
        apply();
      }));
    }
    const t = runsTable([]);
    body.append(side, el('div', {class: 'map-runs'},
                         el('div', {class: 'controls'}, el('label', null, 'Method ', methodSel),
                            el('label', null, 'Source ', sourceSel),
                            el('span', {class: 'count'})),
                         el('div', {class: 'table-wrap'}, t.table)));
    const countEl = body.querySelector('.count');
    function apply() {
      const m = Number(methodSel.value);
      const s = Number(sourceSel.value);
      const picked = grp.runs.filter((i) => (m < 0 || methodOf(i) === m) && (s < 0 || value(i, 'source') === s));
      countEl.textContent = picked.length + ' of ' + grp.runs.length + ' runs';
      for (const c of side.querySelectorAll('.map-source')) {
        c.classList.toggle('picked', Number(c.getAttribute('data-source')) === s);
      }
      t.setRecords(picked);
    }
    methodSel.addEventListener('change', apply);
    sourceSel.addEventListener('change', apply);
    apply();
  }

  // ---------------------------------------------------------------- the run view

  const panel = el('aside', {class: 'run-view', id: 'run-view', role: 'dialog', 'aria-modal': 'false',
                             'aria-labelledby': 'run-title', tabindex: '-1', hidden: true});
  let player = null;
  let returnFocus = null;

  function buildPanel() {
    document.body.append(panel);
    document.addEventListener('keydown', (e) => {
      if (e.key === 'Escape' && !panel.hidden) {
        e.preventDefault();
        closeRun();
      }
    });
    window.addEventListener('hashchange', fromHash);
  }

  function runFromHash() {
    const m = /^#run=(\d+)$/.exec(location.hash);
    return m ? Number(m[1]) : -1;
  }

  function fromHash() {
    const i = runFromHash();
    if (i >= 0) {
      if (i !== currentRun) openRun(i, true);
    } else if (!panel.hidden && /^#?$/.test(location.hash)) {
      closeRun(true);
    }
  }

  // The stops' colour scale: log(1 + v / floor) from 0 to the run's top reading, floor a
  // thousandth of it, so that three decades show.
  function readingScale(top) {
    const t = isNum(top) && top > 0 ? top : 1;
    const floor = t / 1000;
    const f = (v) => (isNum(v) && v > 0 ? Math.min(1, Math.log1p(v / floor) / Math.log1p(t / floor)) : 0);
    return {top: t, floor, t: f, colour: (v) => (isNum(v) && v > 0 ? rgb(tableColour(GAS_TABLE, Math.max(f(v), 0.16)))
                                                              : '#ffffff')};
  }

  function openRun(i, fromHashChange) {
    if (!Number.isInteger(i) || i < 0 || i >= rows.length) {
      if (fromHashChange) showMissingRun(i);
      return;
    }
    if (panel.hidden) returnFocus = document.activeElement;
    if (player) player.destroy();
    player = null;
    currentRun = i;
    panel.dataset.run = String(i);
    try {
      renderRun(i);
    } catch (err) {
      failIn(panel, 'this run', err);
    }
    panel.hidden = false;
    panel.scrollTop = 0;
    document.body.classList.add('run-open');
    if (!fromHashChange && location.hash !== '#run=' + i) history.replaceState(null, '', '#run=' + i);
    for (const t of runTables) markCurrent(t.tbody);
    panel.focus({preventScroll: true});
  }

  function showMissingRun(i) {
    panel.replaceChildren(panelHead('No run ' + i), el('p', {class: 'error', text:
      'This report has runs 0 to ' + (rows.length - 1) + '; #run=' + i + ' is not one of them.'}));
    panel.dataset.run = '';
    panel.hidden = false;
  }

  function closeRun(fromHashChange) {
    if (player) player.destroy();
    player = null;
    panel.hidden = true;
    panel.replaceChildren();
    delete panel.dataset.run;
    currentRun = -1;
    document.body.classList.remove('run-open');
    for (const t of runTables) markCurrent(t.tbody);
    if (!fromHashChange && location.hash) history.replaceState(null, '', location.pathname + location.search);
    if (returnFocus && document.contains(returnFocus) && returnFocus !== document.body) {
      returnFocus.focus({preventScroll: true});
    }
    returnFocus = null;
  }

  function panelHead(title, i) {
    const head = el('div', {class: 'run-head'}, el('h2', {id: 'run-title', text: title}));
    const nav = el('div', {class: 'run-nav'});
    if (isNum(i)) {
      const prev = el('button', {type: 'button', class: 'prev', title: 'previous run', text: '\u2039',
                                 'aria-label': 'previous run', disabled: i <= 0});
      const next = el('button', {type: 'button', class: 'next', title: 'next run', text: '\u203a',
                                 'aria-label': 'next run', disabled: i >= rows.length - 1});
      prev.addEventListener('click', () => openRun(i - 1));
      next.addEventListener('click', () => openRun(i + 1));
      nav.append(prev, next);
    }
    const close = el('button', {type: 'button', class: 'close', title: 'close (Esc)', 'aria-label': 'close',
                                text: '\u00d7'});
    close.addEventListener('click', () => closeRun());
    nav.append(close);
    head.append(nav);
    return head;
  }

  function renderRun(i) {
    const mi = mapOf(i);
    const map = maps[mi] || null;
    panel.replaceChildren(panelHead('Run ' + i, i));
    panel.append(el('p', {class: 'run-sub', text: runName(i)}));
    const robots = trackOf(i) || [];
    const source = [num(value(i, 'source_x')), num(value(i, 'source_y'))];
    const start = [num(value(i, 'start_x')), num(value(i, 'start_y'))];
    const estimate = [num(value(i, 'estimate_x')), num(value(i, 'estimate_y'))];
    const pts = [source, start, estimate];
    let topReading = 0;
    for (const r of robots) {
      const path = Array.isArray(r && r.path) ? r.path : [];
      for (let k = 0; k + 1 < path.length; k += 2) pts.push([path[k], path[k + 1]]);
      const stops = Array.isArray(r && r.stops) ? r.stops : [];
      for (let k = 0; k + 3 < stops.length; k += 4) {
        pts.push([stops[k], stops[k + 1]]);
        if (isNum(stops[k + 2])) topReading = Math.max(topReading, stops[k + 2]);
      }
    }
    const ext = extendExtent(mapExtent(map), pts);
    const pr = projection(ext, 720, 14);
    const scale = readingScale(topReading);
    const root = svg('svg', {class: 'run-svg', viewBox: '0 0 ' + pr.width + ' ' + pr.height.toFixed(1),
                             role: 'img', 'aria-label': 'the run on its map'});
    const g = svg('g');
    drawMap(g, map, pr, ext);
    const haveSource = isNum(source[0]) && isNum(source[1]);
    const haveEstimate = isNum(estimate[0]) && isNum(estimate[1]);
    robots.forEach((r, k) => {
      const d = pathData(pr, Array.isArray(r && r.path) ? r.path : [], 2);
      if (d) {
        g.append(svg('path', {class: 'track', d, stroke: ROBOT_COLOURS[k % ROBOT_COLOURS.length],
                              'data-robot': k}));
      }
    });
    if (haveSource && haveEstimate) {
      g.append(svg('line', {class: 'error-line', x1: pr.x(estimate[0]), y1: pr.y(estimate[1]),
                            x2: pr.x(source[0]), y2: pr.y(source[1])}));
    }
    robots.forEach((r, k) => {
      const stops = Array.isArray(r && r.stops) ? r.stops : [];
      for (let s = 0; s + 3 < stops.length; s += 4) {
        const [x, y, v, t] = [stops[s], stops[s + 1], stops[s + 2], stops[s + 3]];
        if (!isNum(x) || !isNum(y)) continue;
        g.append(svg('circle', {class: 'stop', cx: pr.x(x).toFixed(1), cy: pr.y(y).toFixed(1), r: 5,
                                fill: scale.colour(v), stroke: ROBOT_COLOURS[k % ROBOT_COLOURS.length]},
                     svg('title', {text: 'reading ' + short(v) + (isNum(t) ? ' at ' + t.toFixed(1) + ' s' : '') +
                                           (robots.length > 1 ? ' (robot ' + (k + 1) + ')' : '')})));
      }
    });
    if (isNum(start[0]) && isNum(start[1])) {
      g.append(svg('circle', {class: 'start-marker', cx: pr.x(start[0]), cy: pr.y(start[1]), r: 6,
                              fill: START_COLOUR}, svg('title', {text: 'start ' + point(start[0], start[1])})));
    }
    if (haveEstimate) {
      const ex = pr.x(estimate[0]);
      const ey = pr.y(estimate[1]);
      g.append(cross(ex, ey, 7.5, {class: 'estimate-halo'}));
      g.append(cross(ex, ey, 7.5, {class: 'estimate-marker', stroke: ESTIMATE_COLOUR}));
      const err = num(value(i, 'error_m'));
      if (err !== null && haveSource) {
        const mx = (ex + pr.x(source[0])) / 2;
        const my = (ey + pr.y(source[1])) / 2;
        g.append(svg('text', {class: 'error-label', x: (mx + 8).toFixed(1), y: (my - 8).toFixed(1),
                              text: err.toFixed(2) + ' m'}));
      }
    }
    // The source on top: the estimate's arms still show past it when the two meet.
    if (haveSource) {
      g.append(svg('circle', {class: 'source-marker', cx: pr.x(source[0]), cy: pr.y(source[1]), r: 6,
                              fill: SOURCE_COLOUR}, svg('title', {text: 'source ' + point(source[0], source[1])})));
    }
    root.append(g);
    panel.append(el('div', {class: 'run-picture'}, root));
    panel.append(runLegend(robots.length, scale, topReading > 0));
    if (!robots.length) panel.append(el('p', {class: 'hint', text: 'No track was recorded for this run.'}));
    panel.append(runFigures(i, robots.length));
    const folder = replayOf(i);
    if (folder) {
      const box = el('section', {class: 'player', 'data-state': 'loading'});
      panel.append(box);
      player = makePlayer(box, folder);
    }
  }

  function swatch(kind, colour) {
    const s = svg('svg', {class: 'swatch', viewBox: '0 0 16 16', width: 16, height: 16, 'aria-hidden': 'true'});
    if (kind === 'line') s.append(svg('line', {x1: 1, y1: 8, x2: 15, y2: 8, stroke: colour, 'stroke-width': 2.5}));
    if (kind === 'dash') s.append(svg('line', {x1: 1, y1: 8, x2: 15, y2: 8, class: 'error-line'}));
    if (kind === 'dot') s.append(svg('circle', {cx: 8, cy: 8, r: 5, fill: colour, stroke: '#fff'}));
    if (kind === 'cross') s.append(cross(8, 8, 5, {stroke: colour, 'stroke-width': 2.2}));
    if (kind === 'stop') s.append(svg('circle', {cx: 8, cy: 8, r: 5, fill: '#fff', stroke: '#555'}));
    return s;
  }

  function colourBar(table, labels, title) {
    const bar = el('span', {class: 'colour-bar'});
    bar.append(el('span', {class: 'bar', style: 'background:' + gradientCss(table)}));
    const ticks = el('span', {class: 'bar-ticks'});
    for (const [t, text] of labels) ticks.append(el('span', {style: 'left:' + (100 * t).toFixed(1) + '%', text}));
    bar.append(ticks);
    return el('span', {class: 'legend-item', title}, bar);
  }

  function runLegend(nRobots, scale, haveReadings) {
    const lg = el('div', {class: 'legend'});
    const item = (sw, text) => el('span', {class: 'legend-item'}, sw, ' ' + text);
    if (nRobots === 1) lg.append(item(swatch('line', ROBOT_COLOURS[0]), 'path'));
    for (let k = 0; nRobots > 1 && k < nRobots; ++k) {
      lg.append(item(swatch('line', ROBOT_COLOURS[k % ROBOT_COLOURS.length]), 'robot ' + (k + 1)));
    }
    lg.append(item(swatch('dot', START_COLOUR), 'start'), item(swatch('dot', SOURCE_COLOUR), 'source'),
              item(swatch('cross', ESTIMATE_COLOUR), 'estimate'), item(swatch('dash'), 'error'));
    if (nRobots === 0) return lg;
    lg.append(item(swatch('stop'), 'stop, by its reading:'));
    if (haveReadings) {
      const labels = [[0, '0']];
      for (let d = Math.ceil(Math.log10(scale.floor * 10)); Math.pow(10, d) < scale.top; ++d) {
        const t = scale.t(Math.pow(10, d));
        if (t > 0.12 && t < 0.8) labels.push([t, short(Math.pow(10, d))]);
      }
      labels.push([1, short(scale.top)]);
      lg.append(colourBar(GAS_TABLE, labels, 'mean reading at a stop, log scale'));
    } else {
      lg.append(el('span', {class: 'hint', text: 'no readings above 0'}));
    }
    return lg;
  }

  function runFigures(i, nRobots) {
    const dl = el('dl', {class: 'figures'});
    const add = (k, v) => dl.append(el('dt', {text: k}), el('dd', {text: v}));
    const m = methods[methodOf(i)];
    add('Method', methodLabel(methodOf(i)) + (m && m.name && m.name !== m.label ? ' (' + m.name + ')' : ''));
    add('Map', mapName(mapOf(i)));
    const s = value(i, 'source');
    add('Source', (isNum(s) ? s + ' ' : '') + point(value(i, 'source_x'), value(i, 'source_y')));
    add('Run', isNum(value(i, 'run')) ? String(value(i, 'run')) : DASH);
    add('Seed', isNum(value(i, 'seed')) ? String(value(i, 'seed')) : DASH);
    const unit = (text, u) => (text === DASH ? DASH : text + ' ' + u);
    add('Error', unit(fixed(value(i, 'error_m'), 3), 'm'));
    add('Samples', count(value(i, 'samples')));
    add('Distance', unit(fixed(value(i, 'distance_m'), 2), 'm'));
    add('Mission', unit(fixed(value(i, 'mission_s'), 1), 's'));
    const sb = value(i, 'stopped_by');
    add('Stopped by', sb === null || sb === undefined ? DASH : String(sb));
    add('Start', point(value(i, 'start_x'), value(i, 'start_y')));
    add('Estimate', point(value(i, 'estimate_x'), value(i, 'estimate_y')));
    if (nRobots > 1) add('Robots', String(nRobots));
    dl.append(el('dt', {text: 'Link'}), el('dd', null, el('a', {href: '#run=' + i, text: '#run=' + i})));
    return dl;
  }

  // ---------------------------------------------------------------- the replay player

  let pendingReplay = null;
  const replayCache = new Map();
  window.plumekitReplay = function (obj) {
    pendingReplay = obj;
  };

  function folderUrl(folder) {
    return folder.split('/').filter((p) => p !== '' && p !== '.').map(encodeURIComponent).join('/');
  }

  // Loads <folder>/replay.js, which calls plumekitReplay({...}); a script's load event follows
  // its execution at once, so the object that arrived is this script's.
  function loadReplay(folder) {
    if (replayCache.has(folder)) return replayCache.get(folder);
    const src = folderUrl(folder) + '/replay.js';
    const p = new Promise((resolve, reject) => {
      const s = document.createElement('script');
      s.src = src;
      s.onload = () => {
        const obj = pendingReplay;
        pendingReplay = null;
        s.remove();
        if (obj && typeof obj === 'object') resolve(obj);
        else reject(new Error(src + ' did not hand over a replay'));
      };
      s.onerror = () => {
        s.remove();
        reject(new Error('cannot load ' + src + ' (is the report beside its replays folder?)'));
      };
      document.head.append(s);
    });
    p.catch(() => replayCache.delete(folder));
    replayCache.set(folder, p);
    return p;
  }

  function loadImage(url) {
    return new Promise((resolve, reject) => {
      const img = new Image();
      img.onload = () => resolve(img);
      img.onerror = () => reject(new Error('cannot load ' + url));
      img.src = url;
    });
  }

  function installFilters() {
    const table = (rows, k) => rows.map((c) => (c[k] / 255).toFixed(4)).join(' ');
    const filter = (id, rows) => svg('filter', {id, 'color-interpolation-filters': 'sRGB', x: 0, y: 0,
                                                width: 1, height: 1},
                                     svg('feComponentTransfer', null,
                                         svg('feFuncR', {type: 'table', tableValues: table(rows, 0)}),
                                         svg('feFuncG', {type: 'table', tableValues: table(rows, 1)}),
                                         svg('feFuncB', {type: 'table', tableValues: table(rows, 2)})));
    const defs = svg('svg', {class: 'filters', width: 0, height: 0, 'aria-hidden': 'true', focusable: 'false'},
                     filter(GAS_FILTER_ID, GAS_TABLE), filter(BELIEF_FILTER_ID, BELIEF_TABLE));
    document.body.append(defs);
  }

  function arr2(p) {
    return Array.isArray(p) && isNum(p[0]) && isNum(p[1]) ? p : null;
  }

  // A tunnel's point [x, y, z] as the side view draws it: (x, z).
  function arrXZ(p) {
    return Array.isArray(p) && isNum(p[0]) && isNum(p[2]) ? [p[0], p[2]] : null;
  }

  // Checks the fields the player uses; throws naming what is wrong.
  function checkReplay(rp) {
    if (rp.format !== undefined && rp.format !== 'plumekit-replay/1') {
      throw new Error('unknown replay format ' + JSON.stringify(rp.format));
    }
    if (!Array.isArray(rp.positions) || rp.positions.length === 0) throw new Error('replay has no positions');
    const g = rp.plume && rp.plume.grid;
    if (!g || !(g.nx > 0) || !(g.ny > 0)) throw new Error('replay has no plume grid');
    if (!rp.map || !Array.isArray(rp.map.size)) throw new Error('replay has no map');
    if (rp.side !== undefined) {
      if (!rp.side || !(rp.side.height > 0)) throw new Error('replay\u2019s side has no height');
      const sg = rp.side.plume && rp.side.plume.grid;
      if (!sg || !(sg.nx > 0) || !(sg.ny > 0)) throw new Error('replay\u2019s side has no plume grid');
    }
  }

  function makePlayer(box, folder) {
    let destroyed = false;
    let timer = null;
    let observer = null;
    const status = el('p', {class: 'player-status', text: 'Loading the replay\u2026'});
    box.append(el('h3', {text: 'Replay'}), status);
    const fail = (err) => {
      if (destroyed) return;
      box.dataset.state = 'error';
      status.textContent = 'The replay could not be shown: ' + (err && err.message ? err.message : String(err));
      status.classList.add('error');
    };
    loadReplay(folder).then((rp) => {
      if (destroyed) return null;
      checkReplay(rp);
      const base = folderUrl(folder) + '/';
      const beliefSteps = rp.belief && Array.isArray(rp.belief.steps) ? rp.belief.steps : [];
      const bg = rp.belief && rp.belief.grid;
      const withBelief = beliefSteps.length > 0 && bg && bg.nx > 0 && bg.ny > 0;
      // A tunnel's replay has strips of the side too; its belief's only where the top one is.
      const side = rp.side || null;
      const sbg = side && side.belief && side.belief.grid;
      const withSideBelief = withBelief && sbg && sbg.nx > 0 && sbg.ny > 0;
      return Promise.all([loadImage(base + encodeURIComponent(rp.plume.file || 'replay-plume.png')),
                          withBelief ? loadImage(base + encodeURIComponent(rp.belief.file || 'replay-belief.png'))
                                     : Promise.resolve(null),
                          side ? loadImage(base + encodeURIComponent(side.plume.file || 'replay-plume-side.png'))
                               : Promise.resolve(null),
                          withSideBelief ? loadImage(base + encodeURIComponent(side.belief.file ||
                                                                               'replay-belief-side.png'))
                                         : Promise.resolve(null)])
        .then(([plumeImg, beliefImg, sidePlumeImg, sideBeliefImg]) => {
          if (!destroyed) build(rp, plumeImg, beliefImg, sidePlumeImg, sideBeliefImg);
        });
    }).catch(fail);

    function build(rp, plumeImg, beliefImg, sidePlumeImg, sideBeliefImg) {
      box.dataset.state = 'ready';
      status.remove();
      const nRobots = Math.max(1, rp.robots | 0);
      const every = isNum(rp.every_s) && rp.every_s > 0 ? rp.every_s : 1;
      const frames = rp.positions.length;
      const pg = rp.plume.grid;
      const bgd = rp.belief && rp.belief.grid;
      const steps = beliefImg ? rp.belief.steps : [];
      const stops = (Array.isArray(rp.stops) ? rp.stops : []).filter((s) => s && arr2(s.position));
      const readings = rp.readings && Array.isArray(rp.readings.rows) ? rp.readings.rows : [];
      const rc = rp.readings && Array.isArray(rp.readings.columns) ? rp.readings.columns : [];
      const rcol = {robot: rc.indexOf('robot'), t: rc.indexOf('time_s'), p: rc.indexOf('position'), v: rc.indexOf('value')};
      const origin = rp.map.frame && arr2(rp.map.frame.origin) ? rp.map.frame.origin : [0, 0];
      const W = Number(rp.map.size[0]);
      const H = Number(rp.map.size[1]);
      const ext = {x0: origin[0], y0: origin[1], x1: origin[0] + W, y1: origin[1] + H};
      const obstacles = Array.isArray(rp.map.obstacles) ? rp.map.obstacles : [];
      const source = arr2(rp.source);
      const hasEstimate = rp.has_estimate !== false;
      const endT = Math.max(isNum(rp.ended_s) ? rp.ended_s : 0, (frames - 1) * every);
      const floor = isNum(rp.plume.floor) && rp.plume.floor > 0 ? rp.plume.floor : 5;
      const top = isNum(rp.plume.top) && rp.plume.top > 0 ? rp.plume.top : 1;
      const level = (c) => (isNum(c) && c > 0 ? Math.min(1, Math.log1p(c / floor) / Math.log1p(top / floor)) : 0);
      const concentration = (q) => floor * (Math.pow(1 + top / floor, q) - 1);
      const stopColour = (v) => (isNum(v) && v > 0 ? rgb(tableColour(GAS_TABLE, Math.max(level(v), 40 / 255)))
                                                  : '#ffffff');
      // The planes the views draw: from above (x, y) and, in a tunnel's replay, from the side (x, z)
      // up to the tunnel's height, over the same x as from above so that the two line up.
      const side = sidePlumeImg ? rp.side : null;
      const fromAbove = {ext, at: arr2, obstacles, readings: false};
      // From the side the readings on the way that met gas show at what height it was met (those of
      // none would only cover the way).
      const fromSide = side ? {ext: {x0: ext.x0, y0: 0, x1: ext.x1, y1: side.height}, at: arrXZ, obstacles: [],
                               readings: true} : null;
      const readingColours = side && rcol.v >= 0 ? readings.map((r) => stopColour(r[rcol.v])) : [];

      const wide = W / H > 1.6 || !beliefImg;
      const views = el('div', {class: 'player-views' + (wide ? ' stacked' : '')});
      const worldCanvas = el('canvas', {class: 'world', role: 'img', 'aria-label': 'the gas and the robots'});
      const beliefCanvas = el('canvas', {class: 'belief', role: 'img', 'aria-label': 'the method\u2019s belief'});
      for (const c of [worldCanvas, beliefCanvas]) c.style.aspectRatio = (W + 0.4) + ' / ' + (H + 0.4);
      const sideWorldCanvas = side ? el('canvas', {class: 'world-side', role: 'img',
                                                   'aria-label': 'the gas and the robots from the side'}) : null;
      const sideBeliefCanvas = sideBeliefImg ? el('canvas', {class: 'belief-side', role: 'img',
                                                             'aria-label': 'the method\u2019s belief from the side'})
                                             : null;
      for (const c of [sideWorldCanvas, sideBeliefCanvas]) {
        if (c) c.style.aspectRatio = (W + 0.4) + ' / ' + (side.height + 0.4);
      }
      // A tunnel's views say which plane they show; a 2-D replay's need no label.
      const label = (text) => (side ? el('div', {class: 'view-label', text}) : null);
      const planeAt = (axis, v) => (isNum(v) ? ' at ' + axis + ' = ' + v.toFixed(2) + ' m' : '');
      views.append(el('figure', null,
                      label('from above (x, y)' + planeAt('z', side && side.plane_z)), worldCanvas,
                      label('from the side (x, z)' + planeAt('y', side && side.plane_y)), sideWorldCanvas,
                      el('figcaption', {text: 'Gas (log scale) and robots' +
                                              (beliefImg ? '' : '; this method holds no belief')})));
      if (beliefImg) {
        views.append(el('figure', null,
                        label('from above: the (x, y) marginal'), beliefCanvas,
                        sideBeliefImg ? label('from the side: the (x, z) marginal') : null, sideBeliefCanvas,
                        el('figcaption', {text: 'The method\u2019s belief'})));
      }
      const play = el('button', {type: 'button', class: 'play', 'aria-label': 'play', text: '\u25b6'});
      const slider = el('input', {type: 'range', class: 'slider', min: 0, max: frames - 1, step: 1, value: 0,
                                  'aria-label': 'time'});
      const clock = el('span', {class: 'clock'});
      const speed = el('select', {class: 'speed', 'aria-label': 'frames a second'});
      for (const fps of [2, 5, 10, 20, 40]) {
        speed.append(el('option', {value: String(fps), text: fps + ' frames/s', selected: fps === 10}));
      }
      const controls = el('div', {class: 'player-controls'}, play, slider, clock, speed);
      const timeline = readingsTimeline();
      const legend = el('div', {class: 'legend'},
                        colourBar(GAS_TABLE, [[0, '0'], [0.5, short(concentration(0.5))], [1, short(top)]],
                                  'gas concentration, log scale'),
                        el('span', {class: 'legend-item', text: 'gas'}),
                        beliefImg ? colourBar(BELIEF_TABLE, [[0, '0'], [1, 'peak']], 'belief, square-root scale') : null,
                        beliefImg ? el('span', {class: 'legend-item', text: 'belief'}) : null);
      box.append(controls, views, timeline.node, legend);

      let frame = -1;
      function pxFor(canvas, plane) {
        const w = Math.max(50, Math.round(canvas.clientWidth * (window.devicePixelRatio || 1)));
        const pad = 0.2;
        const e = plane.ext;
        const pe = {x0: e.x0 - pad, y0: e.y0 - pad, x1: e.x1 + pad, y1: e.y1 + pad};
        const pr = projection(pe, w, 0);
        const h = Math.round(pr.height);
        if (canvas.width !== w || canvas.height !== h) {
          canvas.width = w;
          canvas.height = h;
        }
        return pr;
      }
      function drawObstacles(ctx, pr, plane) {
        ctx.fillStyle = '#6b7178';
        for (const poly of plane.obstacles) {
          if (!Array.isArray(poly) || poly.length < 3) continue;
          ctx.beginPath();
          poly.forEach((p, k) => {
            if (!arr2(p)) return;
            if (k === 0) ctx.moveTo(pr.x(p[0]), pr.y(p[1]));
            else ctx.lineTo(pr.x(p[0]), pr.y(p[1]));
          });
          ctx.closePath();
          ctx.fill();
        }
        ctx.strokeStyle = '#30343a';
        ctx.lineWidth = Math.max(1, pr.s * 0.03);
        const e = plane.ext;
        ctx.strokeRect(pr.x(e.x0), pr.y(e.y1), (e.x1 - e.x0) * pr.s, (e.y1 - e.y0) * pr.s);
      }
      // Frame k of a film strip over the plane; none where the strip ends before it.
      function drawGrid(ctx, pr, plane, img, k, ny, nx, filterId) {
        if (k < 0 || k >= Math.floor(img.naturalHeight / ny)) return;
        const e = plane.ext;
        ctx.save();
        ctx.filter = 'url(#' + filterId + ')';
        ctx.imageSmoothingEnabled = true;
        ctx.drawImage(img, 0, k * ny, nx, ny, pr.x(e.x0), pr.y(e.y1), (e.x1 - e.x0) * pr.s, (e.y1 - e.y0) * pr.s);
        ctx.restore();
      }
      function dot(ctx, x, y, r, fill, stroke, lw) {
        ctx.beginPath();
        ctx.arc(x, y, r, 0, 2 * Math.PI);
        ctx.fillStyle = fill;
        ctx.fill();
        if (stroke) {
          ctx.lineWidth = lw;
          ctx.strokeStyle = stroke;
          ctx.stroke();
        }
      }
      function xmark(ctx, x, y, r, colour, lw) {
        ctx.beginPath();
        ctx.moveTo(x - r, y - r);
        ctx.lineTo(x + r, y + r);
        ctx.moveTo(x - r, y + r);
        ctx.lineTo(x + r, y - r);
        ctx.lineWidth = lw;
        ctx.strokeStyle = colour;
        ctx.lineCap = 'round';
        ctx.stroke();
      }
      function estimateAt(t) {
        let e = null;
        for (const s of stops) if (isNum(s.time_s) && s.time_s <= t && arr2(s.estimate)) e = s.estimate;
        if (isNum(rp.declared_s) && t >= rp.declared_s && arr2(rp.estimate)) e = rp.estimate;
        return e;
      }
      function markers(ctx, pr, plane, t, u) {
        const e = hasEstimate ? estimateAt(t) : null;
        const ep = e && plane.at(e);
        if (ep) {
          xmark(ctx, pr.x(ep[0]), pr.y(ep[1]), 7 * u, 'rgba(255,255,255,0.85)', 5 * u);
          xmark(ctx, pr.x(ep[0]), pr.y(ep[1]), 7 * u, ESTIMATE_COLOUR, 2.4 * u);
        }
        const sp = plane.at(rp.source);
        if (sp) dot(ctx, pr.x(sp[0]), pr.y(sp[1]), 5.5 * u, SOURCE_COLOUR, '#fff', 1.5 * u);
      }
      function drawWorld(canvas, plane, img, grid, k, t) {
        const pr = pxFor(canvas, plane);
        const u = window.devicePixelRatio || 1;
        const ctx = canvas.getContext('2d');
        ctx.fillStyle = '#ffffff';
        ctx.fillRect(0, 0, canvas.width, canvas.height);
        drawGrid(ctx, pr, plane, img, k, grid.ny, grid.nx, GAS_FILTER_ID);
        drawObstacles(ctx, pr, plane);
        ctx.lineJoin = 'round';
        for (let r = 0; r < nRobots; ++r) {
          ctx.beginPath();
          let started = false;
          for (let f = 0; f <= k; ++f) {
            const p = plane.at(rp.positions[f] && rp.positions[f][r]);
            if (!p) continue;
            if (started) ctx.lineTo(pr.x(p[0]), pr.y(p[1]));
            else ctx.moveTo(pr.x(p[0]), pr.y(p[1]));
            started = true;
          }
          ctx.lineWidth = 2 * u;
          ctx.strokeStyle = ROBOT_COLOURS[r % ROBOT_COLOURS.length];
          ctx.globalAlpha = 0.85;
          ctx.stroke();
          ctx.globalAlpha = 1;
        }
        if (plane.readings && rcol.t >= 0 && rcol.p >= 0 && rcol.v >= 0) {
          readings.forEach((r, i) => {
            const p = isNum(r[rcol.t]) && r[rcol.t] <= t && r[rcol.v] > 0 ? plane.at(r[rcol.p]) : null;
            if (p) dot(ctx, pr.x(p[0]), pr.y(p[1]), 1.6 * u, readingColours[i] || '#999');
          });
        }
        for (const s of stops) {
          const p = isNum(s.time_s) && s.time_s <= t ? plane.at(s.position) : null;
          if (!p) continue;
          dot(ctx, pr.x(p[0]), pr.y(p[1]), 4.5 * u, stopColour(s.value),
              ROBOT_COLOURS[(s.robot | 0) % ROBOT_COLOURS.length], 1.5 * u);
        }
        markers(ctx, pr, plane, t, u);
        for (let r = 0; r < nRobots; ++r) {
          const p = plane.at(rp.positions[k] && rp.positions[k][r]);
          if (p) dot(ctx, pr.x(p[0]), pr.y(p[1]), 6 * u, ROBOT_COLOURS[r % ROBOT_COLOURS.length], '#fff', 2 * u);
        }
      }
      // The belief after the latest decision by t; from the side its frame of the same index.
      function drawBelief(canvas, plane, img, grid, k, t) {
        const pr = pxFor(canvas, plane);
        const u = window.devicePixelRatio || 1;
        const ctx = canvas.getContext('2d');
        ctx.fillStyle = '#ffffff';
        ctx.fillRect(0, 0, canvas.width, canvas.height);
        let j = -1;
        for (let s = 0; s < steps.length; ++s) if (isNum(steps[s].time_s) && steps[s].time_s <= t + 1e-9) j = s;
        drawGrid(ctx, pr, plane, img, j, grid.ny, grid.nx, BELIEF_FILTER_ID);
        drawObstacles(ctx, pr, plane);
        markers(ctx, pr, plane, t, u);
        for (let r = 0; r < nRobots; ++r) {
          const p = plane.at(rp.positions[k] && rp.positions[k][r]);
          if (p) dot(ctx, pr.x(p[0]), pr.y(p[1]), 4 * u, ROBOT_COLOURS[r % ROBOT_COLOURS.length], '#fff', 1.5 * u);
        }
        if (j < 0) {
          ctx.fillStyle = '#555';
          ctx.font = Math.round(13 * u) + 'px system-ui, sans-serif';
          ctx.textAlign = 'center';
          ctx.fillText('no decision yet', canvas.width / 2, canvas.height / 2);
        }
      }
      function readingsTimeline() {
        const TW = 640;
        const TH = 96;
        const L = 40;
        const R = 8;
        const T = 6;
        const B = 20;
        let vmax = 0;
        for (const s of stops) if (isNum(s.value)) vmax = Math.max(vmax, s.value);
        for (const r of readings) if (isNum(r[rcol.v])) vmax = Math.max(vmax, r[rcol.v]);
        const yt = (v) => (isNum(v) && v > 0 ? Math.log1p(v / floor) / Math.log1p(Math.max(vmax, floor) / floor) : 0);
        const X = (t) => L + (Math.max(0, t) / (endT || 1)) * (TW - L - R);
        const Y = (v) => T + (1 - yt(v)) * (TH - T - B);
        const root = svg('svg', {class: 'timeline', viewBox: '0 0 ' + TW + ' ' + TH, role: 'img',
                                 'aria-label': 'readings over time'});
        root.append(svg('rect', {class: 'plot', x: L, y: T, width: TW - L - R, height: TH - T - B}));
        const {ticks, step} = niceTicks(0, endT || 1, 8);
        for (const t of ticks) {
          root.append(svg('text', {class: 'tick', x: X(t), y: TH - 6, text: tickLabel(t, step)}));
        }
        root.append(svg('text', {class: 'tick y', x: L - 4, y: T + 9, text: short(vmax)}),
                    svg('text', {class: 'tick y', x: L - 4, y: TH - B, text: '0'}));
        const grey = svg('g', {class: 'readings'});
        if (rcol.t >= 0 && rcol.v >= 0) {
          for (const r of readings) {
            if (!isNum(r[rcol.t])) continue;
            grey.append(svg('circle', {cx: X(r[rcol.t]).toFixed(1), cy: Y(r[rcol.v]).toFixed(1), r: 1.2}));
          }
        }
        root.append(grey);
        for (const s of stops) {
          if (!isNum(s.time_s)) continue;
          root.append(svg('circle', {class: 'stop', cx: X(s.time_s).toFixed(1), cy: Y(s.value).toFixed(1), r: 3.5,
                                     fill: stopColour(s.value), stroke: ROBOT_COLOURS[(s.robot | 0) % ROBOT_COLOURS.length]}));
        }
        if (isNum(rp.declared_s) && rp.stopped_by) {
          root.append(svg('line', {class: 'declared', x1: X(rp.declared_s), x2: X(rp.declared_s), y1: T, y2: TH - B},
                          svg('title', {text: 'declared at ' + rp.declared_s.toFixed(1) + ' s (' + rp.stopped_by + ')'})));
        }
        const cursor = svg('line', {class: 'cursor', x1: L, x2: L, y1: T, y2: TH - B});
        root.append(cursor);
        root.addEventListener('click', (e) => {
          const box2 = root.getBoundingClientRect();
          const x = ((e.clientX - box2.left) / box2.width) * TW;
          const t = ((x - L) / (TW - L - R)) * endT;
          pause();
          show(Math.round(Math.min(frames - 1, Math.max(0, t / every))));
        });
        return {node: el('figure', {class: 'timeline-figure'}, root,
                         el('figcaption', {text: 'Readings over time (s), log scale: each stop\u2019s mean as a dot, the readings on the way grey; ' +
                                       'click to jump'})),
                setTime(t) {
                  cursor.setAttribute('x1', X(t).toFixed(1));
                  cursor.setAttribute('x2', X(t).toFixed(1));
                }};
      }
      function show(k) {
        frame = Math.max(0, Math.min(frames - 1, k));
        const t = frame * every;
        drawWorld(worldCanvas, fromAbove, plumeImg, pg, frame, t);
        if (side) drawWorld(sideWorldCanvas, fromSide, sidePlumeImg, side.plume.grid, frame, t);
        if (beliefImg) drawBelief(beliefCanvas, fromAbove, beliefImg, bgd, frame, t);
        if (sideBeliefImg) drawBelief(sideBeliefCanvas, fromSide, sideBeliefImg, side.belief.grid, frame, t);
        timeline.setTime(t);
        slider.value = String(frame);
        box.dataset.frame = String(frame);
        const nStops = stops.filter((s) => isNum(s.time_s) && s.time_s <= t).length;
        const e = hasEstimate ? estimateAt(t) : null;
        let text = 't = ' + t.toFixed(0) + ' s of ' + endT.toFixed(0) + ' s \u00b7 ' + nStops +
                   (nStops === 1 ? ' stop' : ' stops');
        if (e && source) {
          // In the tunnel the error is in 3-D, as the run's.
          const dz = side && isNum(e[2]) && isNum(rp.source[2]) ? e[2] - rp.source[2] : 0;
          text += ' \u00b7 error ' + Math.hypot(e[0] - source[0], e[1] - source[1], dz).toFixed(2) + ' m';
        }
        if (isNum(rp.declared_s) && t >= rp.declared_s && rp.stopped_by) text += ' \u00b7 ' + rp.stopped_by;
        clock.textContent = text;
      }
      function pause() {
        if (timer !== null) clearInterval(timer);
        timer = null;
        play.textContent = '\u25b6';
        play.setAttribute('aria-label', 'play');
        box.dataset.playing = '0';
      }
      function start() {
        if (frame >= frames - 1) show(0);
        pause();
        play.textContent = '\u275a\u275a';
        play.setAttribute('aria-label', 'pause');
        box.dataset.playing = '1';
        timer = setInterval(() => {
          if (frame >= frames - 1) pause();
          else show(frame + 1);
        }, 1000 / Number(speed.value));
      }
      play.addEventListener('click', () => (timer === null ? start() : pause()));
      speed.addEventListener('change', () => {
        if (timer !== null) start();
      });
      slider.addEventListener('input', () => {
        pause();
        show(Number(slider.value));
      });
      let queued = false;
      observer = new ResizeObserver(() => {
        if (queued) return;
        queued = true;
        requestAnimationFrame(() => {
          queued = false;
          if (!destroyed && frame >= 0) show(frame);
        });
      });
      observer.observe(views);
      show(0);
    }

    return {
      destroy() {
        destroyed = true;
        if (timer !== null) clearInterval(timer);
        timer = null;
        if (observer) observer.disconnect();
      },
    };
  }

  // ---------------------------------------------------------------- go

  function guarded(what, build) {
    try {
      build();
    } catch (err) {
      failIn(main, what, err);
    }
  }

  guarded('the header', buildHeader);
  guarded('the summary', buildSummary);
  guarded('the box plots', buildBoxPlots);
  guarded('the maps', buildMaps);
  installFilters();
  buildPanel();
  if (runFromHash() >= 0) fromHash();
  document.body.dataset.ready = '1';
})();
