// The calibration's plots: objective per evaluation, each load per evaluation against its target,
// the evaluated points in the (F_r0, F_s0) plane, and the packing-seed scatter.
import {num} from '../format.js';
import {linePlot} from '../plot/line_plot.js';

const PHASE_MARKERS = {start: 'circle', ratio: 'triangle', scale: 'diamond', direct_2d: 'square', local: 'square'};

// The standard error of an evaluation's load when it ran several realisations (packings).
const seOf = (r, test) => r.ensemble && r.ensemble[test] && r.ensemble[test].peak_load ? r.ensemble[test].peak_load.se : null;

function byPhase(history) {
  const phases = [...new Set(history.map((r) => r.phase))];
  return phases.map((phase) => ({phase, rows: history.filter((r) => r.phase === phase)}));
}

export function convergencePlot(history, width) {
  const ok = history.filter((r) => r.ok && r.misfit > 0);
  const series = byPhase(ok).map(({phase, rows}, i) => ({
    name: `${phase} evaluations`, marker: PHASE_MARKERS[phase] || ['circle', 'square', 'triangle'][i % 3],
    points: rows.map((r) => ({x: r.index, y: r.misfit, key: `e${r.index}`,
      label: `evaluation ${r.index} (${r.phase}): misfit ${num(r.misfit, 3)} at F_r0 ${num(r.fr0)} N, F_s0 ${num(r.fs0)} N`})),
  }));
  const steps = history.filter((r) => Number.isFinite(r.best_misfit_so_far) && r.best_misfit_so_far > 0);
  series.push({name: 'best so far', line: true, step: true, marker: null, colour: '#000', dash: null,
    points: steps.map((r) => ({x: r.index, y: r.best_misfit_so_far}))});
  const failed = history.length - history.filter((r) => r.ok).length;
  return linePlot({title: 'Objective per evaluation', width, height: 300, series,
    caption: `misfit = Σ w ln(sim/target)²${failed ? `; ${failed} failed evaluations not shown` : ''}`,
    x: {label: 'evaluation (0 = first)', include: [0]}, y: {label: 'misfit (–, log scale)', log: true}});
}

export function loadsPlot(history, test, s, lab, width) {
  const target = s.targets[test] && s.targets[test].peak_load;
  const tol = s.tolerance;
  const ok = history.filter((r) => r.ok && Number.isFinite(r[test]));
  const name = test.toUpperCase();
  const series = byPhase(ok).map(({phase, rows}, i) => ({
    name: `${phase} evaluations`, marker: PHASE_MARKERS[phase] || ['circle', 'square', 'triangle'][i % 3],
    points: rows.map((r) => ({x: r.index, y: r[test], key: `e${r.index}`, yErr: seOf(r, test),
      label: `evaluation ${r.index}: ${name} peak ${num(r[test])} N` +
        (Number.isFinite(seOf(r, test)) ? ` ± ${num(seOf(r, test), 2)} (se of ${r.ensemble[test].peak_load.n} realisations)` : '') +
        (target ? ` (${num((r[test] / target - 1) * 100, 3)} % from the target)` : '') +
        (lab ? `, lab ${num(r[test] * lab.force / 1e3)} kN` : '')})),
  }));
  const hlines = Number.isFinite(target) ? [{y: target, label: `target ${num(target)} N`,
    legend: `target ${num(target)} N`, band: tol ? [target * (1 - tol), target * (1 + tol)] : null,
    bandLegend: tol ? `tolerance ±${num(tol * 100, 2)} %` : null}] : [];
  return linePlot({title: `${name} peak load per evaluation`, width, height: 300, series, hlines,
    x: {label: 'evaluation (0 = first)', include: [0]},
    y: {label: `${name} peak load (N, model units)`, log: true,
      second: lab ? {factor: lab.force / 1e3, label: `${name} peak load (kN, lab units)`} : null}});
}

