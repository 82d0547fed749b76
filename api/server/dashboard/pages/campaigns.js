// The campaigns list, newest first, with live state and progress (polled while any is live).
import {append, badge, clear, h, table} from '../dom.js';
import {dateTime} from '../format.js';
import {watchJson} from '../poll.js';
import {isLive, progressCell} from './progress.js';

const PAGE = 50;

export async function render(_params, ctx) {
  ctx.setTitle('Campaigns');
  const offset = Math.max(0, parseInt(ctx.query.get('offset') || '0', 10) || 0);
  const body = h('div', {id: 'campaigns'});
  ctx.main.append(h('div', {class: 'page-head'}, h('h1', {}, 'Campaigns'),
    h('a', {class: 'button', href: '/submit'}, 'Submit a campaign')), body);
  await watchJson(`/api/v1/campaigns?limit=${PAGE}&offset=${offset}`, {
    signal: ctx.signal,
    live: (list) => list.campaigns.some(isLive),
    show: (list) => append(clear(body), [view(list, offset)]),
  });
}

function view(list, offset) {
  if (list.total === 0) {
    return h('p', {}, 'No campaigns yet. ', h('a', {href: '/submit'}, 'Submit one'), ' or use ',
      h('code', {}, 'rockcal submit FILE.json'), '.');
  }
  const rows = list.campaigns;
  const pager = [];
  if (offset > 0) pager.push(h('a', {href: `/?offset=${Math.max(0, offset - PAGE)}`}, '← newer'));
  if (offset + rows.length < list.total) pager.push(h('a', {href: `/?offset=${offset + PAGE}`}, 'older →'));
  return [
    h('p', {class: 'note'}, `${list.total} campaigns; showing ${offset + 1}–${offset + rows.length}. `,
      'Live campaigns update every few seconds.'),
    table([
      {label: 'id', num: true, value: (c) => h('a', {href: `/campaigns/${c.id}`}, `#${c.id}`)},
      {label: 'name', value: (c) => h('a', {href: `/campaigns/${c.id}`}, c.name || '(unnamed)')},
      {label: 'kind', value: (c) => c.kind},
      {label: 'state', value: (c) => [badge(c.state), c.cancel_requested && c.state !== 'cancelled' ? ' cancelling' : '']},
      {label: 'progress', value: progressCell},
      {label: 'created', value: (c) => h('span', {class: 'nowrap'}, dateTime(c.created_at))},
    ], rows, {rowAttrs: (c) => ({dataset: {campaign: c.id, state: c.state}})}),
    pager.length ? h('p', {class: 'pager'}, pager) : null,
  ];
}
