// A heat map over a grid (F_r0 across, F_s0 up): one cell per grid point, its value written in the
// cell when it fits, colour from viridis with a colour bar, hatching where there is no value, and
// iso-lines (targets) drawn by marching squares. Cells are keyboard navigable (arrows by row and
// column) and link to their job.
import {num} from '../format.js';
import {textOn, viridis} from './colour.js';
import {isoSegments} from './contour.js';
import {figure, readoutLine, svgRoot} from './figure.js';
import {navigable} from './focus.js';
import {scale} from './scale.js';
import {s} from './svg.js';

// values[iy][ix]: number or null. cell(ix, iy) -> {label, href, key, note}.
// isolines: [{field (like values), level, label, dash}]
export function heatMap({title, caption, width = 640, xs, ys, values, xLabel, yLabel, valueLabel,
  log = false, isolines = [], cell, onActivate, format = (v) => num(v, 3)}) {
  const nx = xs.length;
  const ny = ys.length;
  const m = {top: 14, right: 92, bottom: 50, left: 70};
  const w = Math.max(120, width - m.left - m.right);
  const ph = Math.round(Math.min(420, Math.max(ny * 26, 150, Math.min(w * ny / nx, 360))));
  const height = ph + m.top + m.bottom;
  const cw = w / nx;
  const ch = ph / ny;
  const finite = values.flat().filter((v) => typeof v === 'number' && Number.isFinite(v) && (!log || v > 0));
  const lo = finite.length ? Math.min(...finite) : 0;
  const hi = finite.length ? Math.max(...finite) : 1;
  const t = (v) => {
    if (hi === lo) return 0.5;
    return log ? Math.log(v / lo) / Math.log(hi / lo) : (v - lo) / (hi - lo);
  };

  const svg = svgRoot(width, height, title);
  const hatch = `hatch-${Math.random().toString(36).slice(2)}`;
  svg.append(s('defs', {}, s('pattern', {id: hatch, width: 6, height: 6, patternUnits: 'userSpaceOnUse',
    patternTransform: 'rotate(45)'}, s('rect', {width: 6, height: 6, fill: '#f3f3f3'}),
  s('line', {x1: 0, y1: 0, x2: 0, y2: 6, stroke: '#aaa', 'stroke-width': 2}))));
  const plot = s('g', {transform: `translate(${m.left},${m.top})`});
  svg.append(plot);

  const marks = [];
  const cells = s('g', {class: 'cells'});
  for (let iy = ny - 1; iy >= 0; --iy) {
    for (let ix = 0; ix < nx; ++ix) {
      const v = values[iy][ix];
      const has = typeof v === 'number' && Number.isFinite(v) && (!log || v > 0);
      const X = ix * cw;
      const Y = (ny - 1 - iy) * ch;
      const info = cell ? cell(ix, iy) : {};
      const g = s('g', {class: has ? 'cell' : 'cell missing'});
      g.append(s('rect', {x: X, y: Y, width: cw, height: ch, fill: has ? viridis(t(v)) : `url(#${hatch})`}));
      if (cw >= 34 && ch >= 16) {
        g.append(s('text', {x: X + cw / 2, y: Y + ch / 2 + 4, 'text-anchor': 'middle',
          fill: has ? textOn(t(v)) : '#555', class: 'cell-text'}, has ? format(v) : info.note || '–'));
      }
      cells.append(g);
      marks.push({el: g, label: info.label || `${num(xs[ix])}, ${num(ys[iy])}: ${has ? num(v) : 'no value'}`,
        href: info.href, key: info.key ?? `${ix},${iy}`});
    }
  }
  plot.append(cells);

  // Iso-lines in grid coordinates -> pixels (cell centres).
  const toPx = ([gx, gy]) => [(gx + 0.5) * cw, (ny - 1 - gy + 0.5) * ch];
  const lines = s('g', {class: 'isolines', 'pointer-events': 'none'});
  const placed = [];  // label positions so far: the next one moves down until it is clear of them
  for (const iso of isolines) {
    const field = iso.field.map((row) => row.map((v) => (typeof v === 'number' && v > 0 ? Math.log(v) : null)));
    const segs = isoSegments(field, Math.log(iso.level));
    if (segs.length === 0) continue;
    const d = segs.map((seg) => seg.map(toPx).map(([a, b], k) => `${k ? 'L' : 'M'}${a.toFixed(1)},${b.toFixed(1)}`).join('')).join('');
    lines.append(s('path', {class: 'iso-halo', d}), s('path', {class: 'iso', d, 'stroke-dasharray': iso.dash || null,
      dataset: {level: iso.level, segments: segs.length}}));
    // The label at the line's point nearest the top right corner, clear of the labels before it.
    const ends = segs.flat().map(toPx);
    const [lx, ly] = ends.reduce((a, b) => (b[0] - b[1] > a[0] - a[1] ? b : a));
    const x = Math.max(40, Math.min(lx, w - 40));
    let y = Math.max(ly - 6, 12);
    while (placed.some(([px, py]) => Math.abs(px - x) < 90 && Math.abs(py - y) < 14) && y < ph - 4) y += 14;
    placed.push([x, y]);
    lines.append(s('text', {class: 'iso-label', x, y, 'text-anchor': 'middle'}, iso.label));
  }
  plot.append(lines);

  // Axes: ticks at the grid values (the sweep's own points).
  const axis = s('g', {class: 'axes'});
  const every = Math.max(1, Math.ceil(nx / Math.max(1, Math.floor(w / 48))));
  const xAxis = s('g', {class: 'axis x', transform: `translate(0,${ph})`});
  xs.forEach((v, ix) => {
    if (ix % every !== 0 && ix !== nx - 1) return;
    xAxis.append(s('line', {x1: (ix + 0.5) * cw, x2: (ix + 0.5) * cw, y1: 0, y2: 5}),
      s('text', {x: (ix + 0.5) * cw, y: 18, 'text-anchor': 'middle'}, num(v, 3)));
  });
  xAxis.append(s('text', {class: 'label', x: w / 2, y: 38, 'text-anchor': 'middle'}, xLabel));
  const everyY = Math.max(1, Math.ceil(ny / Math.max(1, Math.floor(ph / 18))));
  const yAxis = s('g', {class: 'axis y'});
  ys.forEach((v, iy) => {
    if (iy % everyY !== 0 && iy !== ny - 1) return;
    const Y = (ny - 1 - iy + 0.5) * ch;
    yAxis.append(s('line', {x1: -5, x2: 0, y1: Y, y2: Y}),
      s('text', {x: -8, y: Y + 4, 'text-anchor': 'end'}, num(v, 3)));
  });
  yAxis.append(s('text', {class: 'label', transform: `translate(-56,${ph / 2}) rotate(-90)`, 'text-anchor': 'middle'}, yLabel));
  axis.append(s('rect', {class: 'frame', x: 0, y: 0, width: w, height: ph, fill: 'none'}), xAxis, yAxis);
  plot.append(axis);

  // The colour bar, with its own ticks in the value's units.
  if (finite.length) {
    const bar = s('g', {class: 'colourbar', transform: `translate(${w + 16},0)`});
    const gid = `grad-${Math.random().toString(36).slice(2)}`;
    const grad = s('linearGradient', {id: gid, x1: 0, y1: 1, x2: 0, y2: 0});
    for (let k = 0; k <= 10; ++k) grad.append(s('stop', {offset: `${k * 10}%`, 'stop-color': viridis(k / 10)}));
    svg.querySelector('defs').append(grad);
    bar.append(s('rect', {x: 0, y: 0, width: 14, height: ph, fill: `url(#${gid})`, stroke: '#666'}));
    const sc = scale(hi === lo ? [lo * 0.9 || -1, hi * 1.1 || 1] : [lo, hi], [ph, 0], {log: log && lo > 0});
    for (const v of sc.ticks(5)) {
      bar.append(s('line', {x1: 14, x2: 19, y1: sc(v), y2: sc(v), stroke: '#333'}),
        s('text', {x: 22, y: sc(v) + 4}, num(v, 3)));
    }
    bar.append(s('text', {class: 'label', transform: `translate(${70},${ph / 2}) rotate(90)`, 'text-anchor': 'middle'}, valueLabel));
    plot.append(bar);
  }

  const readout = readoutLine('Tab to the map, then arrow keys: read each cell; Enter opens its job.');
  navigable(marks, {readout, columns: nx, onActivate});
  svg.dataset.points = String(marks.length);
  const legendItems = isolines.filter((i) => i.legend).map((i) => ({name: i.legend, colour: '#111', dash: i.dash, line: true}));
  const missing = marks.length - finite.length;
  return figure({title, caption, svg, readout, className: 'heat',
    legendItems: legendItems.concat(missing > 0 ? [{name: `hatched: no value (${missing} of ${marks.length})`, hatch: true}] : [])});
}
