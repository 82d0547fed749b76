// The dashboard's entry: routes a bookmarkable path to its page, keeps navigation inside the page
// (History API), and runs the header's token form. Pages render into <main> and stop their polls
// when the user leaves them.
import {getJson, setToken, token} from './api.js';
import {clear, h} from './dom.js';
import * as campaign from './pages/campaign.js';
import * as campaigns from './pages/campaigns.js';
import * as job from './pages/job.js';
import * as submit from './pages/submit.js';

const ROUTES = [
  {pattern: /^\/(?:campaigns)?$/, page: campaigns, nav: 'campaigns'},
  {pattern: /^\/campaigns\/([^/]+)$/, page: campaign, nav: 'campaigns'},
  {pattern: /^\/jobs\/([^/]+)$/, page: job, nav: 'campaigns'},
  {pattern: /^\/submit$/, page: submit, nav: 'submit'},
];

let current = null;  // {controller} of the page on screen

export function navigate(href, {replace = false} = {}) {
  if (replace) history.replaceState(null, '', href);
  else history.pushState(null, '', href);
  render();
}

// Page state in the query string (e.g. a sweep's targets), so that the URL keeps it.
export function setQuery(params) {
  const url = new URL(location.href);
  for (const [k, v] of Object.entries(params)) {
    if (v === null || v === undefined || v === '') url.searchParams.delete(k);
    else url.searchParams.set(k, v);
  }
  history.replaceState(null, '', url.pathname + url.search + url.hash);
}

async function render() {
  if (current) current.controller.abort();
  const controller = new AbortController();
  current = {controller};
  const main = document.getElementById('main');
  const path = location.pathname.replace(/\/+$/, '') || '/';
  const route = ROUTES.find((r) => r.pattern.test(path));
  for (const a of document.querySelectorAll('[data-nav]')) {
    if (route && a.dataset.nav === route.nav) a.setAttribute('aria-current', 'page');
    else a.removeAttribute('aria-current');
  }
  clear(main);
  if (!route) {
    document.title = 'rockcal: not found';
    main.append(h('h1', {}, 'Not found'), h('p', {}, `No page at ${path}. `, h('a', {href: '/'}, 'Campaigns')));
    return;
  }
  const params = path.match(route.pattern).slice(1).map(decodeURIComponent);
  const ctx = {
    main,
    signal: controller.signal,
    query: new URLSearchParams(location.search),
    setTitle: (t) => {
      document.title = `${t} · rockcal`;
    },
    navigate,
    setQuery,
  };
  try {
    await route.page.render(params, ctx);
  } catch (e) {
    if (e && e.name === 'AbortError') return;
    if (controller.signal.aborted) return;
    clear(main);
    main.append(h('h1', {}, 'Error'), h('p', {class: 'error', role: 'alert'}, e.message || String(e)));
  }
}

// Same-origin page links stay in the app; API links (JSON, CSV, the HTML report) load as usual.
document.addEventListener('click', (e) => {
  if (e.defaultPrevented || e.button !== 0 || e.metaKey || e.ctrlKey || e.shiftKey || e.altKey) return;
  const a = e.target.closest('a[href]');
  if (!a || a.target || a.hasAttribute('download')) return;
  const url = new URL(a.href, location.href);
  if (url.origin !== location.origin || url.pathname.startsWith('/api/') || url.pathname.startsWith('/ui/')) return;
  if (url.pathname === location.pathname && url.search === location.search && url.hash) return;
  e.preventDefault();
  navigate(url.pathname + url.search);
  document.getElementById('main').focus({preventScroll: true});
  window.scrollTo(0, 0);
});
window.addEventListener('popstate', render);

function tokenForm() {
  const details = document.getElementById('token');
  const input = document.getElementById('token-input');
  const summary = details.querySelector('summary');
  const show = () => {
    summary.textContent = token() ? 'Token: set' : 'Token';
  };
  document.getElementById('token-form').addEventListener('submit', (e) => {
    e.preventDefault();
    setToken(input.value.trim());
    input.value = '';
    details.open = false;
    show();
  });
  document.getElementById('token-clear').addEventListener('click', () => {
    setToken('');
    input.value = '';
    show();
  });
  show();
}

async function footer() {
  const f = document.getElementById('footer');
  try {
    const health = await getJson('/healthz');
    f.textContent = `engine ${health.engine_version} · ${health.workers} workers · `;
  } catch {
    f.textContent = 'server not answering · ';
  }
  f.append(h('a', {href: '/api/v1/campaigns'}, 'API (JSON)'));
}

// Live pages keep polling through a server restart; the banner says so meanwhile.
window.addEventListener('rockcal:offline', (e) => {
  const banner = document.getElementById('offline');
  banner.textContent = `No answer from the server (${e.detail}); trying again every few seconds.`;
  banner.hidden = false;
});
window.addEventListener('rockcal:online', () => {
  document.getElementById('offline').hidden = true;
});

tokenForm();
footer();
render();
