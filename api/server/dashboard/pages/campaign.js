// One campaign: its header (state, progress, cancel) and the page of its kind, refreshed while it
// runs. The kind's page gets the campaign and a cache for what does not change (finished jobs'
// curves).
import {deleteJson} from '../api.js';
import {badge, clear, facts, h, rememberFocus} from '../dom.js';
import {dateTime} from '../format.js';
import {watchJson} from '../poll.js';
import {renderCalibration} from './calibration.js';
import {renderDiagnosis} from './diagnosis.js';
import {isLive, progressCell} from './progress.js';
import {renderResultsTable} from './results.js';
import {renderSweep} from './sweep.js';

const KINDS = {sweep: renderSweep, calibration: renderCalibration, diagnosis: renderDiagnosis};
// What the campaign's driver (the search of a calibration or diagnosis) is doing, in words.
const DRIVER = {running: 'search running', done: 'report ready', failed: 'search failed (see below)',
  cancelled: 'stopped before its report'};

export async function render([idText], ctx) {
  const id = Number(idText);
  if (!Number.isInteger(id) || id <= 0) throw new Error(`"${idText}" is not a campaign id`);
  ctx.setTitle(`Campaign #${id}`);
  const head = h('div', {id: 'campaign-head'});
  const body = h('div', {id: 'campaign-body'});
  ctx.main.append(head, body);
  const cache = new Map();
  await watchJson(`/api/v1/campaigns/${id}`, {
    signal: ctx.signal,
    resize: ctx.main,
    live: isLive,
    // Each update of a sweep's page fetches every job's row: 2 ms more per job between updates.
    slower: (c) => 2 * ((c.progress && c.progress.total) || 0),
    missing: (e) => clear(head).append(h('h1', {}, `Campaign #${id}`), h('p', {class: 'error', role: 'alert'}, e.message)),
    show: async (c) => {
      ctx.setTitle(`#${c.id} ${c.name}`);
      const renderKind = KINDS[c.kind] || renderResultsTable;
      // The new view is built off screen and swapped in at once; keyboard focus stays where it was.
      const next = await renderKind(c, {...ctx, cache});
      const focus = rememberFocus(ctx.main);
      clear(head).append(header(c, ctx));
      clear(body).append(next);
      focus.restore();
    },
  });
}

function header(c, ctx) {
  const live = isLive(c);
  const links = [
    h('a', {href: `/api/v1/campaigns/${c.id}`}, 'JSON'),
    ' · ', h('a', {href: `/api/v1/campaigns/${c.id}/results?format=csv`}, 'results CSV'),
  ];
  if (c.kind === 'diagnosis' && c.driver_status === 'done') {
    links.push(' · ', h('a', {href: `/api/v1/campaigns/${c.id}/report.html`}, 'HTML report'));
  }
  return h('div', {class: 'campaign-head'},
    h('div', {class: 'page-head'},
      h('h1', {}, h('span', {class: 'muted'}, `#${c.id} `), c.name || '(unnamed)'),
      live && !c.cancel_requested ? cancelButton(c, ctx) : null),
    facts([
      ['kind', c.kind],
      ['state', [badge(c.state), c.driver_status ? ` · ${DRIVER[c.driver_status] || c.driver_status}` : '',
        c.cancel_requested && c.state !== 'cancelled' ? ' cancelling…' : '']],
      ['progress', progressCell(c)],
      ['created', dateTime(c.created_at)],
      ['data', links],
    ]),
    h('p', {class: 'error', role: 'alert', id: 'cancel-error', hidden: true}));
}

function cancelButton(c, ctx) {
  const button = h('button', {class: 'danger', type: 'button', id: 'cancel'}, 'Cancel campaign');
  button.addEventListener('click', async () => {
    if (!confirm(`Cancel campaign #${c.id} (${c.name})? Running jobs are stopped.`)) return;
    button.disabled = true;
    const err = document.getElementById('cancel-error');
    try {
      await deleteJson(`/api/v1/campaigns/${c.id}`);
      ctx.navigate(`/campaigns/${c.id}`, {replace: true});
    } catch (e) {
      button.disabled = false;
      err.hidden = false;
      err.textContent = e.status === 401
        ? `${e.message}. Set the server's token under "Token" at the top of the page.`
        : e.message;
    }
  });
  return button;
}
