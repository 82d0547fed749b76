// A campaign's progress in words and as a bar: jobs for a sweep, evaluations for a calibration
// (its jobs are not known in advance), the phase for a diagnosis.
import {progressBar} from '../dom.js';
import {duration} from '../format.js';

export function isLive(c) {
  return c.state === 'queued' || c.state === 'running' || c.driver_status === 'running';
}

export function progressOf(c) {
  const p = c.progress || {};
  const s = c.summary || {};
  const parts = [];
  let fraction = p.fraction;
  // A driver adds jobs as it goes, so the jobs' own ETA covers only those queued now.
  let eta = p.eta_seconds;
  let etaText = 'ETA';
  if (c.kind === 'calibration' && typeof s.evaluations === 'number') {
    parts.push(`${s.evaluations} of ${s.max_evaluations} evaluations`);
    if (isLive(c)) {
      fraction = s.max_evaluations ? s.evaluations / s.max_evaluations : fraction;
      // At the pace so far, the rest of the budget; the search may stop sooner.
      const elapsed = Date.now() / 1000 - c.created_at;
      if (s.evaluations > 0 && elapsed > 0) {
        eta = (elapsed / s.evaluations) * Math.max(0, s.max_evaluations - s.evaluations);
        etaText = 'at most';
      }
    } else {
      fraction = 1;
    }
  } else if (c.kind === 'diagnosis' && typeof s.phase === 'string') {
    parts.push(`phase ${s.step} of ${s.steps}: ${s.phase}`);
    if (s.steps) fraction = (s.step - 1 + (p.fraction || 0)) / s.steps;
    etaText = 'queued jobs done in';
  }
  parts.push(`${p.succeeded ?? 0} of ${p.total ?? 0} jobs done`);
  if (p.running) parts.push(`${p.running} running`);
  if (p.queued) parts.push(`${p.queued} queued`);
  if (p.failed) parts.push(`${p.failed} failed`);
  if (p.cancelled) parts.push(`${p.cancelled} cancelled`);
  if (p.cached) parts.push(`${p.cached} from the store`);
  if (isLive(c) && typeof eta === 'number') parts.push(`${etaText} ${duration(eta)}${etaText === 'at most' ? ' left' : ''}`);
  return {fraction: fraction ?? 0, text: parts.join(', ')};
}

export function progressCell(c) {
  const {fraction, text} = progressOf(c);
  return progressBar(fraction, text);
}
