// A campaign's progress in words and as a bar: jobs for a sweep, evaluations for a calibration
// (its jobs are not known in advance), the phase for a diagnosis.
import {progressBar} from '../dom.js';
import {duration} from '../format.js';

export function isLive(c) {
  return c.state === 'queued' || c.state === 'running' || c.driver_status === 'running';
}

function progressOf(c) {
  const p = c.progress || {};
  const s = c.summary || {};
  const parts = [];
  let fraction = p.fraction;
  // A driver (calibration, diagnosis) adds jobs as it goes, so the server's ETA covers only the
  // jobs queued now.
  const etaText = c.driver_status ? 'queued jobs done in' : 'ETA';
  if (c.kind === 'calibration' && typeof s.evaluations === 'number') {
    parts.push(`${s.evaluations} of ${s.max_evaluations} evaluations`);
    if (isLive(c)) {
      fraction = s.max_evaluations ? s.evaluations / s.max_evaluations : fraction;
    } else {
      fraction = 1;
    }
  } else if (c.kind === 'diagnosis' && typeof s.phase === 'string') {
    parts.push(`phase ${s.step} of ${s.steps}: ${s.phase}`);
    if (s.steps) fraction = (s.step - 1 + (p.fraction || 0)) / s.steps;
  }
  parts.push(`${p.succeeded ?? 0} of ${p.total ?? 0} jobs done`);
  if (p.running) parts.push(`${p.running} running`);
  if (p.queued) parts.push(`${p.queued} queued`);
  if (p.failed) parts.push(`${p.failed} failed`);
  if (p.cancelled) parts.push(`${p.cancelled} cancelled`);
  if (p.cached) parts.push(`${p.cached} from the store`);
  if (isLive(c) && typeof p.eta_seconds === 'number' && (p.queued || p.running)) {
    parts.push(`${etaText} ${duration(p.eta_seconds)}`);
  }
  return {fraction: fraction ?? 0, text: parts.join(', ')};
}

export function progressCell(c) {
  const {fraction, text} = progressOf(c);
  return progressBar(fraction, text);
}
