// Points on a specimen's plane at the same scale on both axes: its outline (a rectangle for a
// cylinder seen from the side, a circle for a disc seen face on) and marks by group, each group
// with its own colour and marker shape (e.g. broken bonds by mode).
import {num} from '../format.js';
import {axes, margins} from './axes.js';
import {MARKERS, SERIES} from './colour.js';
import {figure, readoutLine, svgRoot} from './figure.js';
import {scale} from './scale.js';
import {marker, s} from './svg.js';

const MAX_PLOT_HEIGHT = 380;

// The specimen's outline in plot coordinates: a rectangle, an ellipse (a circle at equal scale), or
// a circle with two flats.
function outlineShape({shape, halfWidth: a, halfHeight: b, flatY}, px, py) {
  const attrs = {class: 'specimen-outline'};
  if (shape !== 'circle') return s('rect', {...attrs, x: px(-a), y: py(b), width: px(a) - px(-a), height: py(-b) - py(b)});
  const rx = px(a) - px(0);
  const ry = py(-b) - py(0);
  if (!(flatY > 0 && flatY < b)) return s('ellipse', {...attrs, cx: px(0), cy: py(0), rx, ry});
  const xf = a * Math.sqrt(1 - (flatY / b) ** 2);
  const d = `M${px(xf)},${py(flatY)} A${rx},${ry} 0 0 1 ${px(xf)},${py(-flatY)} L${px(-xf)},${py(-flatY)} ` +
    `A${rx},${ry} 0 0 1 ${px(-xf)},${py(flatY)} Z`;
  return s('path', {...attrs, d});
}

// outline: {shape: 'rect' | 'circle', halfWidth, halfHeight, flatY (a disc cut flat at |y| =
// flatY)}; groups: [{name, points: [[x, y]]}]
// (every group keeps its colour and marker by its place in the list, even when it is empty).
export function specimenMap({title, caption, width, outline, groups, xLabel, yLabel}) {
  const m = margins();
  const hw = outline.halfWidth * 1.08;
  const hh = outline.halfHeight * 1.08;
  let w = Math.max(120, width - m.left - m.right);
  let ph = Math.round((w * hh) / hw);
  if (ph > MAX_PLOT_HEIGHT) {
    ph = MAX_PLOT_HEIGHT;
    w = Math.round((ph * hw) / hh);
  }
  const px = scale([-hw, hw], [0, w]);
  const py = scale([-hh, hh], [ph, 0]);
  const svg = svgRoot(w + m.left + m.right, ph + m.top + m.bottom, title);
  const plot = s('g', {transform: `translate(${m.left},${m.top})`});
  svg.append(plot);
  plot.append(axes({x: px, y: py, w, h: ph, xLabel, yLabel, xTicks: 4, yTicks: 4}));
  const a = outline.halfWidth;
  const b = outline.halfHeight;
  plot.append(outlineShape(outline, px, py));
  let total = 0;
  const legendItems = groups.map((g, i) => {
    const colour = SERIES[i % SERIES.length];
    const shape = MARKERS[i % MARKERS.length];
    const layer = s('g', {class: 'series', dataset: {series: g.name, points: g.points.length}});
    for (const [x, y] of g.points) layer.append(marker(shape, px(x), py(y), 5, {fill: colour, stroke: colour}));
    plot.append(layer);
    total += g.points.length;
    return {name: `${g.name} (${g.points.length})`, colour, marker: shape, line: false};
  });
  svg.dataset.points = String(total);
  const counts = groups.map((g) => `${g.name} ${g.points.length}`).join(', ');
  return figure({title, caption, svg, legendItems, className: 'specimen-map',
    readout: readoutLine(`${num(total)} points: ${counts}.`)});
}
