// The REST API from the same origin: relative URLs, JSON with its content type on every mutating
// request, the bearer token (when the user gave one) on POST and DELETE.

const TOKEN_KEY = 'rockcal.token';

export class ApiError extends Error {
  constructor(status, message, field) {
    super(message);
    this.status = status;
    this.field = field || '';
  }
}

// The token lives in this tab's session storage: gone when the tab closes.
export function token() {
  try {
    return sessionStorage.getItem(TOKEN_KEY) || '';
  } catch {
    return '';
  }
}

export function setToken(value) {
  try {
    if (value) sessionStorage.setItem(TOKEN_KEY, value);
    else sessionStorage.removeItem(TOKEN_KEY);
  } catch {
    // Storage refused (private mode): the token stays unset.
  }
}

async function request(method, path, {body, accept = 'application/json', signal} = {}) {
  const headers = {Accept: accept};
  if (method !== 'GET') headers['Content-Type'] = 'application/json';
  if (token()) headers.Authorization = `Bearer ${token()}`;  // reads too, for --protect-reads
  let response;
  try {
    response = await fetch(path, {
      method, headers, signal, credentials: 'same-origin', cache: 'no-store',
      body: body === undefined ? undefined : typeof body === 'string' ? body : JSON.stringify(body),
    });
  } catch (e) {
    if (e.name === 'AbortError') throw e;
    throw new ApiError(0, `the server did not answer (${e.message})`);
  }
  if (!response.ok) {
    let message = `HTTP ${response.status}`;
    let field = '';
    try {
      const j = await response.json();
      if (j && typeof j.error === 'string') message = j.error;
      if (j && typeof j.field === 'string') field = j.field;
    } catch {
      // Not our JSON error shape: keep the status line.
    }
    throw new ApiError(response.status, message, field);
  }
  return response;
}

export async function getJson(path, options) {
  return (await request('GET', path, options)).json();
}

export async function getText(path, options) {
  return (await request('GET', path, {accept: 'text/plain, text/csv', ...options})).text();
}

export async function postJson(path, body, options) {
  return (await request('POST', path, {body, ...options})).json();
}

export async function deleteJson(path, options) {
  return (await request('DELETE', path, options)).json();
}

// "step,time_s,displacement_m,load_n,broken_bonds\n0,0,0,0,0\n..." -> {columns, rows: [[...]]}
export function parseCsv(text) {
  const lines = text.split('\n').filter((l) => l.trim() !== '');
  if (lines.length === 0) return {columns: [], rows: []};
  const columns = lines[0].split(',').map((c) => c.trim());
  const rows = lines.slice(1).map((l) => l.split(',').map(Number));
  return {columns, rows};
}
