// The figures of a campaign's server-rendered HTML report (GET /api/v1/campaigns/{id}/report.html)
// drawn by the dashboard's own code: every element with data-figures-fr0 and data-figures-fs0 gets
// the stress-strain curve and the fracture (pages/job_figures.js, as on the job page) of the
// campaign's UCT and BTT runs at that point. A copy of the report opened without the server keeps
// the element's note instead.
import {clear, note} from './dom.js';
import {jobFigures} from './pages/job_figures.js';
import {fetchResults} from './pages/results.js';

const same = (a, b) => Math.abs(a - b) <= 1e-9 * Math.max(Math.abs(a), Math.abs(b));

async function draw(el, campaignId, ctx) {
  const fr0 = Number(el.dataset.figuresFr0);
  const fs0 = Number(el.dataset.figuresFs0);
  const rows = await fetchResults({id: campaignId}, ctx);
  const width = Math.max(320, Math.min(640, el.clientWidth));
  const drawn = [];
  for (const test of ['uct', 'btt']) {
    const job = rows.find((r) => r.test === test && r.state === 'succeeded' && same(r.fr0, fr0) && same(r.fs0, fs0));
    if (job) drawn.push(await jobFigures(job.job_id, `${test.toUpperCase()} run at this point`, width, null, ctx));
  }
  clear(el).append(...(drawn.length ? drawn : [note(`The campaign has no finished UCT or BTT run at F_r0 ${fr0} N, F_s0 ${fs0} N.`)]));
}

const match = /^\/api\/v1\/campaigns\/(\d+)\/report\.html$/.exec(location.pathname);
if (match) {
  const ctx = {cache: new Map(), signal: undefined};
  for (const el of document.querySelectorAll('[data-figures-fr0]')) {
    draw(el, Number(match[1]), ctx).catch((e) => clear(el).append(note(`The figures could not be drawn: ${e.message}`)));
  }
}
