// How a job's run failed, drawn the same wherever a run is shown (the job page, a calibration's
// best point, the diagnosis's HTML report): the stress-strain curve of a UCT or triaxial job
// (curves.js) and where its bonds broke, at the peak and at the end, by mode (fracture.js).
import {getJson} from '../api.js';
import {h, note, section} from '../dom.js';
import {fetchCurve, stressStrainPlot} from './curves.js';
import {fractureSection} from './fracture.js';

// The stress-strain plot of a UCT or triaxial job that reached a peak, else null.
export function stressStrainFor(j, curve, width, lab) {
  const r = j.result || {};
  if (!curve || !(j.test === 'uct' || j.test === 'triaxial') || !(r.peak_load > 0) || !j.spec || !j.spec.sample) return null;
  return stressStrainPlot({title: `${j.test.toUpperCase()} stress against strain`, r, curve, height: j.spec.sample.height, width, lab});
}

// The fracture section of a job (none for an elastic test), or a note why there is none.
export async function fractureFor(j, curve, width, ctx) {
  if (j.test === 'elastic') return null;
  try {
    return await fractureSection(j, curve, width, ctx);
  } catch (e) {
    if (e.name === 'AbortError') throw e;
    return section('Fracture', note(`No broken bonds to draw: ${e.message}`));
  }
}

// A finished job's detail (GET /api/v1/jobs/{id}), fetched once per page.
export async function jobDetail(id, ctx) {
  const key = `job:${id}`;
  if (!ctx.cache.has(key)) ctx.cache.set(key, await getJson(`/api/v1/jobs/${id}`, {signal: ctx.signal}));
  return ctx.cache.get(key);
}

// Finished job `id`'s stress-strain curve and fracture, headed by `title` with a link to its page.
export async function jobFigures(id, title, width, lab, ctx) {
  const j = await jobDetail(id, ctx);
  let curve = null;
  const parts = [];
  try {
    curve = await fetchCurve(id, ctx);
  } catch (e) {
    if (e.name === 'AbortError') throw e;
    parts.push(note(`No load curve: ${e.message}`));
  }
  const stress = stressStrainFor(j, curve, width, lab);
  if (stress) parts.push(h('div', {class: 'plots'}, stress));
  const fracture = await fractureFor(j, curve, width, ctx);
  if (fracture) parts.push(fracture);
  return h('div', {class: 'job-figures', dataset: {job: id}},
    h('h3', {}, title, ' (job ', h('a', {href: `/jobs/${id}`}, `#${id}`), ')'), ...parts);
}
