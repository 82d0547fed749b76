// Bar charts: grouped vertical bars per category with a shaded band per category (residuals with
// their noise band), and horizontal bars for scores. Series differ by fill pattern as well as
// colour; every bar group is a navigable mark.
import {num, signed} from '../format.js';
import {axes} from './axes.js';
import {SERIES} from './colour.js';
import {figure, readoutLine, svgRoot} from './figure.js';
import {navigable} from './focus.js';
import {extent, scale} from './scale.js';
import {s} from './svg.js';

function patterns(svg) {
  const id = `bars-${Math.random().toString(36).slice(2)}`;
  const defs = s('defs', {});
  SERIES.forEach((c, i) => {
    defs.append(s('pattern', {id: `${id}-${i}`, width: 5, height: 5, patternUnits: 'userSpaceOnUse', patternTransform: 'rotate(45)'},
      s('rect', {width: 5, height: 5, fill: '#fff'}), s('line', {x1: 0, y1: 0, x2: 0, y2: 5, stroke: c, 'stroke-width': 3})));
  });
  svg.append(defs);
  return (i, hatched) => (hatched ? `url(#${id}-${i})` : SERIES[i]);
}

// categories: [name]; series: [{name, values: [..], hatched, colourIndex}]; band: [half-width].
export function groupedBars({title, caption, width = 640, height = 320, categories, series, band,
  yLabel, bandLabel, describe}) {
  const labelRoom = Math.min(120, 8 + 6.2 * Math.max(...categories.map((c) => c.length)));
  const rotate = categories.length * 70 > width - 90;
  const m = {top: 14, right: 18, bottom: rotate ? 30 + labelRoom * 0.72 : 48, left: 66};
  const w = width - m.left - m.right;
  const ph = height - m.top - m.bottom;
  const vals = series.flatMap((sr) => sr.values).concat((band || []).flatMap((b) => [b, -b]));
  const py = scale(extent(vals, {include: [0]}), [ph, 0]);
  const bx = w / categories.length;
  const svg = svgRoot(width, height, title);
  const fill = patterns(svg);
  const plot = s('g', {transform: `translate(${m.left},${m.top})`});
  svg.append(plot);
  const px = scale([0, 1], [0, w]);
  px.ticks = () => [];
  plot.append(axes({x: px, y: py, w, h: ph, xLabel: '', yLabel}));
  const bars = s('g', {class: 'bars'});
  const marks = [];
  categories.forEach((cat, k) => {
    const g = s('g', {class: 'bar-group'});
    if (band && Number.isFinite(band[k])) {
      g.append(s('rect', {class: 'band', x: k * bx + 2, width: bx - 4, y: py(band[k]), height: py(-band[k]) - py(band[k])}));
    }
    const bw = (bx * 0.7) / series.length;
    series.forEach((sr, i) => {
      const v = sr.values[k];
      if (!Number.isFinite(v)) return;
      const x0 = k * bx + bx * 0.15 + i * bw;
      const ci = sr.colourIndex ?? i;
      g.append(s('rect', {class: 'bar', x: x0, width: bw - 1, y: Math.min(py(v), py(0)), height: Math.abs(py(v) - py(0)),
        fill: fill(ci, sr.hatched), stroke: SERIES[ci], 'stroke-width': 1.2}));
    });
    const tx = k * bx + bx / 2;
    g.append(rotate
      // Rotated labels end under their bars, so the last one stays inside the chart.
      ? s('text', {class: 'cat', transform: `translate(${tx + 4},${ph + 12}) rotate(-35)`, 'text-anchor': 'end'}, cat)
      : s('text', {class: 'cat', x: tx, y: ph + 18, 'text-anchor': 'middle'}, cat));
    bars.append(g);
    marks.push({el: g, key: cat, label: describe ? describe(k) :
      `${cat}: ${series.map((sr) => `${sr.name} ${signed(sr.values[k])}`).join(', ')}` +
      (band ? `; band ±${num(band[k], 3)}` : '')});
  });
  plot.append(bars);
  plot.append(s('line', {class: 'zero', x1: 0, x2: w, y1: py(0), y2: py(0)}));
  const readout = readoutLine('Tab to the chart, then arrow keys: read each observation.');
  navigable(marks, {readout});
  svg.dataset.points = String(marks.length);
  const legendItems = series.map((sr, i) => ({name: sr.name, colour: SERIES[sr.colourIndex ?? i], hatched: sr.hatched, bar: true}))
    .concat(band ? [{name: bandLabel, band: true}] : []);
  return figure({title, caption, svg, legendItems, readout});
}

// items: [{label, value, note, highlight}]
export function horizontalBars({title, caption, width = 640, items, xLabel, domain}) {
  const m = {top: 10, right: 24, bottom: 46, left: Math.min(220, 16 + 7 * Math.max(...items.map((i) => i.label.length)))};
  const rowH = 30;
  const height = m.top + m.bottom + rowH * items.length;
  const w = width - m.left - m.right;
  const ph = rowH * items.length;
  const vals = items.map((i) => i.value).filter(Number.isFinite);
  const px = scale(domain || extent(vals, {include: [0, 1]}), [0, w]);
  const svg = svgRoot(width, height, title);
  const fill = patterns(svg);
  const plot = s('g', {transform: `translate(${m.left},${m.top})`});
  svg.append(plot);
  const py = scale([0, 1], [ph, 0]);
  py.ticks = () => [];
  plot.append(axes({x: px, y: py, w, h: ph, xLabel, yLabel: ''}));
  const marks = [];
  items.forEach((it, k) => {
    const g = s('g', {class: it.highlight ? 'hbar highlight' : 'hbar'});
    const y = k * rowH + 6;
    if (Number.isFinite(it.value)) {
      g.append(s('rect', {class: 'bar', x: Math.min(px(0), px(it.value)), width: Math.abs(px(it.value) - px(0)), y, height: rowH - 12,
        fill: fill(it.highlight ? 0 : 6, !it.highlight), stroke: SERIES[it.highlight ? 0 : 6]}));
    }
    g.append(s('text', {class: 'cat', x: -8, y: y + rowH / 2 - 1, 'text-anchor': 'end'}, it.label));
    g.append(s('text', {class: 'value', x: Number.isFinite(it.value) ? Math.max(px(it.value), px(0)) + 5 : px(0) + 5,
      y: y + rowH / 2 - 1}, Number.isFinite(it.value) ? num(it.value, 3) : 'not scored'));
    plot.append(g);
    marks.push({el: g, key: it.label, label: `${it.label}: ${Number.isFinite(it.value) ? num(it.value, 3) : 'not scored'}${it.note ? ` (${it.note})` : ''}`});
  });
  plot.append(s('line', {class: 'zero', x1: px(0), x2: px(0), y1: 0, y2: ph}));
  const readout = readoutLine('Tab to the chart, then arrow keys: read each candidate.');
  navigable(marks, {readout});
  svg.dataset.points = String(marks.length);
  return figure({title, caption, svg, readout});
}
