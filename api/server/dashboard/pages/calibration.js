// A calibration: the verdict and the best strengths (model and lab units), the consistent set of
// strengths when the report has one, the search (objective and both loads per evaluation, the
// evaluated points in the (F_r0, F_s0) plane), the best point's load curves against the targets,
// the packing-seed scatter, and the evaluations and jobs as tables. While it runs, the same page
// shows the history so far.
import {h, note, section, table} from '../dom.js';
import {newtons, num, pct, pm, signed} from '../format.js';
import {bestCurves, bestFigures} from './calibration_curves.js';
import {consistentSection} from './calibration_consistent.js';
import {posteriorSection} from './calibration_posterior.js';
import {convergencePlot, loadsPlot, planePlot, scatterPlot} from './calibration_plots.js';
import {budgetText, isLive} from './progress.js';
import {plotWidth} from './layout.js';
import {fetchResults, resultsTable} from './results.js';

// Factors from model to lab units (lab = model x factor), when the targets came in lab units.
export function labFactors(summary) {
  const sc = summary && summary.targets && summary.targets.scaling;
  if (!sc || !(sc.force > 0) || !(sc.length > 0) || !(sc.stress > 0)) return null;
  return {force: 1 / sc.force, length: 1 / sc.length, stress: 1 / sc.stress};
}

export async function renderCalibration(c, ctx) {
  const s = c.summary || {};
  const out = h('div', {class: 'calibration'});
  if (s.error) {
    out.append(h('p', {class: 'error', role: 'alert'}, `The calibration failed: ${s.error}`));
  }
  const history = Array.isArray(s.history) ? s.history : [];
  if (!s.targets) {
    out.append(note(isLive(c) ? 'The calibration is starting: the first evaluations are running.' : 'No report.'));
    return out;
  }
  const lab = labFactors(s);
  const best = s.best || bestSoFar(history);
  out.append(verdictSection(c, s, best, lab));
  if (s.posterior) {
    out.append(posteriorSection(s, history, plotWidth(ctx.main, {columns: 1})));
  } else if (s.consistent || s.unique !== undefined) {
    out.append(consistentSection(s, lab, plotWidth(ctx.main, {columns: 2})));
  }
  const width = plotWidth(ctx.main, {columns: 2});
  const plots = [];
  if (history.length) {
    plots.push(convergencePlot(history, width), planePlot(history, s, best, width, ctx),
      loadsPlot(history, 'uct', s, lab, width), loadsPlot(history, 'btt', s, lab, width));
  }
  out.append(section(`The search (${history.length} evaluations${isLive(c) ? ' so far' : ''})`,
    history.length ? h('div', {class: 'plots'}, plots) : note('No evaluation has finished yet.')));
  const rows = await fetchResults(c, ctx);
  if (best && best.fr0) {
    out.append(section(s.best ? 'The best point’s load curves' : 'The best point so far: load curves',
      await bestCurves(best, rows, s, lab, width, ctx)));
    out.append(section(s.best ? 'The best point’s fracture and stress-strain' : 'The best point so far: fracture and stress-strain',
      await bestFigures(best, rows, s, lab, width, ctx)));
  }
  if (s.scatter && Array.isArray(s.scatter.runs) && s.scatter.runs.length) {
    out.append(scatterSection(s, lab, width));
  }
  if (s.homogeneity) out.append(homogeneitySection(s.homogeneity));
  out.append(h('details', {class: 'jobs'}, h('summary', {}, `All ${history.length} evaluations`), historyTable(history)));
  out.append(h('details', {class: 'jobs'}, h('summary', {}, `All ${rows.length} jobs`), resultsTable(rows)));
  return out;
}

function bestSoFar(history) {
  let best = null;
  for (const r of history) {
    if (r.ok && (!best || r.misfit < best.misfit)) best = r;
  }
  return best && {fr0: best.fr0, fs0: best.fs0, misfit: best.misfit, evaluation: best.index, seed: best.seed,
    uct: {peak_load: best.uct}, btt: {peak_load: best.btt}, within_tolerance: best.within_tolerance, soFar: true};
}

