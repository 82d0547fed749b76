// A gap diagnosis: the verdict and its confidence, residuals by observation before (base model)
// and after (the verdict's model) against each observation's noise band, each candidate effect's
// score, the numerical budget. Residuals are ln(sim / lab): unitless, so model and lab agree.
import {h, note, section, table} from '../dom.js';
import {num, pct, signed} from '../format.js';
import {groupedBars, horizontalBars} from '../plot/bar_chart.js';
import {budgetText, isLive} from './progress.js';
import {plotWidth} from './layout.js';
import {fetchResults, resultsTable} from './results.js';

const effectName = (c) => (typeof c.effect === 'string' ? c.effect : 'base model');
// The report's values are in model units (its "units"); the unit of each observable.
const UNITS = {peak_load: 'N', strength: 'Pa', youngs_modulus: 'Pa', poisson_ratio: ''};
const withUnit = (x, o) => `${num(x)}${UNITS[o.observable] ? ` ${UNITS[o.observable]}` : ''}`;
// A fitted parameter, and the span of values giving the same model when it stands for one.
const parameterText = (p) => `${p.name} = ${num(p.value)} ${p.unit || ''}`
  + (p.same_model ? ` (the same model as any value in [${num(p.same_model.from)}, ${num(p.same_model.to)}))` : '');

export async function renderDiagnosis(c, ctx) {
  const s = c.summary || {};
  const out = h('div', {class: 'diagnosis'});
  if (s.error) out.append(h('p', {class: 'error', role: 'alert'}, `The diagnosis failed: ${s.error}`));
  if (!s.verdict) {
    const where = s.phase ? `phase ${s.step} of ${s.steps} (${s.phase}), ${s.progress ? budgetText(s.progress) : `${s.runs ?? 0} runs`}` : 'the start';
    out.append(h('p', {class: `verdict ${isLive(c) ? 'verdict-running' : 'verdict-incomplete'}`},
      isLive(c) ? [h('strong', {}, 'Running: '), `${where} so far. The verdict, residuals and scores appear when it finishes.`]
        : [h('strong', {}, `No report (${c.driver_status || c.state}): `), `it stopped at ${where}.`]));
    const rows = await fetchResults(c, ctx);
    out.append(h('details', {class: 'jobs'}, h('summary', {}, `All ${rows.length} jobs`), resultsTable(rows)));
    return out;
  }
  const width = plotWidth(ctx.main, {columns: 1, max: 1000});
  out.append(verdictSection(s), residualSection(s, width), candidateSection(s, width), budgetSection(s));
  return out;
}

function verdictSection(s) {
  const v = s.verdict;
  const p = v.parameter;
  const conf = v.confidence || {};
  const boot = conf.bootstrap || {};
  const gap = v.gap || {};
  const rms = (role) => `${num(gap[role] && gap[role].before, 4)} → ${num(gap[role] && gap[role].after, 4)}`;
  const pairs = [
    p ? ['fitted parameter', parameterText(p)] : null,
    ['F_r0, F_s0 (model)', `${num(v.fr0)} N, ${num(v.fs0)} N`],
    v.evidence ? ['evidence (held out)', v.evidence.effect
      ? `${v.evidence.effect}: ${num(v.evidence.value, 3)} nats over the base; threshold ${num(v.evidence.threshold, 3)} nats`
      : `no contender; threshold ${num(v.evidence.threshold, 3)} nats`] : null,
    ['gap closure G', num(v.gap_closure, 3)],
    ['rms ln(sim/lab), calibration', rms('calibration')],
    ['rms ln(sim/lab), held out', rms('held_out')],
    v.runner_up ? ['runner-up', `${v.runner_up.effect}, evidence ${num(v.runner_up.evidence, 3)} nats, G = ${num(v.runner_up.gap_closure, 3)} (${v.runner_up.basis})`] : null,
  ].filter(Boolean);
  return section('Verdict',
    h('p', {class: 'verdict verdict-diagnosis'}, h('strong', {}, v.label), v.reason ? ` — ${v.reason}` : ''),
    h('p', {class: `confidence confidence-${conf.level}`}, h('strong', {}, `Confidence: ${conf.level || '–'}`),
      ` — bootstrap agreement ${pct(boot.agreement)} of ${boot.replicates ?? 0} replicates; `,
      `${conf.seeds_agreeing ?? 0} of ${conf.seeds_informative ?? 0} replicate seeds agree`,
      conf.seeds_identical ? ` (${conf.seeds_identical} more re-ran identically and are not counted)` : '', '.'),
    h('dl', {class: 'facts'}, pairs.map(([a, b]) => [h('dt', {}, a), h('dd', {}, b)])),
    // The lab test that would tell the leading hypotheses apart (next_test.reason).
    s.next_test && s.next_test.reason ? h('p', {class: 'next-test'}, h('strong', {}, 'Next test: '), s.next_test.reason) : null,
    conf.method ? h('details', {}, h('summary', {}, 'How the confidence is measured'), note(conf.method)) : null);
}

