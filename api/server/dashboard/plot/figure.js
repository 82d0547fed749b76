// A plot as a <figure>: caption, the SVG, a legend in HTML (marker, dash and name, so no series is
// told apart by colour alone) and a readout line that names what the keyboard or mouse points at.
import {h} from '../dom.js';
import {marker, s} from './svg.js';

function swatch(item) {
  const svg = s('svg', {width: 34, height: 14, viewBox: '0 0 34 14', 'aria-hidden': 'true'});
  if (item.hatch) {
    svg.append(s('rect', {x: 1, y: 1, width: 32, height: 12, fill: '#f3f3f3', stroke: '#aaa'}));
    for (let x = -8; x < 34; x += 6) svg.append(s('line', {x1: x, y1: 13, x2: x + 12, y2: 1, stroke: '#aaa', 'stroke-width': 1.5}));
  } else if (item.bar) {
    svg.append(s('rect', {x: 6, y: 1, width: 22, height: 12, stroke: item.colour, 'stroke-width': 1.2,
      fill: item.hatched ? '#fff' : item.colour}));
    if (item.hatched) {
      for (let k = 0; k < 3; ++k) {
        svg.append(s('line', {x1: 8 + 6 * k, y1: 12, x2: 14 + 6 * k, y2: 2, stroke: item.colour, 'stroke-width': 2}));
      }
    }
  } else if (item.band) {
    svg.append(s('rect', {x: 1, y: 2, width: 32, height: 10, class: 'band'}));
  } else if (item.line !== false) {
    svg.append(s('line', {x1: 1, x2: 33, y1: 7, y2: 7, stroke: item.colour, 'stroke-width': 2,
      'stroke-dasharray': item.dash || null}));
  }
  if (item.marker) {
    svg.append(marker(item.marker, 17, 7, 8, {fill: item.hollow ? '#fff' : item.colour, stroke: item.colour, 'stroke-width': 1.5}));
  }
  return svg;
}

export function legend(items) {
  if (!items || items.length === 0) return null;
  return h('ul', {class: 'legend'}, items.map((item) => h('li', {}, swatch(item), ' ', item.name)));
}

export function figure({title, caption, svg, legendItems, readout, className}) {
  return h('figure', {class: `plot ${className || ''}`},
    h('figcaption', {}, h('strong', {}, title), caption ? [' ', h('span', {class: 'caption'}, caption)] : null),
    svg,
    legend(legendItems),
    readout);
}

export function readoutLine(hint) {
  return h('p', {class: 'readout', 'aria-live': 'polite'}, hint || '');
}

// The SVG root: `width` CSS pixels wide, scaled down with its container.
export function svgRoot(width, height, label) {
  return s('svg', {class: 'chart', viewBox: `0 0 ${width} ${height}`, width, height,
    role: 'group', 'aria-label': label, preserveAspectRatio: 'xMinYMin meet'});
}
