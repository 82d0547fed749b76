// An x-y plot: curves (polylines) and point series (markers, optional error bars), horizontal
// reference lines (targets) with tolerance bands, second axes in other units, keyboard access.
import {num} from '../format.js';
import {axes, margins} from './axes.js';
import {DASHES, MARKERS, SERIES} from './colour.js';
import {figure, readoutLine, svgRoot} from './figure.js';
import {cursor, navigable} from './focus.js';
import {extent, scale} from './scale.js';
import {marker, s} from './svg.js';

// series: [{name, points: [{x, y, label, href, key, xErr, yErr}], line, marker, dash, colour,
//           step, cursor}]
//  - line: a polyline through the points; marker: a shape at each point (a navigable mark).
//  - cursor: the series is followed by the crosshair (curves with many points).
// hlines: [{y, label, dash, band: [lo, hi]}]
// x, y: {label, log, include, min, max, second: {factor, label}}
export function linePlot({title, caption, width = 640, height = 300, x = {}, y = {}, series = [],
  hlines = [], onActivate, hint}) {
  const m = margins({x2: x.second, y2: y.second});
  const w = Math.max(120, width - m.left - m.right);
  const ph = Math.max(80, height - m.top - m.bottom);
  const finite = (v) => typeof v === 'number' && Number.isFinite(v);
  const xs = [];
  const ys = [];
  series.forEach((sr, i) => {
    sr.style = {colour: sr.colour || SERIES[i % SERIES.length],
      marker: sr.marker === undefined ? MARKERS[i % MARKERS.length] : sr.marker,
      dash: sr.dash === undefined ? DASHES[i % DASHES.length] : sr.dash};
    for (const p of sr.points) {
      if (finite(p.x)) xs.push(p.x, ...(finite(p.xErr) ? [p.x - p.xErr, p.x + p.xErr] : []));
      if (finite(p.y)) ys.push(p.y, ...(finite(p.yErr) ? [p.y - p.yErr, p.y + p.yErr] : []));
    }
  });
  for (const l of hlines) {
    if (finite(l.y)) ys.push(l.y);
    if (l.band) ys.push(...l.band.filter(finite));
  }
  const xd = [x.min ?? extent(xs, {log: x.log, include: x.include || []})[0],
    x.max ?? extent(xs, {log: x.log, include: x.include || []})[1]];
  const yd = [y.min ?? extent(ys, {log: y.log, include: y.include || []})[0],
    y.max ?? extent(ys, {log: y.log, include: y.include || []})[1]];
  const px = scale(xd, [0, w], {log: x.log});
  const py = scale(yd, [ph, 0], {log: y.log});
  const svg = svgRoot(width, height, title);
  const plot = s('g', {transform: `translate(${m.left},${m.top})`});
  svg.append(plot);
  plot.append(axes({x: px, y: py, w, h: ph, xLabel: x.label, yLabel: y.label, x2: x.second, y2: y.second}));

  const clipId = `clip-${Math.random().toString(36).slice(2)}`;
  svg.append(s('defs', {}, s('clipPath', {id: clipId}, s('rect', {x: 0, y: 0, width: w, height: ph}))));
  const inside = s('g', {'clip-path': `url(#${clipId})`});
  plot.append(inside);

  for (const l of hlines) {
    if (l.band && l.band.every(finite)) {
      const [a, b] = l.band.map(py);
      inside.append(s('rect', {class: 'band', x: 0, width: w, y: Math.min(a, b), height: Math.abs(a - b)}));
    }
    if (!finite(l.y)) continue;
    inside.append(s('line', {class: 'refline', x1: 0, x2: w, y1: py(l.y), y2: py(l.y),
      'stroke-dasharray': l.dash || '7 4'}));
    // Above its line, or below it when the line runs along the top of the frame.
    const ly = py(l.y) < 16 ? py(l.y) + 14 : py(l.y) - 5;
    plot.append(s('text', {class: 'reflabel', x: w - 4, y: ly, 'text-anchor': 'end'}, l.label));
  }

  const marks = [];
  let followed = null;
  for (const sr of series) {
    const pts = sr.points.filter((p) => finite(p.x) && finite(p.y) && (!x.log || p.x > 0) && (!y.log || p.y > 0));
    const group = s('g', {class: 'series', dataset: {series: sr.name, points: pts.length}});
    if (sr.line && pts.length > 1) {
      let d = '';
      pts.forEach((p, i) => {
        const X = px(p.x).toFixed(2);
        const Y = py(p.y).toFixed(2);
        if (i === 0) d = `M${X},${Y}`;
        else if (sr.step) d += `H${X}V${Y}`;
        else d += `L${X},${Y}`;
      });
      group.append(s('path', {class: 'line', d, fill: 'none', stroke: sr.style.colour, 'stroke-width': 2,
        'stroke-dasharray': sr.style.dash, 'stroke-linejoin': 'round'}));
    }
    if (sr.style.marker && !sr.cursor) {
      for (const p of pts) {
        const X = px(p.x);
        const Y = py(p.y);
        const g = s('g', {class: 'point'});
        if (finite(p.yErr)) {
          g.append(s('line', {class: 'errbar', x1: X, x2: X, y1: py(p.y - p.yErr), y2: py(p.y + p.yErr), stroke: sr.style.colour}));
        }
        if (finite(p.xErr)) {
          g.append(s('line', {class: 'errbar', y1: Y, y2: Y, x1: px(p.x - p.xErr), x2: px(p.x + p.xErr), stroke: sr.style.colour}));
        }
        g.append(marker(p.marker || sr.style.marker, X, Y, p.size || sr.size || 8,
          {fill: p.hollow || sr.hollow ? '#fff' : sr.style.colour, stroke: sr.style.colour, 'stroke-width': 1.5}));
        group.append(g);
        marks.push({el: g, label: p.label || `${sr.name}: x ${num(p.x)}, y ${num(p.y)}`, href: p.href, key: p.key});
      }
    }
    inside.append(group);
    if (sr.cursor) followed = pts;
  }
  const readout = readoutLine(hint || (followed ? 'Pointer or arrow keys: read the curve point by point.'
    : marks.length ? 'Pointer or Tab then arrow keys: read each point.' : ''));
  if (followed) {
    plot.append(cursor(followed, {px, py, w, h: ph, readout, label: title}));
  }
  // Marks above the curve's pointer layer, so that they keep their own hover and click.
  const markLayer = s('g', {class: 'marks'});
  for (const mk of marks) markLayer.append(mk.el);
  plot.append(markLayer);
  navigable(marks, {readout, onActivate});
  svg.dataset.points = String(marks.length + (followed ? followed.length : 0));
  const legendItems = series.filter((sr) => sr.name).map((sr) => ({name: sr.name,
    colour: sr.style.colour, marker: sr.cursor ? null : sr.style.marker, dash: sr.style.dash, line: !!sr.line,
    hollow: sr.hollow}))
    .concat(hlines.filter((l) => l.legend).map((l) => ({name: l.legend, colour: '#333', dash: l.dash || '7 4', line: true})))
    .concat(hlines.filter((l) => l.band && l.bandLegend).map((l) => ({name: l.bandLegend, band: true})));
  return figure({title, caption, svg, legendItems, readout});
}