export function planePlot(history, s, best, width) {
  const ok = history.filter((r) => r.ok);
  const bad = history.filter((r) => !r.ok);
  const series = [{name: 'evaluated', marker: 'circle', hollow: true,
    points: ok.map((r) => ({x: r.fr0, y: r.fs0, key: `e${r.index}`,
      label: `evaluation ${r.index} (${r.phase}): F_r0 ${num(r.fr0)} N, F_s0 ${num(r.fs0)} N; UCT ${num(r.uct)} N, BTT ${num(r.btt)} N, misfit ${num(r.misfit, 3)}`}))}];
  if (bad.length) {
    series.push({name: 'failed', marker: 'cross', colour: '#D55E00',
      points: bad.map((r) => ({x: r.fr0, y: r.fs0, key: `e${r.index}`, label: `evaluation ${r.index} failed: ${r.error}`}))});
  }
  if (s.consistent && Array.isArray(s.consistent.points)) {
    series.push({name: s.targets && s.targets.units === 'lab' ? 'consistent with the lab loads' : 'consistent with the targets', marker: 'diamond', colour: '#009E73',
      points: s.consistent.points.map((p, i) => ({x: p.fr0, y: p.fs0, key: `c${i}`,
        label: `consistent: F_r0 ${num(p.fr0)} N, F_s0 ${num(p.fs0)} N`}))});
  }
  if (best && best.fr0) {
    series.push({name: best.soFar ? 'best so far' : 'best', marker: 'star', colour: '#000', size: 14,
      points: [{x: best.fr0, y: best.fs0, key: 'best', label: `best: F_r0 ${num(best.fr0)} N, F_s0 ${num(best.fs0)} N`}]});
  }
  return linePlot({title: 'Evaluated strengths', width, height: 300, series,
    caption: 'each point one UCT and one BTT run',
    x: {label: 'F_r0, bond normal strength (N, log)', log: true},
    y: {label: 'F_s0, bond shear strength (N, log)', log: true}});
}

export function scatterPlot(s, lab, width) {
  const runs = s.scatter.runs.filter((r) => Number.isFinite(r.uct) && Number.isFinite(r.btt));
  const series = [{name: 'one packing seed', marker: 'circle',
    points: runs.map((r) => ({x: r.uct, y: r.btt, key: `seed${r.seed}`,
      label: `seed ${r.seed}: UCT ${num(r.uct)} N, BTT ${num(r.btt)} N`}))}];
  // The best point's own realisations, when the search ran an ensemble per evaluation (one
  // realisation is the scatter's run of the template's seed, already plotted).
  const e = s.best && s.best.ensemble;
  if (e && e.uct && e.btt && Array.isArray(e.uct.realisations) && e.uct.realisations.length > 1) {
    const btt = new Map(e.btt.realisations.map((r) => [r.seed, r.peak_load_n]));
    const pairs = e.uct.realisations.filter((r) => Number.isFinite(r.peak_load_n) && Number.isFinite(btt.get(r.seed)));
    series.push({name: 'realisation of the search', marker: 'triangle', hollow: true,
      points: pairs.map((r) => ({x: r.peak_load_n, y: btt.get(r.seed), key: `real${r.seed}`,
        label: `realisation seed ${r.seed}: UCT ${num(r.peak_load_n)} N, BTT ${num(btt.get(r.seed))} N`}))});
  }
  const su = s.scatter.uct;
  const sb = s.scatter.btt;
  if (su && sb) {
    series.push({name: 'mean ± sd', marker: 'square', colour: '#000',
      points: [{x: su.mean, y: sb.mean, xErr: su.stddev, yErr: sb.stddev, key: 'mean',
        label: `mean over ${su.runs} seeds: UCT ${num(su.mean)} ± ${num(su.stddev, 2)} N, BTT ${num(sb.mean)} ± ${num(sb.stddev, 2)} N`}]});
  }
  const tu = s.targets.uct && s.targets.uct.peak_load;
  const tb = s.targets.btt && s.targets.btt.peak_load;
  if (tu && tb) {
    series.push({name: 'target', marker: 'cross', colour: '#D55E00', size: 12,
      points: [{x: tu, y: tb, key: 'target', label: `target: UCT ${num(tu)} N, BTT ${num(tb)} N`}]});
  }
  return linePlot({title: 'Packing-seed scatter', width, height: 300, series,
    caption: 'UCT against BTT peak load, one point per seed',
    x: {label: 'UCT peak load (N, model units)', second: lab ? {factor: lab.force / 1e3, label: 'UCT (kN, lab units)'} : null},
    y: {label: 'BTT peak load (N, model units)', second: lab ? {factor: lab.force / 1e3, label: 'BTT (kN, lab units)'} : null}});
}
