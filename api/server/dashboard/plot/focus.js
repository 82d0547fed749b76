// Keyboard and pointer access to what a plot shows.
//  - navigable(): marks a user steps through with the arrow keys (one tab stop per plot, a roving
//    tabindex); Enter follows the mark's link. A grid (heat map) moves by rows with up and down.
//  - cursor(): a crosshair that follows a curve point by point (arrows; Page keys jump a tenth;
//    Home/End) or the pointer.
import {s} from './svg.js';

export function navigable(marks, {readout, columns = 0, onActivate} = {}) {
  const show = (m) => {
    if (readout) readout.textContent = m.label + (m.href ? ' (Enter opens it)' : '');
  };
  const move = (from, to) => {
    if (to < 0 || to >= marks.length || to === from) return;
    marks[from].el.setAttribute('tabindex', '-1');
    marks[to].el.setAttribute('tabindex', '0');
    marks[to].el.focus();
  };
  marks.forEach((m, i) => {
    const el = m.el;
    el.classList.add('mark');
    el.setAttribute('tabindex', i === 0 ? '0' : '-1');
    el.setAttribute('role', m.href ? 'link' : 'img');
    el.setAttribute('aria-label', m.label);
    if (m.key !== undefined) el.dataset.key = m.key;
    el.append(s('title', {}, m.label));
    el.addEventListener('focus', () => show(m));
    el.addEventListener('mouseenter', () => show(m));
    if (m.href && onActivate) el.addEventListener('click', () => onActivate(m));
    el.addEventListener('keydown', (e) => {
      const step = {ArrowRight: 1, ArrowLeft: -1, ArrowDown: columns || 1, ArrowUp: -(columns || 1)}[e.key];
      if (step !== undefined) {
        move(i, i + step);
      } else if (e.key === 'Home') {
        move(i, 0);
      } else if (e.key === 'End') {
        move(i, marks.length - 1);
      } else if ((e.key === 'Enter' || e.key === ' ') && m.href && onActivate) {
        onActivate(m);
      } else {
        return;
      }
      e.preventDefault();
    });
  });
}

// points: [{x, y, label}] in data units; px, py: the plot's scales. Returns the layer to append.
export function cursor(points, {px, py, w, h, readout, label}) {
  const layer = s('g', {class: 'cursor-layer'});
  const vline = s('line', {class: 'cursor', y1: 0, y2: h, visibility: 'hidden'});
  const dot = s('circle', {class: 'cursor-dot', r: 4.5, visibility: 'hidden'});
  const hit = s('rect', {class: 'hit', x: 0, y: 0, width: w, height: h, tabindex: 0, role: 'slider',
    'aria-label': `${label}: arrow keys step through the ${points.length} points`,
    'aria-valuemin': 0, 'aria-valuemax': Math.max(0, points.length - 1)});
  let index = -1;
  const show = (i) => {
    if (points.length === 0) return;
    index = Math.max(0, Math.min(points.length - 1, i));
    const p = points[index];
    vline.setAttribute('x1', px(p.x));
    vline.setAttribute('x2', px(p.x));
    dot.setAttribute('cx', px(p.x));
    dot.setAttribute('cy', py(p.y));
    vline.setAttribute('visibility', 'visible');
    dot.setAttribute('visibility', 'visible');
    hit.setAttribute('aria-valuenow', index);
    hit.setAttribute('aria-valuetext', p.label);
    if (readout) readout.textContent = p.label;
  };
  const nearest = (x) => {
    let best = 0;
    for (let i = 1; i < points.length; ++i) {
      if (Math.abs(px(points[i].x) - x) < Math.abs(px(points[best].x) - x)) best = i;
    }
    return best;
  };
  hit.addEventListener('pointermove', (e) => {
    const box = hit.getBoundingClientRect();
    const scaleX = w / (box.width || w);
    show(nearest((e.clientX - box.left) * scaleX));
  });
  hit.addEventListener('focus', () => show(index < 0 ? 0 : index));
  hit.addEventListener('keydown', (e) => {
    const jump = Math.max(1, Math.round(points.length / 10));
    const to = {ArrowRight: index + 1, ArrowLeft: index - 1, ArrowUp: index + 1, ArrowDown: index - 1,
      PageUp: index + jump, PageDown: index - jump, Home: 0, End: points.length - 1}[e.key];
    if (to === undefined) return;
    e.preventDefault();
    show(to);
  });
  layer.append(vline, dot, hit);
  return layer;
}
