// Building HTML without a framework: h('p', {class: 'note'}, 'text', child, ...).
// Attributes: `class`, `text`, `on<event>` handlers, `dataset` (object), `hidden`, others verbatim.

export function h(tag, attrs = {}, ...children) {
  const el = document.createElement(tag);
  setAttributes(el, attrs);
  append(el, children);
  return el;
}

function setAttributes(el, attrs) {
  for (const [key, value] of Object.entries(attrs || {})) {
    if (value === undefined || value === null || value === false) continue;
    if (key === 'text') el.textContent = value;
    else if (key === 'dataset') Object.assign(el.dataset, value);
    else if (key.startsWith('on') && typeof value === 'function') el.addEventListener(key.slice(2), value);
    else el.setAttribute(key, value === true ? '' : String(value));
  }
}

export function append(el, children) {
  for (const child of children.flat(Infinity)) {
    if (child === undefined || child === null || child === false) continue;
    el.append(child instanceof Node ? child : document.createTextNode(String(child)));
  }
  return el;
}

export function clear(el) {
  while (el.firstChild) el.firstChild.remove();
  return el;
}

// A table from column definitions: {label, value(row) -> string|Node, num: right-aligned}.
export function table(columns, rows, {caption, rowAttrs} = {}) {
  const head = h('tr', {}, columns.map((c) => h('th', {scope: 'col', class: c.num ? 'num' : null}, c.label)));
  const body = rows.map((row) =>
    h('tr', rowAttrs ? rowAttrs(row) : {},
      columns.map((c) => h('td', {class: c.num ? 'num' : null}, c.value(row)))));
  return h('div', {class: 'table-wrap'},
    h('table', {}, caption ? h('caption', {}, caption) : null, h('thead', {}, head), h('tbody', {}, body)));
}

// Label / value pairs as a definition list.
export function facts(pairs) {
  return h('dl', {class: 'facts'},
    pairs.filter(Boolean).map(([label, value]) => [h('dt', {}, label), h('dd', {}, value)]));
}

export function section(title, ...children) {
  return h('section', {}, h('h2', {}, title), ...children);
}

export function note(...children) {
  return h('p', {class: 'note'}, ...children);
}

export function link(href, ...children) {
  return h('a', {href}, ...children);
}

// A state badge: the word is always shown, the colour only repeats it.
export function badge(state) {
  return h('span', {class: `badge state-${state}`}, state);
}

// A progress bar with its numbers as text beside it.
export function progressBar(fraction, text) {
  const f = Math.max(0, Math.min(1, Number(fraction) || 0));
  const fill = h('span', {class: 'fill'});
  fill.style.width = `${(f * 100).toFixed(1)}%`;  // CSSOM, which the page's CSP allows (no inline style)
  return h('span', {class: 'progress'},
    h('span', {class: 'bar', role: 'progressbar', 'aria-valuemin': 0, 'aria-valuemax': 100,
      'aria-valuenow': Math.round(f * 100), 'aria-label': text || `${Math.round(f * 100)}%`}, fill),
    h('span', {class: 'progress-text'}, text || `${Math.round(f * 100)}%`));
}

// Where keyboard focus is (an element id, or a plot mark by its figure and data-key), so that a
// view rebuilt by a live update can put it back.
export function rememberFocus(root) {
  const el = document.activeElement;
  if (!el || el === root || !root.contains(el)) return {restore() {}};
  const id = el.id;
  const figures = [...root.querySelectorAll('figure')];
  const figure = el.closest('figure');
  const index = figure ? figures.indexOf(figure) : -1;
  const key = el.closest('[data-key]')?.dataset.key;
  const slider = el.getAttribute('role') === 'slider';
  return {
    restore() {
      let target = id ? document.getElementById(id) : null;
      const f = !target && index >= 0 ? root.querySelectorAll('figure')[index] : null;
      if (f && slider) target = f.querySelector('[role="slider"]');
      else if (f && key !== undefined) target = f.querySelector(`[data-key="${CSS.escape(key)}"]`);
      if (!target) return;
      if (f) {
        for (const m of f.querySelectorAll('.mark[tabindex="0"]')) m.setAttribute('tabindex', '-1');
        target.setAttribute('tabindex', '0');
      }
      target.focus({preventScroll: true});
    },
  };
}
