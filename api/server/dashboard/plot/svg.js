// SVG elements: s('circle', {cx: 1, cy: 2, r: 3}, s('title', {}, 'label')).
const NS = 'http://www.w3.org/2000/svg';

export function s(tag, attrs = {}, ...children) {
  const el = document.createElementNS(NS, tag);
  for (const [key, value] of Object.entries(attrs)) {
    if (value === undefined || value === null || value === false) continue;
    if (key === 'text') el.textContent = value;
    else if (key === 'dataset') Object.assign(el.dataset, value);
    else if (key.startsWith('on') && typeof value === 'function') el.addEventListener(key.slice(2), value);
    else el.setAttribute(key, String(value));
  }
  for (const child of children.flat(Infinity)) {
    if (child === undefined || child === null || child === false) continue;
    el.append(child instanceof Node ? child : document.createTextNode(String(child)));
  }
  return el;
}

// A marker shape centred on (x, y): circle, square, triangle, diamond, cross, star.
export function marker(shape, x, y, size, attrs = {}) {
  const r = size / 2;
  switch (shape) {
    case 'square':
      return s('rect', {x: x - r, y: y - r, width: size, height: size, ...attrs});
    case 'triangle':
      return s('path', {d: `M${x},${y - r * 1.15}L${x + r},${y + r * 0.85}L${x - r},${y + r * 0.85}Z`, ...attrs});
    case 'diamond':
      return s('path', {d: `M${x},${y - r * 1.2}L${x + r},${y}L${x},${y + r * 1.2}L${x - r},${y}Z`, ...attrs});
    case 'cross':
      return s('path', {d: `M${x - r},${y - r}L${x + r},${y + r}M${x - r},${y + r}L${x + r},${y - r}`,
        'stroke-width': 2, fill: 'none', ...attrs, stroke: attrs.stroke || attrs.fill});
    case 'star': {
      let d = '';
      for (let i = 0; i < 10; ++i) {
        const a = -Math.PI / 2 + (i * Math.PI) / 5;
        const rr = i % 2 ? r * 0.5 : r * 1.3;
        d += `${i ? 'L' : 'M'}${(x + rr * Math.cos(a)).toFixed(2)},${(y + rr * Math.sin(a)).toFixed(2)}`;
      }
      return s('path', {d: d + 'Z', ...attrs});
    }
    default:
      return s('circle', {cx: x, cy: y, r, ...attrs});
  }
}
