// One engine job: its state and files, the result's numbers (with a table in lab units when the
// campaign has them), the load-displacement and stress-strain curves, broken bonds against
// displacement and where they broke (at the peak and at the end), the log and the raw spec and
// result. Polled while it is queued or running.
import {getJson, getText} from '../api.js';
import {badge, clear, facts, h, note, progressBar, rememberFocus, section, table} from '../dom.js';
import {dateTime, duration, newtons, num, pascals, strengthFormula} from '../format.js';
import {watchJson} from '../poll.js';
import {labFactors} from './calibration.js';
import {brokenBondsPlot, fetchCurve, loadCurvePlot} from './curves.js';
import {fractureFor, stressStrainFor} from './job_figures.js';
import {plotWidth} from './layout.js';

const live = (j) => j.state === 'queued' || j.state === 'running';

export async function render([idText], ctx) {
  const id = Number(idText);
  if (!Number.isInteger(id) || id <= 0) throw new Error(`"${idText}" is not a job id`);
  ctx.setTitle(`Job #${id}`);
  const view = h('div', {id: 'job'});
  ctx.main.append(view);
  const cache = new Map();
  await watchJson(`/api/v1/jobs/${id}`, {
    signal: ctx.signal,
    resize: ctx.main,
    live,
    missing: (e) => clear(view).append(h('h1', {}, `Job #${id}`), h('p', {class: 'error', role: 'alert'}, e.message)),
    show: async (j) => {
      const next = await jobView(j, {...ctx, cache});
      const focus = rememberFocus(ctx.main);
      clear(view).append(...next);
      focus.restore();
    },
  });
}

async function campaignLab(j, ctx) {
  try {
    const c = await getJson(`/api/v1/campaigns/${j.campaign_id}`, {signal: ctx.signal});
    return {campaign: c, lab: c.kind === 'calibration' ? labFactors(c.summary) : null};
  } catch (e) {
    if (e.name === 'AbortError') throw e;
    return {campaign: null, lab: null};
  }
}

async function jobView(j, ctx) {
  const name = j.test.toUpperCase();
  ctx.setTitle(`Job #${j.id} ${name}`);
  const {campaign, lab} = await campaignLab(j, ctx);
  const r = j.result || {};
  const out = [
    h('div', {class: 'page-head'}, h('h1', {}, h('span', {class: 'muted'}, `Job #${j.id} `),
      `${name} at F_r0 ${num(j.fr0)} N, F_s0 ${num(j.fs0)} N`)),
    facts([
      ['campaign', h('a', {href: `/campaigns/${j.campaign_id}`}, `#${j.campaign_id}${campaign ? ` ${campaign.name}` : ''}`)],
      ['state', [badge(j.state), j.cached ? ' (answered from the store: an identical job ran before)' : '',
        j.attempts > 1 ? ` after ${j.attempts} attempts` : '']],
      live(j) ? ['progress', progressBar(j.progress || 0, j.state === 'queued' ? 'queued' : `${Math.round((j.progress || 0) * 100)}% of the run`)] : null,
      ['created', dateTime(j.created_at)],
      j.started_at ? ['ran', `${dateTime(j.started_at)}${j.finished_at ? ` for ${duration(j.finished_at - j.started_at)}` : ''}`] : null,
      ['data', downloads(j)],
    ]),
  ];
  if (j.error) out.push(h('pre', {class: 'error', role: 'alert'}, j.error));
  if (j.result) out.push(resultSection(r, lab), labTable(r, lab));
  // A run without a peak keeps its result and curve for inspection (its job failed).
  if (j.state === 'succeeded' || j.result) {
    const width = plotWidth(ctx.main, {columns: 2});
    let curve = null;
    try {
      curve = await fetchCurve(j.id, ctx);
      const plots = [loadCurvePlot({title: `${name} load against displacement`, width, lab, curves: [{name, curve}],
        peak: r.peak_load, caption: `${curve.load.length} points`}),
      brokenBondsPlot({title: 'Broken bonds against displacement', width, curve, lab, bonds: r.bonds})];
      const stress = stressStrainFor(j, curve, width, lab);
      if (stress) plots.push(stress);
      out.push(section('Load, stress and broken bonds', h('div', {class: 'plots'}, ...plots)));
    } catch (e) {
      if (e.name === 'AbortError') throw e;
      out.push(note(`No load curve: ${e.message}`));
    }
    const fracture = await fractureFor(j, curve, width, ctx);
    if (fracture) out.push(fracture);
  }
  out.push(await logSection(j, ctx));
  out.push(h('details', {}, h('summary', {}, 'Spec (canonical JSON)'), h('pre', {class: 'json'}, JSON.stringify(j.spec, null, 2))));
  if (j.result) out.push(h('details', {}, h('summary', {}, 'result.json'), h('pre', {class: 'json'}, JSON.stringify(j.result, null, 2))));
  return out;
}