function verdictSection(c, s, best, lab) {
  const t = s.targets;
  const parts = [];
  if (s.verdict) {
    parts.push(h('p', {class: `verdict verdict-${s.verdict}`}, h('strong', {}, `Verdict: ${s.verdict}`),
      s.verdict_reason ? ` — ${s.verdict_reason}` : ''));
    parts.push(h('p', {}, `Stopped: ${String(s.stop_reason || '').replaceAll('_', ' ')}; `,
      `${s.progress ? budgetText(s.progress) : `${s.evaluations} evaluations`} (${s.failed_evaluations || 0} failed); `,
      `tolerance ${pct(s.tolerance, 1)} on each load; strategy ${s.strategy ? s.strategy.used || s.strategy.requested : '–'}` +
      (s.strategy && s.strategy.algorithm ? ` (${s.strategy.algorithm})` : '') + '.'));
  } else if (isLive(c)) {
    parts.push(h('p', {class: 'verdict verdict-running'}, h('strong', {}, 'Running: '),
      `${s.progress ? budgetText(s.progress) : `${s.evaluations ?? 0} evaluations`}; the report comes when the search ends.`));
  } else {
    // Cancelled (or stopped) before its report: what it evaluated is all there is.
    parts.push(h('p', {class: 'verdict verdict-incomplete'}, h('strong', {}, `No report (${c.driver_status || c.state}): `),
      `the search stopped after ${s.progress ? budgetText(s.progress) : `${s.evaluations ?? 0} evaluations`}; below is what it evaluated.`));
  }
  if (best) {
    const labBest = s.best && s.best.lab;
    const row = (test) => {
      const r = best[test] || {};
      const target = t[test] && t[test].peak_load;
      const rel = Number.isFinite(r.relative_error) ? r.relative_error
        : Number.isFinite(r.peak_load) && target ? r.peak_load / target - 1 : null;
      // An ensemble's mean carries its standard error.
      const se = Number.isFinite(r.se) ? ` ± ${newtons(r.se)} (n = ${r.n})` : '';
      const cells = {test: test.toUpperCase(), sim: newtons(r.peak_load) + se, target: newtons(target), rel: Number.isFinite(rel) ? `${signed(rel * 100, 3)} %` : '–'};
      if (lab) {
        cells.labSim = newtons(labBest ? labBest[test].peak_load : r.peak_load * lab.force);
        cells.labTarget = newtons(t.lab ? t.lab[test].peak_load : target * lab.force);
      }
      return cells;
    };
    const columns = [
      {label: 'test', value: (r) => r.test},
      {label: 'simulated (model)', num: true, value: (r) => r.sim},
      {label: 'target (model)', num: true, value: (r) => r.target},
      {label: 'error', num: true, value: (r) => r.rel},
    ];
    if (lab) {
      columns.push({label: 'simulated (lab)', num: true, value: (r) => r.labSim},
        {label: 'target (lab)', num: true, value: (r) => r.labTarget});
    }
    // A bayes calibration's answer is its posterior (below); its "best" is the check batch run at
    // the estimate.
    parts.push(h('h3', {}, s.posterior ? 'Check runs at the estimate' : best.soFar ? 'Best point so far' : 'Best point'),
      h('p', {class: 'best-point'}, `F_r0 = ${num(best.fr0)} N, F_s0 = ${num(best.fs0)} N (model units)`,
        labBest ? `; lab F_r0 = ${newtons(labBest.fr0)}, F_s0 = ${newtons(labBest.fs0)}`
          : lab ? `; lab F_r0 = ${newtons(best.fr0 * lab.force)}, F_s0 = ${newtons(best.fs0 * lab.force)}` : '',
        `; evaluation ${best.evaluation}, misfit ${num(best.misfit, 3)}, `,
        best.within_tolerance ? 'both loads within tolerance.' : 'not within tolerance.'),
      table(columns, [row('uct'), row('btt')], {caption: 'Peak loads at the best point'}));
    const sc = s.scatter;
    if (sc && sc.uct && sc.btt) {
      parts.push(h('p', {}, `Over ${sc.uct.runs} packing seeds: UCT ${pm(sc.uct.mean, sc.uct.stddev)} N (CV ${pct(sc.uct.cv)}), `,
        `BTT ${pm(sc.btt.mean, sc.btt.stddev)} N (CV ${pct(sc.btt.cv)}).`));
    }
    if (s.ratio) {
      parts.push(h('p', {}, `UCT/BTT ratio: target ${num(s.ratio.target, 3)}, reached ${num(s.ratio.min, 3)}–${num(s.ratio.max, 3)} `,
        s.ratio.target_inside ? '(the target lies inside).' : h('strong', {}, '(the target lies outside: no pair of strengths in the search reaches it).')));
    }
  }
  return section('Result', ...parts);
}

function scatterSection(s, lab, width) {
  const runs = s.scatter.runs;
  return section('Packing-seed scatter at the best point',
    h('div', {class: 'plots'}, scatterPlot(s, lab, width),
      table([
        {label: 'seed', num: true, value: (r) => r.seed},
        {label: 'UCT peak', num: true, value: (r) => newtons(r.uct)},
        {label: 'BTT peak', num: true, value: (r) => newtons(r.btt)},
        {label: 'UCT/BTT', num: true, value: (r) => (r.uct && r.btt ? num(r.uct / r.btt, 3) : '–')},
        {label: 'error', value: (r) => r.error || ''},
      ], runs, {caption: 'One row per packing seed (the search’s own seed first)'})));
}

function homogeneitySection(hm) {
  const verdict = hm.holds === null || hm.holds === undefined ? 'not measured' : hm.holds ? 'holds' : 'does not hold';
  return h('details', {class: 'jobs'}, h('summary', {}, `Homogeneity check: ${verdict}`),
    note('Loads scale like c^p when both strengths scale by c; the ratio-then-scale strategy relies on p being equal for both tests.'),
    table([
      {label: 'measured', value: (r) => (r.measured ? 'yes' : 'no')},
      {label: 'base F_r0, F_s0 (N)', value: (r) => `${num(r.base.fr0)}, ${num(r.base.fs0)}`},
      {label: 'scale c', num: true, value: (r) => num(r.scale_factor, 3)},
      {label: 'p (UCT)', num: true, value: (r) => num(r.exponent_uct, 3)},
      {label: 'p (BTT)', num: true, value: (r) => num(r.exponent_btt, 3)},
      {label: 'holds', value: (r) => (r.holds ? 'yes' : 'no')},
    ], hm.checks || []));
}

function historyTable(history) {
  return table([
    {label: 'index', num: true, value: (r) => r.index},
    {label: 'phase', value: (r) => r.phase},
    {label: 'F_r0 (N)', num: true, value: (r) => num(r.fr0)},
    {label: 'F_s0 (N)', num: true, value: (r) => num(r.fs0)},
    {label: 'seed', num: true, value: (r) => r.seed},
    {label: 'UCT (N)', num: true, value: (r) => num(r.uct)},
    {label: 'BTT (N)', num: true, value: (r) => num(r.btt)},
    {label: 'misfit', num: true, value: (r) => num(r.misfit, 3)},
    {label: 'within tol.', value: (r) => (r.within_tolerance ? 'yes' : '')},
    {label: 'error', value: (r) => r.error || ''},
  ], history, {rowAttrs: (r) => ({class: r.ok ? null : 'failed-row'})});
}