// The model "after": the verdict's effect; when no effect is needed, the best-scoring candidate
// (the runner-up), so that the page shows what it would have changed.
function afterModel(s, obs) {
  if (s.verdict.effect) {
    return {name: `with ${s.verdict.effect} (the verdict)`, short: s.verdict.effect,
      values: obs.map((o) => o.verdict && o.verdict.residual)};
  }
  const ru = s.verdict.runner_up;
  const cand = ru && (s.candidates || []).find((c) => c.effect === ru.effect);
  const res = cand && (cand.residuals || cand.predicted_residuals);
  if (!res) return null;
  return {name: `with ${cand.effect} (the runner-up, not needed; ${cand.residuals ? 'real runs' : 'its fitted surface'})`,
    short: `${cand.effect}, runner-up`, values: obs.map((o) => res[o.id])};
}

function residualSection(s, width) {
  const obs = s.observations || [];
  const categories = obs.map((o) => `${o.id}${o.role === 'held_out' ? ' (held out)' : ''}`);
  const band = obs.map((o) => o.budget + o.lab_uncertainty + ((o.base && o.base.fit_spread) || 0));
  const later = afterModel(s, obs);
  const after = later ? later.name : '';
  const series = [{name: 'base model (before)', values: obs.map((o) => o.base && o.base.residual), colourIndex: 0}];
  if (later) series.push({name: later.name, values: later.values, colourIndex: 1, hatched: true});
  const chart = groupedBars({title: 'Residuals by observation', width, height: 340, categories, series, band,
    yLabel: 'ln(sim / lab) (–)', bandLabel: '± (numerical budget + lab uncertainty + the fit\'s spread)',
    caption: 'a bar beyond its band is a gap, not noise',
    describe: (k) => {
      const o = obs[k];
      return `${o.id} (${o.test} ${o.observable}, ${o.role.replace('_', ' ')}): lab ${withUnit(o.lab, o)}, base ${withUnit(o.base && o.base.sim, o)} ` +
        `(ln ${signed(o.base && o.base.residual, 3)}${o.base && o.base.significant ? ', beyond its band' : ''})` +
        (later ? `, ${after}: ln ${signed(later.values[k], 3)}` : '') + `; band ±${num(band[k], 3)}`;
    }});
  const rows = table([
    {label: 'observation', value: (o) => o.id},
    {label: 'test', value: (o) => `${o.test} ${o.observable}`},
    {label: 'role', value: (o) => o.role.replace('_', ' ')},
    {label: `lab (${s.units || 'model'} units)`, num: true, value: (o) => withUnit(o.lab, o)},
    {label: 'base sim', num: true, value: (o) => withUnit(o.base && o.base.sim, o)},
    {label: 'ln(sim/lab) before', num: true, value: (o) => [signed(o.base && o.base.residual, 3), o.base && o.base.significant ? ' ⚠ gap' : '']},
    {label: `after (${later ? later.short : 'no effect'})`, num: true, value: (o) => (later ? signed(later.values[obs.indexOf(o)], 3) : '–')},
    {label: 'budget', num: true, value: (o) => num(o.budget, 3)},
    {label: 'lab unc.', num: true, value: (o) => num(o.lab_uncertainty, 3)},
    {label: 'fit spread', num: true, value: (o) => num(o.base && o.base.fit_spread, 3)},
  ], obs, {rowAttrs: (o) => ({class: o.base && o.base.significant ? 'gap-row' : null})});
  const g = s.gap || {};
  return section('Where the gap lies',
    h('p', {}, `Held-out residuals in units of their budgets: ${num(g.held_out_budgets, 3)} `,
      g.exceeds_budget ? h('strong', {}, '(above 1: a real gap)') : '(not above 1: within noise)',
      g.significant && g.significant.length ? `; beyond their band: ${g.significant.join(', ')}.` : '.'),
    chart, rows);
}