// The job's files: JSON, log, and what the run that answered it left (curve, breaks, VTK).
function downloads(j) {
  const f = j.files || {};
  const links = [h('a', {href: `/api/v1/jobs/${j.id}`}, 'JSON'), h('a', {href: `/api/v1/jobs/${j.id}/log`}, 'log')];
  if (f.curve_csv) links.push(h('a', {href: f.curve_csv, download: 'curve.csv'}, 'curve.csv'));
  if (f.breaks_csv) links.push(h('a', {href: f.breaks_csv, download: 'breaks.csv'}, 'breaks.csv'));
  const vtk = (f.vtk || []).map((url) => {
    const file = url.slice(url.lastIndexOf('/') + 1);
    return h('a', {href: url, download: file}, file);
  });
  const out = links.flatMap((a, i) => (i ? [' · ', a] : [a]));
  if (vtk.length) {
    out.push(h('details', {class: 'vtk-files'}, h('summary', {}, `VTK for ParaView (${vtk.length} files: save them in one folder, open particles.pvd)`),
      h('ul', {}, vtk.map((a) => h('li', {}, a)))));
  } else if (j.state === 'succeeded') {
    out.push(' · no VTK (ask for it with "output": {"vtk": true})');
  }
  return out;
}

// The job's strength, modulus and Poisson's ratio in model units and, when the campaign's targets
// came in lab units, in lab units (the model specimen scaled by eq. 4's factors).
function labTable(r, lab) {
  const def = r.strength_definition;
  const rows = [];
  if (Number.isFinite(r.peak_load)) rows.push({q: 'peak load', model: newtons(r.peak_load), lab: lab ? newtons(r.peak_load * lab.force) : ''});
  if (def && Number.isFinite(r.strength) && r.peak_reached !== false) {
    rows.push({q: `${def.name} (${strengthFormula(def)})`, model: pascals(r.strength), lab: lab ? pascals(r.strength * lab.stress) : ''});
  }
  if (Number.isFinite(r.youngs_modulus)) rows.push({q: 'E, Young’s modulus', model: pascals(r.youngs_modulus), lab: lab ? pascals(r.youngs_modulus * lab.stress) : ''});
  if (Number.isFinite(r.poisson_ratio)) rows.push({q: 'ν, Poisson’s ratio', model: num(r.poisson_ratio, 3), lab: lab ? num(r.poisson_ratio, 3) : ''});
  const columns = [{label: 'quantity', value: (x) => x.q}, {label: 'model units', num: true, value: (x) => x.model}];
  if (lab) columns.push({label: 'lab units (eq. 4)', num: true, value: (x) => x.lab});
  return section(lab ? 'Strength and stiffness in lab units' : 'Strength and stiffness (model units)',
    lab ? note('Lab units: this model specimen scaled to the lab by the campaign\'s force, length and stress factors (eq. 4). ' +
      'Where the model specimen is not the lab specimen scaled (another size or resolution), its strengths are not the lab specimen\'s: compare the loads.')
      : note('Model units: the campaign has no lab case to scale to.'),
    table(columns, rows, {caption: lab ? 'model and lab units' : 'model units'}));
}

function resultSection(r, lab) {
  const by = r.broken_by || {};
  const modes = Object.entries(by).filter(([, n]) => n > 0).map(([k, n]) => `${k} ${n}`).join(', ');
  const labLoad = (x) => (lab && Number.isFinite(x) ? ` (lab ${newtons(x * lab.force)})` : '');
  return section('Result', facts([
    ['peak load', [newtons(r.peak_load), labLoad(r.peak_load),
      r.peak_reached === false ? h('strong', {class: 'warn'}, ` — no peak: ${r.no_peak_reason || r.stop_reason}; not a result`) : '']],
    // No lab strength: a model specimen at demo resolution is not the lab specimen scaled, so the
    // mapped load is comparable and the stress is not (docs/calibration.md).
    ['strength', [pascals(r.strength), ` (model units${r.strength_definition ? `; ${strengthFormula(r.strength_definition)}` : ''})`]],
    Number.isFinite(r.youngs_modulus) ? ['Young’s modulus', pascals(r.youngs_modulus)] : null,
    Number.isFinite(r.poisson_ratio) ? ['Poisson’s ratio', num(r.poisson_ratio, 3)] : null,
    ['displacement at peak', [`${num(r.peak_displacement)} m`, lab ? ` (lab ${num(r.peak_displacement * lab.length * 1e3)} mm)` : '']],
    ['particles, bonds', `${r.particles}, ${r.bonds}`],
    ['broken bonds', `${r.broken_bonds} (${r.broken_bonds_at_peak} at the peak)${modes ? `; by mode: ${modes}` : ''}`],
    ['stop', `${String(r.stop_reason || '').replaceAll('_', ' ')} after ${r.steps} steps of ${num(r.dt)} s`],
    ['run time', `${duration(r.wall_seconds)} on ${r.ranks} rank${r.ranks === 1 ? '' : 's'} (${num(r.particle_steps_per_second, 3)} particle-steps/s)`],
  ]));
}

async function logSection(j, ctx) {
  if (j.cached) return section('Log', note('This job was answered from the store and never ran: it has no log.'));
  if (j.state === 'queued') return section('Log', note('Not started yet.'));
  try {
    const text = await getText(`/api/v1/jobs/${j.id}/log`, {signal: ctx.signal});
    const lines = text.split('\n');
    const tail = lines.slice(-200).join('\n');
    return section('Log', lines.length > 200 ? note(`The last 200 of ${lines.length} lines.`) : null,
      h('pre', {class: 'log', tabindex: 0}, tail || '(empty)'));
  } catch (e) {
    if (e.name === 'AbortError') throw e;
    return section('Log', note(e.message));
  }
}
