// A campaign's progress in words and as a bar: jobs for a sweep, a driver's progress model for a
// calibration (evaluations of its budget) or a diagnosis (jobs of the ones it plans, and its phase).
import {progressBar} from '../dom.js';
import {duration} from '../format.js';

export function isLive(c) {
  return c.state === 'queued' || c.state === 'running' || c.driver_status === 'running';
}

// "3 of 64 evaluations (search 40, valley trace 24; +2 seed re-runs)", "40 of 134 jobs (grid 54,
// budget 40, confirm 40)": a driver's progress model (the summary's "progress",
// orchestrator/progress_model.hpp; the count `rockcal status` prints too).
export function budgetText(model) {
  if (!model || typeof model.budget !== 'number') return '';
  const notes = [];
  if (Array.isArray(model.parts) && model.parts.length > 1) notes.push(model.parts.map((p) => `${p.name} ${p.budget}`).join(', '));
  if (model.seed_reruns > 0) notes.push(`+${model.seed_reruns} seed re-runs`);
  return `${model.done} of ${model.budget} ${model.unit}${notes.length ? ` (${notes.join('; ')})` : ''}`;
}

function progressOf(c) {
  const p = c.progress || {};
  const s = c.summary || {};
  const parts = [];
  // The server's fraction: of the jobs for a sweep, of the driver's progress model for a
  // calibration (its evaluations of the budget) or a diagnosis or twin (its jobs of the planned);
  // it never goes backwards.
  const fraction = p.fraction;
  // A driver's progress model: a calibration's evaluations, a diagnosis's or twin's jobs of the
  // ones it plans, each of its budget, and the ETA of that budget.
  const model = s.progress && typeof s.progress.budget === 'number' ? s.progress : null;
  let eta = isLive(c) && typeof p.eta_seconds === 'number' && (p.queued || p.running)
    ? `${c.driver_status ? 'queued jobs done in' : 'ETA'} ${duration(p.eta_seconds)}` : null;
  if (model) {
    parts.push(budgetText(model));
    eta = isLive(c) && typeof model.eta_seconds === 'number' ? `ETA ${duration(model.eta_seconds)} (full budget)` : null;
  }
  if (c.kind === 'diagnosis' && typeof s.phase === 'string') {
    parts.push(`phase ${s.step} of ${s.steps}: ${s.phase}`);
  }
  parts.push(`${p.succeeded ?? 0} of ${p.total ?? 0} jobs done`);
  if (p.running) parts.push(`${p.running} running`);
  if (p.queued) parts.push(`${p.queued} queued`);
  if (p.failed) parts.push(`${p.failed} failed`);
  if (p.cancelled) parts.push(`${p.cancelled} cancelled`);
  if (p.cached) parts.push(`${p.cached} from the store`);
  if (eta) parts.push(eta);
  return {fraction: fraction ?? 0, text: parts.join(', ')};
}

export function progressCell(c) {
  const {fraction, text} = progressOf(c);
  return progressBar(fraction, text);
}
