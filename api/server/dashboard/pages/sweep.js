// A sweep: heat maps of the UCT and BTT peak loads and their ratio over (F_r0, F_s0), with the
// targets' iso-lines when the user gives targets (kept in the URL: ?uct=..&btt=..), and the jobs
// table. Model units throughout (a sweep has no lab scaling).
import {h, note} from '../dom.js';
import {num} from '../format.js';
import {heatMap} from '../plot/heat_map.js';
import {plotWidth} from './layout.js';
import {fetchResults, resultsTable} from './results.js';

const sortNum = (a, b) => a - b;

// rows -> {xs, ys, tests, at(test, ix, iy) -> {mean, n, rows}}
function sweepGrid(rows) {
  const xs = [...new Set(rows.map((r) => r.fr0))].sort(sortNum);
  const ys = [...new Set(rows.map((r) => r.fs0))].sort(sortNum);
  const tests = [...new Set(rows.map((r) => r.test))];
  const cells = new Map();
  for (const r of rows) {
    const k = `${r.test}|${xs.indexOf(r.fr0)}|${ys.indexOf(r.fs0)}`;
    if (!cells.has(k)) cells.set(k, []);
    cells.get(k).push(r);
  }
  const at = (test, ix, iy) => {
    const list = cells.get(`${test}|${ix}|${iy}`) || [];
    const loads = list.filter((r) => r.state === 'succeeded' && Number.isFinite(r.peak_load)).map((r) => r.peak_load);
    const n = loads.length;
    const mean = n ? loads.reduce((a, b) => a + b, 0) / n : null;
    // Several realisations (packing seeds) of a point: their standard error, sd over n - 1.
    const se = n >= 2 ? Math.sqrt(loads.reduce((a, b) => a + (b - mean) ** 2, 0) / (n - 1) / n) : null;
    return {mean, se, n, rows: list};
  };
  return {xs, ys, tests, at};
}

function field(grid, f) {
  return grid.ys.map((_, iy) => grid.xs.map((_, ix) => f(ix, iy)));
}

function missingNote(rows) {
  if (rows.length === 0) return 'not swept';
  const states = [...new Set(rows.map((r) => r.state))];
  return states.join('/');
}

function targetForm(ctx, targets, redraw) {
  const input = (name, label, value) => h('label', {}, label, ' ',
    h('input', {type: 'number', name, min: 0, step: 'any', value: value ?? '', inputmode: 'decimal', size: 10}), ' N');
  const form = h('form', {class: 'inline-form', id: 'targets'},
    h('strong', {}, 'Target peak loads (model units): '),
    input('uct', 'UCT', targets.uct), ' ', input('btt', 'BTT', targets.btt), ' ',
    h('button', {type: 'submit'}, 'Draw iso-lines'), ' ',
    h('button', {type: 'button', class: 'link', onclick: () => {
      ctx.setQuery({uct: null, btt: null});
      redraw();
    }}, 'clear'));
  form.addEventListener('submit', (e) => {
    e.preventDefault();
    const v = (n) => {
      const x = parseFloat(form.elements[n].value);
      return Number.isFinite(x) && x > 0 ? String(x) : null;
    };
    ctx.setQuery({uct: v('uct'), btt: v('btt')});
    redraw();
  });
  return form;
}

export async function renderSweep(c, ctx) {
  const rows = await fetchResults(c, ctx);
  const view = h('div', {class: 'sweep'});
  const draw = () => {
    view.replaceChildren(...sweepView(c, rows, ctx, draw));
  };
  draw();
  return view;
}

