// Submitting a campaign: a JSON editor with starting templates, checked as JSON in the page and
// validated by the server, whose error names the field; the editor then selects that field.
import {getJson, getText, postJson} from '../api.js';
import {append, h, note} from '../dom.js';
import {TEMPLATES} from '../templates.js';

const DRAFT_KEY = 'rockcal.draft';

function draft() {
  try {
    return localStorage.getItem(DRAFT_KEY);
  } catch {
    return null;
  }
}

function saveDraft(text) {
  try {
    localStorage.setItem(DRAFT_KEY, text);
  } catch {
    // No storage: the draft lives only in the page.
  }
}

// Line and column of a character offset.
function lineCol(text, offset) {
  const before = text.slice(0, offset).split('\n');
  return {line: before.length, column: before[before.length - 1].length + 1};
}

// Where a field path ("job.sample.diameter", "grid.fr0[2]") is in the text: the offset of its last
// key, found key by key from the top; -1 when a key is not there.
function locateField(text, field) {
  if (!field || field === '(body)') return -1;
  let at = 0;
  let found = -1;
  for (const part of field.split('.')) {
    const key = part.replace(/\[\d+\]/g, '');
    if (!key) continue;
    const i = text.indexOf(`"${key}"`, at);
    if (i < 0) return found;
    found = i;
    at = i + key.length + 2;
  }
  return found;
}

// An example from the repository, its dataset_file put inline (the server takes datasets inline;
// `rockcal diagnose` does the same for a file on disk).
async function exampleRequest(file, ctx) {
  const request = await getJson(`/ui/${file}`, {signal: ctx.signal});
  if (typeof request.dataset_file === 'string') {
    const path = `examples/${request.dataset_file.replace(/^\.\//, '')}`;
    if (path.endsWith('.csv')) request.dataset_csv = await getText(`/ui/${path}`, {signal: ctx.signal});
    else request.dataset = await getJson(`/ui/${path}`, {signal: ctx.signal});
    delete request.dataset_file;
  }
  return request;
}

export async function render(_params, ctx) {
  ctx.setTitle('Submit a campaign');
  let examples = [];
  try {
    examples = await getJson('/ui/examples/index.json', {signal: ctx.signal});
  } catch (e) {
    if (e.name === 'AbortError') throw e;
  }
  const choice = h('select', {id: 'template', 'aria-label': 'start from a template'},
    h('option', {value: ''}, 'Start from a template…'),
    h('optgroup', {label: 'small'}, Object.entries(TEMPLATES).map(([k, t]) => h('option', {value: k}, t.title))),
    examples.length ? h('optgroup', {label: 'the repository\u2019s examples'},
      examples.map((x) => h('option', {value: x.file}, `${x.kind}: ${x.name} (${x.file})`))) : null);
  const editor = h('textarea', {id: 'request', spellcheck: 'false', autocomplete: 'off', rows: 24,
    'aria-describedby': 'request-status', 'aria-label': 'campaign request (JSON)'});
  const status = h('p', {id: 'request-status', class: 'note', 'aria-live': 'polite'});
  const error = h('div', {id: 'submit-error', class: 'error', role: 'alert', hidden: true});
  const submit = h('button', {type: 'submit', id: 'submit'}, 'Submit');
  const form = h('form', {class: 'submit-form'},
    h('div', {class: 'toolbar'}, choice, ' ', h('button', {type: 'button', onclick: format}, 'Format JSON'), ' ', submit),
    editor, status, error);
  ctx.main.append(h('h1', {}, 'Submit a campaign'),
    note('A campaign request as JSON: kind "sweep", "calibration" or "diagnosis" (see docs/calibration.md and docs/diagnosis.md). ',
      'The server checks the whole request before it stores anything and names the field at fault.'),
    form);

  const start = ctx.query.get('template');
  editor.value = (start && TEMPLATES[start] ? JSON.stringify(TEMPLATES[start].request, null, 2) : draft()) ||
    JSON.stringify(TEMPLATES.sweep.request, null, 2);

  function check() {
    try {
      const v = JSON.parse(editor.value);
      status.textContent = `Valid JSON${v && typeof v.kind === 'string' ? `, kind "${v.kind}"` : ''}.`;
      status.classList.remove('bad');
      return v;
    } catch (e) {
      const m = /position (\d+)/.exec(e.message);
      const where = m ? lineCol(editor.value, Number(m[1])) : null;
      status.textContent = `Not valid JSON${where ? ` at line ${where.line}, column ${where.column}` : ''}: ${e.message}`;
      status.classList.add('bad');
      return undefined;
    }
  }
  function format() {
    const v = check();
    if (v !== undefined) editor.value = JSON.stringify(v, null, 2);
  }
  editor.addEventListener('input', () => {
    saveDraft(editor.value);
    check();
  });
  choice.addEventListener('change', async () => {
    const key = choice.value;
    if (!key) return;
    let request;
    try {
      request = TEMPLATES[key] ? TEMPLATES[key].request : await exampleRequest(key, ctx);
    } catch (err) {
      if (err.name === 'AbortError') return;
      status.textContent = `Cannot load ${key}: ${err.message}`;
      return;
    }
    editor.value = JSON.stringify(request, null, 2);
    choice.value = '';  // a menu of starting points, not a state: the editor is the request
    saveDraft(editor.value);
    check();
  });
  check();

  form.addEventListener('submit', async (e) => {
    e.preventDefault();
    error.hidden = true;
    if (check() === undefined) {
      editor.focus();
      return;
    }
    submit.disabled = true;
    try {
      const created = await postJson('/api/v1/campaigns', editor.value, {signal: ctx.signal});
      ctx.navigate(`/campaigns/${created.id}`);
    } catch (err) {
      if (err.name === 'AbortError') return;
      submit.disabled = false;
      showError(err);
    }
  });

  function showError(err) {
    error.hidden = false;
    // The server's message may already start with the field's name.
    const message = err.field && err.message.startsWith(`${err.field}: `) ? err.message.slice(err.field.length + 2) : err.message;
    error.replaceChildren();
    append(error, [h('strong', {}, `The server refused it (${err.status || 'no answer'}): `),
      err.field ? [h('code', {class: 'field'}, err.field), ': '] : null, message,
      err.status === 401 ? h('p', {}, 'Set the server’s token under "Token" at the top of the page.') : null]);
    if (err.status === 401) {
      // The way out, opened: the header's token form.
      document.getElementById('token').open = true;
      document.getElementById('token-input').focus();
      return;
    }
    const at = locateField(editor.value, err.field);
    if (at >= 0) {
      const end = editor.value.indexOf('\n', at);
      const {line} = lineCol(editor.value, at);
      error.append(h('p', {}, `Line ${line} of the request is selected.`));
      editor.focus();
      editor.setSelectionRange(at, end < 0 ? editor.value.length : end);
      // Scroll the selected line into view (about one line height per line).
      const lh = parseFloat(getComputedStyle(editor).lineHeight) || 18;
      editor.scrollTop = Math.max(0, (line - 4) * lh);
    }
  }
}
