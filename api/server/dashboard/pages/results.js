// A campaign's jobs as a table (every kind has it; the page of a kind without its own view): units
// in the headers, and why a job has no values (its error's first line).
import {getJson} from '../api.js';
import {badge, h, table} from '../dom.js';
import {newtons, num, pascals} from '../format.js';

export function resultsTable(rows, {caption} = {}) {
  return table([
    {label: 'job', num: true, value: (r) => h('a', {href: `/jobs/${r.job_id}`}, `#${r.job_id}`)},
    {label: 'test', value: (r) => r.test},
    {label: 'F_r0 (N)', num: true, value: (r) => num(r.fr0)},
    {label: 'F_s0 (N)', num: true, value: (r) => num(r.fs0)},
    {label: 'peak load (N)', num: true, value: (r) => newtons(r.peak_load)},
    {label: 'strength (Pa)', num: true, value: (r) => [pascals(r.strength), r.strength_definition ? h('span', {class: 'muted'}, ` ${r.strength_definition.name}`) : '']},
    {label: 'E (Pa)', num: true, value: (r) => pascals(r.youngs_modulus)},
    {label: 'state', value: (r) => [badge(r.state), r.cached ? ' (stored)' : '']},
    {label: 'error', value: (r) => (r.error ? r.error.split('\n')[0] : '')},
  ], rows, {caption, rowAttrs: (r) => ({dataset: {job: r.job_id}})});
}

export async function fetchResults(c, ctx) {
  return (await getJson(`/api/v1/campaigns/${c.id}/results`, {signal: ctx.signal})).results;
}

export async function renderResultsTable(c, ctx) {
  const rows = await fetchResults(c, ctx);
  return h('section', {}, h('h2', {}, `Jobs (${rows.length})`), resultsTable(rows));
}
