// The best point's UCT and BTT jobs (same strengths and the search's packing seed): their load
// curves against the targets, and their stress-strain curves and fractures as the job page draws
// them.
import {h, note} from '../dom.js';
import {loadCurvePlot, fetchCurve} from './curves.js';
import {jobDetail, jobFigures} from './job_figures.js';

const same = (a, b) => Math.abs(a - b) <= 1e-9 * Math.max(Math.abs(a), Math.abs(b));

// The succeeded job of `test` at the best point; with several (other packing seeds), the one
// whose spec has the search's seed.
async function bestJob(rows, best, test, seed, ctx) {
  const at = rows.filter((r) => r.test === test && r.state === 'succeeded' && same(r.fr0, best.fr0) && same(r.fs0, best.fs0));
  if (at.length <= 1 || seed === undefined) return at[0] || null;
  for (const r of at) {
    const j = await jobDetail(r.job_id, ctx);
    if (j.spec && j.spec.sample && j.spec.sample.seed === seed) return r;
  }
  return at[0];
}

function bestSeed(best, s) {
  return best.seed ?? (s.history || []).find((r) => r.index === best.evaluation)?.seed;
}

export async function bestCurves(best, rows, s, lab, width, ctx) {
  const seed = bestSeed(best, s);
  const out = [];
  for (const test of ['uct', 'btt']) {
    const job = await bestJob(rows, best, test, seed, ctx);
    const target = s.targets[test] && s.targets[test].peak_load;
    const name = test.toUpperCase();
    if (!job) {
      out.push(note(`No finished ${name} job at the best point yet.`));
      continue;
    }
    const curve = await fetchCurve(job.job_id, ctx);
    out.push(h('div', {class: 'curve-cell'}, loadCurvePlot({
      title: `${name} load curve at the best point`, width, lab, target,
      caption: h('span', {}, `job `, h('a', {href: `/jobs/${job.job_id}`}, `#${job.job_id}`), `; ${curve.load.length} points`),
      curves: [{name: `${name}, seed ${seed ?? '?'}`, curve}],
    })));
  }
  return h('div', {class: 'plots'}, out);
}

export async function bestFigures(best, rows, s, lab, width, ctx) {
  const seed = bestSeed(best, s);
  const out = [];
  for (const test of ['uct', 'btt']) {
    const job = await bestJob(rows, best, test, seed, ctx);
    if (job) out.push(await jobFigures(job.job_id, `${test.toUpperCase()} at the best point`, width, lab, ctx));
  }
  return out.length ? out : note('No finished job at the best point yet.');
}
