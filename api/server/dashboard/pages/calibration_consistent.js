// The consistent set of strengths (which (F_r0, F_s0) match both target loads within their
// uncertainty), whether it is unique and why (the report's reason), and what would narrow it when
// it is not.
import {h, note, section, table} from '../dom.js';
import {newtons, num, pm} from '../format.js';
import {linePlot} from '../plot/line_plot.js';

const range = (r) => (Array.isArray(r) && r.length === 2 ? `${num(r[0])} – ${num(r[1])}` : '–');
const stat = (v) => (v && Number.isFinite(v.mean) ? pm(v.mean, v.se) : '–');

export function consistentSection(s, lab, width) {
  const c = s.consistent;
  const parts = [];
  // The report's own reason (consistent.why), never a fixed sentence.
  const why = c && typeof c.why === 'string' && c.why ? `${c.why}.` : '';
  if (s.unique === true) {
    parts.push(h('p', {class: 'verdict verdict-feasible'}, h('strong', {}, 'Unique: '), why));
  } else if (s.unique === false) {
    parts.push(h('p', {class: 'verdict verdict-compromise'}, h('strong', {}, 'Not unique: '), why));
  }
  const loads = s.targets && s.targets.units === 'lab' ? 'both lab loads' : 'both target loads (model units)';
  if (c) {
    parts.push(table([
      {label: 'quantity', value: (r) => r[0]},
      {label: 'consistent range', num: true, value: (r) => r[1]},
    ], [['F_r0 (N, model)', range(c.fr0)], ['F_s0 (N, model)', range(c.fs0)], ['F_s0 / F_r0', range(c.ratio)]],
    {caption: `Strengths consistent with ${loads}`}));
    const points = Array.isArray(c.points) ? c.points : [];
    if (points.length) {
      parts.push(h('div', {class: 'plots'},
        linePlot({title: 'Consistent strengths', width, height: 280,
          caption: `${points.length} points`,
          x: {label: 'F_r0 (N, model units, log)', log: true}, y: {label: 'F_s0 (N, model units, log)', log: true},
          series: [{name: 'consistent point', marker: 'diamond', colour: '#009E73',
            points: points.map((p, i) => ({x: p.fr0, y: p.fs0, key: `c${i}`,
              label: `F_r0 ${num(p.fr0)} N, F_s0 ${num(p.fs0)} N: UCT ${stat(p.uct)} N, BTT ${stat(p.btt)} N`}))}]}),
        table([
          {label: 'F_r0 (N)', num: true, value: (p) => num(p.fr0)},
          {label: 'F_s0 (N)', num: true, value: (p) => num(p.fs0)},
          {label: 'UCT mean ± se (N)', num: true, value: (p) => stat(p.uct)},
          {label: 'BTT mean ± se (N)', num: true, value: (p) => stat(p.btt)},
          lab ? {label: 'UCT (lab)', num: true, value: (p) => newtons(p.uct && p.uct.mean * lab.force)} : null,
          lab ? {label: 'BTT (lab)', num: true, value: (p) => newtons(p.btt && p.btt.mean * lab.force)} : null,
        ].filter(Boolean), points)));
    }
  }
  const g = s.suggestion;
  if (g) {
    parts.push(h('p', {}, h('strong', {}, 'To narrow it: '), `measure ${g.observable}`,
      Array.isArray(g.values) && g.values.length ? ` (${g.values.map((v) => num(v)).join(', ')})` : '',
      g.why ? ` — ${g.why}` : ''));
  }
  if (!c && s.unique === undefined) parts.push(note('The report has no consistent set.'));
  return section('Consistent strengths', ...parts);
}
