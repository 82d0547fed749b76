// Axes with ticks, grid lines and labels that carry units; an optional second axis (top or right)
// shows the same positions in other units (lab units beside model units).
import {num} from '../format.js';
import {linearTicks, logTicks} from './scale.js';
import {s} from './svg.js';

// Ticks of the second axis: nice values in its own units, placed where value / factor falls.
function secondTicks(primary, factor) {
  const [d0, d1] = primary.domain.map((v) => v * factor);
  const lo = Math.min(d0, d1);
  const hi = Math.max(d0, d1);
  const ticks = primary.log ? logTicks(lo, hi) : linearTicks(lo, hi);
  return ticks.map((v) => ({value: v, at: primary(v / factor)}));
}

// x, y: scales from scale.js over the plot area [0, w] x [h, 0].
export function axes({x, y, w, h, xLabel, yLabel, x2, y2, xTicks = 6, yTicks = 5, xFormat = num, yFormat = num}) {
  const g = s('g', {class: 'axes'});
  const grid = s('g', {class: 'grid', 'aria-hidden': 'true'});
  const xt = x.ticks(xTicks);
  const yt = y.ticks(yTicks);
  for (const v of xt) grid.append(s('line', {x1: x(v), x2: x(v), y1: 0, y2: h}));
  for (const v of yt) grid.append(s('line', {x1: 0, x2: w, y1: y(v), y2: y(v)}));
  g.append(grid);
  g.append(s('rect', {class: 'frame', x: 0, y: 0, width: w, height: h, fill: 'none'}));

  const bottom = s('g', {class: 'axis x', transform: `translate(0,${h})`});
  for (const v of xt) {
    bottom.append(s('line', {x1: x(v), x2: x(v), y1: 0, y2: 5}),
      s('text', {x: x(v), y: 18, 'text-anchor': 'middle'}, xFormat(v)));
  }
  bottom.append(s('text', {class: 'label', x: w / 2, y: 36, 'text-anchor': 'middle'}, xLabel));
  g.append(bottom);

  const left = s('g', {class: 'axis y'});
  for (const v of yt) {
    left.append(s('line', {x1: -5, x2: 0, y1: y(v), y2: y(v)}),
      s('text', {x: -8, y: y(v) + 4, 'text-anchor': 'end'}, yFormat(v)));
  }
  left.append(s('text', {class: 'label', transform: `translate(${-52},${h / 2}) rotate(-90)`,
    'text-anchor': 'middle'}, yLabel));
  g.append(left);

  if (x2) {
    const top = s('g', {class: 'axis x2'});
    for (const t of secondTicks(x, x2.factor)) {
      if (t.at < -0.5 || t.at > w + 0.5) continue;
      top.append(s('line', {x1: t.at, x2: t.at, y1: -5, y2: 0}),
        s('text', {x: t.at, y: -9, 'text-anchor': 'middle'}, num(t.value)));
    }
    top.append(s('text', {class: 'label', x: w / 2, y: -26, 'text-anchor': 'middle'}, x2.label));
    g.append(top);
  }
  if (y2) {
    const right = s('g', {class: 'axis y2', transform: `translate(${w},0)`});
    for (const t of secondTicks(y, y2.factor)) {
      if (t.at < -0.5 || t.at > h + 0.5) continue;
      right.append(s('line', {x1: 0, x2: 5, y1: t.at, y2: t.at}),
        s('text', {x: 8, y: t.at + 4, 'text-anchor': 'start'}, num(t.value)));
    }
    right.append(s('text', {class: 'label', transform: `translate(${54},${h / 2}) rotate(90)`,
      'text-anchor': 'middle'}, y2.label));
    g.append(right);
  }
  return g;
}

// The margins the axes need around the plot area.
export function margins({x2, y2} = {}) {
  return {top: x2 ? 44 : 14, right: y2 ? 64 : 18, bottom: 46, left: 66};
}