function sweepView(c, rows, ctx, redraw) {
  const grid = sweepGrid(rows);
  const q = new URLSearchParams(location.search);
  const targets = {uct: parseFloat(q.get('uct')) || null, btt: parseFloat(q.get('btt')) || null};
  const out = [targetForm(ctx, targets, redraw)];
  const has = (t) => grid.tests.includes(t);
  if (!has('uct') && !has('btt')) {
    out.push(note('This sweep has no UCT or BTT jobs: the maps show peak loads of those two tests.'));
  } else if (grid.xs.length < 2 || grid.ys.length < 2) {
    out.push(note('The sweep varies only one strength: a map needs at least two values of each; see the table.'));
  } else {
    const uct = field(grid, (ix, iy) => grid.at('uct', ix, iy).mean);
    const btt = field(grid, (ix, iy) => grid.at('btt', ix, iy).mean);
    const ratio = field(grid, (ix, iy) => (uct[iy][ix] > 0 && btt[iy][ix] > 0 ? uct[iy][ix] / btt[iy][ix] : null));
    const iso = [];
    if (targets.uct) iso.push({field: uct, level: targets.uct, label: `UCT ${num(targets.uct)} N`, legend: `UCT = target ${num(targets.uct)} N`});
    if (targets.btt) iso.push({field: btt, level: targets.btt, label: `BTT ${num(targets.btt)} N`, dash: '7 4', legend: `BTT = target ${num(targets.btt)} N`});
    const ratioIso = targets.uct && targets.btt
      ? [{field: ratio, level: targets.uct / targets.btt, label: `ratio ${num(targets.uct / targets.btt, 3)}`, dash: '2 3',
        legend: `UCT/BTT = target ratio ${num(targets.uct / targets.btt, 3)}`}] : [];
    const width = plotWidth(ctx.main, {columns: 2, min: 420});
    const positive = (f) => f.flat().filter((v) => v > 0);
    const logScale = (f) => {
      const v = positive(f);
      return v.length > 1 && Math.max(...v) / Math.min(...v) > 8;
    };
    const map = (test, values, title, valueLabel, isolines) => heatMap({
      title, width, xs: grid.xs, ys: grid.ys, values, log: logScale(values), isolines,
      xLabel: 'F_r0, bond normal strength (N)', yLabel: 'F_s0, bond shear strength (N)', valueLabel,
      caption: `${positive(values).length} of ${grid.xs.length * grid.ys.length} points; colour ${logScale(values) ? 'log' : 'linear'} scale`,
      onActivate: (m) => ctx.navigate(m.href),
      cell: (ix, iy) => cellInfo(grid, test, ix, iy, values[iy][ix], valueLabel),
    });
    const maps = [];
    if (has('uct')) maps.push(map('uct', uct, 'UCT peak load', 'UCT peak load (N)', iso));
    if (has('btt')) maps.push(map('btt', btt, 'BTT peak load', 'BTT peak load (N)', iso));
    if (has('uct') && has('btt')) maps.push(map('ratio', ratio, 'UCT / BTT peak-load ratio', 'UCT/BTT (–)', iso.concat(ratioIso)));
    out.push(h('div', {class: 'plots'}, maps));
    if (iso.length === 2) {
      out.push(note('Where the solid (UCT) and dashed (BTT) iso-lines cross, both targets are met; if they do not ',
        'cross inside the map, no swept pair of strengths meets both.'));
    } else if (iso.length === 0) {
      out.push(note('Enter target peak loads above to draw their iso-lines on the maps.'));
    }
  }
  out.push(h('details', {class: 'jobs'}, h('summary', {}, `All ${rows.length} jobs`), resultsTable(rows)));
  return out;
}

function cellInfo(grid, test, ix, iy, value, valueLabel) {
  const x = grid.xs[ix];
  const y = grid.ys[iy];
  const u = grid.at('uct', ix, iy);
  const b = grid.at('btt', ix, iy);
  const own = test === 'btt' ? b : u;
  const job = own.rows[0]?.job_id;
  const n = test !== 'ratio' && own.n > 1 ? ` ± ${num(own.se, 2)} (mean ± se of ${own.n} realisations)` : '';
  const label = `F_r0 ${num(x)} N, F_s0 ${num(y)} N: ${valueLabel.replace(/ \(.*\)$/, '')} ` +
    (Number.isFinite(value) ? `${num(value)}${valueLabel.endsWith('(N)') ? ' N' : ''}${n}` : `none (${missingNote(own.rows)})`) +
    (job ? `, job #${job}` : '');
  return {label, href: job ? `/jobs/${job}` : null, note: Number.isFinite(value) ? null : missingNote(own.rows), key: `${ix},${iy}`};
}