function candidateSection(s, width) {
  const cands = (s.candidates || []).filter((c) => typeof c.effect === 'string');
  const items = cands.map((c) => ({
    label: c.effect,
    value: c.gap_closure ? c.gap_closure.value : NaN,
    highlight: c.effect === s.verdict.effect,
    note: [c.gap_closure ? `basis ${c.gap_closure.basis}` : 'not fitted', c.identifiable === false ? 'not identifiable' : null,
      c.effect === s.verdict.effect ? 'the verdict' : null].filter(Boolean).join(', '),
  }));
  // Nothing to draw: the report's own reason (gap.closure_missing), never an empty chart.
  const missing = s.gap && s.gap.closure_missing;
  const chart = missing ? note(`No gap closure to show: ${missing}.`)
    : items.length ? horizontalBars({title: 'Candidate effects: gap closure G', width, items,
      xLabel: 'G, held-out gap closed (–)',
      caption: 'the share of the held-out gap each effect closes (1 all, 0 none); solid: the verdict, hatched: the others'})
      : note('No candidate effects were tried (base model only).');
  const all = s.candidates || [];
  const rows = table([
    {label: 'candidate', value: (c) => effectName(c)},
    {label: 'rank', num: true, value: (c) => c.rank ?? '–'},
    {label: 'evidence (nats)', num: true, value: (c) => (c.evidence ? num(c.evidence.value, 3) : '–')},
    {label: 'G', num: true, value: (c) => (c.gap_closure ? num(c.gap_closure.value, 3) : '–')},
    {label: 'basis', value: (c) => (c.gap_closure ? c.gap_closure.basis : '')},
    {label: 'fitted parameter', value: (c) => (c.parameter ? parameterText(c.parameter) : '')},
    {label: 'F_r0, F_s0 (N)', value: (c) => (c.fit ? `${num(c.fit.fr0)}, ${num(c.fit.fs0)}` : '')},
    {label: 'rms held out', num: true, value: (c) => num(c.rms && (c.rms.confirmed || c.rms.surface).held_out, 3)},
    {label: 'identifiable', value: (c) => (c.identifiable === undefined ? ''
      : (c.identifiable ? 'yes' : 'no') + (c.identifiable_reason ? `: ${c.identifiable_reason}` : ''))},
    {label: 'on bounds', value: (c) => (c.fit && c.fit.on_bounds && c.fit.on_bounds.length ? c.fit.on_bounds.join(', ') : '')},
    {label: 'error', value: (c) => c.error || ''},
  ], all);
  return section('Candidate scores', chart, rows);
}

function budgetSection(s) {
  const b = s.budget || {};
  const per = b.per_observation || {};
  const r = s.ratio;
  return h('details', {class: 'jobs'}, h('summary', {}, 'Numerical budget, ratio and runs'),
    table([
      {label: 'observation', value: (k) => k},
      {label: 'budget (ln)', num: true, value: (k) => num(per[k], 3)},
    ], Object.keys(per), {caption: `Measured at F_r0 ${num(b.point && b.point.fr0)} N, F_s0 ${num(b.point && b.point.fs0)} N`}),
    r ? h('p', {}, `UCT/BTT ratio (${r.uct} / ${r.btt}): lab ${num(r.lab, 3)}, the base model reaches ${num(r.min, 3)}–${num(r.max, 3)} `,
      r.inside ? '(inside).' : h('strong', {}, '(outside).')) : null,
    s.runs ? h('p', {}, `${s.runs.model_points} model points; ${s.runs.failed_values} failed and ${s.runs.censored_values} censored values.`,
      s.runs.first_error ? ` First error: ${s.runs.first_error}` : '') : null);
}
