// A "bayes" calibration's answer: the posterior of (F_r0, F_s0). The estimate and each strength's
// credible interval (model and lab units), the predicted loads with their intervals, the lab
// uncertainty used and where it came from, and the credible region drawn over the (F_r0, F_s0)
// plane with the runs behind it. Every number is the report's (summary.posterior).
import {h, section, table} from '../dom.js';
import {newtons, num, pct, signed} from '../format.js';
import {linePlot} from '../plot/line_plot.js';

const interval = (r) => (Array.isArray(r) && r.length === 2 ? `${num(r[0])} – ${num(r[1])}` : '–');

// The region's outline on the log grid of the bounds: spans [j, i_lo, i_hi] of cells, each row's
// left edges up and right edges down (one closed line per run of consecutive rows).
export function regionOutline(region) {
  const g = region && region.grid;
  if (!g || !Array.isArray(region.spans) || !region.spans.length) return [];
  const n = g.cells;
  const at = (range, k) => range[0] * (range[1] / range[0]) ** (k / n);
  const rows = new Map();
  for (const [j, lo, hi] of region.spans) {
    const r = rows.get(j);
    rows.set(j, r ? [Math.min(r[0], lo), Math.max(r[1], hi)] : [lo, hi]);
  }
  const js = [...rows.keys()].sort((a, b) => a - b);
  const left = [];
  const right = [];
  for (const j of js) {
    const [lo, hi] = rows.get(j);
    left.push({x: at(g.fr0, lo), y: at(g.fs0, j)}, {x: at(g.fr0, lo), y: at(g.fs0, j + 1)});
    right.push({x: at(g.fr0, hi + 1), y: at(g.fs0, j)}, {x: at(g.fr0, hi + 1), y: at(g.fs0, j + 1)});
  }
  const outline = [...left, ...right.reverse()];
  outline.push(outline[0]);
  return outline;
}

// The check runs' mean against the prediction and the sd the prediction allows it.
function checkText(k) {
  if (!k) return '-';
  return `${signed(100 * k.relative_to_prediction, 3)} % (sd ${pct(k.sd)}, n ${k.runs}): ` +
    (k.agrees ? 'agrees' : 'DISAGREES');
}

export function posteriorSection(s, history, width) {
  const p = s.posterior;
  const level = `${Math.round(100 * p.level)}%`;
  const labOf = p.lab || null;
  const strengths = table([
    {label: 'strength', value: (r) => r.name},
    {label: 'estimate (N, model)', num: true, value: (r) => num(r.est)},
    {label: `${level} interval (N, model)`, num: true, value: (r) => interval(r.iv)},
    ...(labOf ? [{label: 'estimate (N, lab)', num: true, value: (r) => newtons(r.labEst)},
      {label: `${level} interval (N, lab)`, num: true, value: (r) => interval(r.labIv)}] : []),
  ], ['fr0', 'fs0'].map((k) => ({name: k === 'fr0' ? 'F_r0' : 'F_s0', est: p.estimate[k], iv: p[k],
    labEst: labOf && labOf.estimate[k], labIv: labOf && labOf[k]})),
  {caption: `The strengths' posterior: estimate and ${level} credible intervals`});
  const loads = table([
    {label: 'test', value: (r) => r.name},
    {label: 'target', num: true, value: (r) => newtons(r.t.target)},
    {label: 'predicted mean', num: true, value: (r) => newtons(r.t.mean)},
    {label: `${level} interval of the mean`, num: true, value: (r) => interval(r.t.interval)},
    {label: 'one packing', num: true, value: (r) => interval(r.t.run_interval)},
    {label: 'error', num: true, value: (r) => `${signed(100 * r.t.relative_error, 3)} %`},
    {label: 'check runs against the prediction', num: true, value: (r) => checkText(r.t.check)},
  ], [{name: 'UCT', t: p.uct}, {name: 'BTT', t: p.btt}],
  {caption: 'Peak loads predicted at the estimate (model units, N)'});
  const lu = p.lab_uncertainty || {};
  const facts = h('p', {}, `From ${p.runs} runs at ${p.points} points (${p.rounds} design rounds). `,
    `The targets are taken as known to UCT ${pct(lu.uct)} and BTT ${pct(lu.btt)} `,
    lu.source === 'request' ? '(stated in the request). ' : '(a default: the request did not state it). ',
    `One packing scatters by ${pct(p.uct.run_sd)} (UCT) and ${pct(p.btt.run_sd)} (BTT) in ln.`);
  const unique = h('p', {class: `verdict ${p.unique ? 'verdict-feasible' : 'verdict-compromise'}`},
    h('strong', {}, p.unique ? 'Unique: ' : 'Not unique: '), `${p.why}.`);
  const ok = history.filter((r) => r.ok);
  const series = [
    {name: `${level} credible region`, line: true, marker: null, colour: '#0072B2', points: regionOutline(p.region)},
    {name: 'run', marker: 'circle', hollow: true, colour: '#999',
      points: ok.map((r) => ({x: r.fr0, y: r.fs0, key: `r${r.index}`,
        label: `run ${r.index} (${r.phase}, seed ${r.seed}): UCT ${num(r.uct)} N, BTT ${num(r.btt)} N`}))},
    {name: 'estimate', marker: 'star', colour: '#000', size: 14,
      points: [{x: p.estimate.fr0, y: p.estimate.fs0, key: 'estimate',
        label: `estimate: F_r0 ${num(p.estimate.fr0)} N, F_s0 ${num(p.estimate.fs0)} N`}]},
  ];
  const plot = linePlot({title: 'The credible region over (F_r0, F_s0)', width, height: 400, series,
    caption: `the ${level} highest-density region of the posterior, the runs and the estimate`,
    x: {label: 'F_r0, bond normal strength (N, log)', log: true},
    y: {label: 'F_s0, bond shear strength (N, log)', log: true}});
  plot.classList.add('posterior-region');
  const parts = [facts, strengths, loads, unique, plot];
  const next = s.suggestion;
  if (next && Array.isArray(next.candidates)) {
    parts.push(h('p', {class: 'next-test'}, h('strong', {}, 'Next test: '), `${next.observable} — ${next.why}.`),
      table([
        {label: 'further test', value: (k) => k.observable},
        {label: 'expected shortening of the long axis', num: true, value: (k) => pct(k.expected_shrinkage, 0)},
      ], next.candidates.filter((k) => Number.isFinite(k.expected_shrinkage)),
      {caption: 'What each test from the engine’s menu would do to the region, measured to the targets’ uncertainty'}));
  }
  return section('The answer: a posterior', ...parts);
}
