// Live updates by polling: `tick` runs now, and again `period()` ms after each answer while it
// returns true. One request at a time per page, none while the tab is hidden, none after the page
// is left. The period is longer than the server's keep-alive timeout (2 s), so the browser's idle
// connection closes between polls and no server thread stays held by an open page.
import {ApiError, getJson} from './api.js';

const POLL_MS = 3000;

function startPolling(tick, {signal, period = () => POLL_MS} = {}) {
  let timer = null;
  let parked = false;
  const run = async () => {
    timer = null;
    if (signal && signal.aborted) return;
    if (document.hidden) {
      parked = true;
      return;
    }
    let again = true;
    try {
      again = await tick();
      window.dispatchEvent(new CustomEvent('rockcal:online'));
    } catch (e) {
      if (e && e.name === 'AbortError') return;
      // A failed poll (the server restarting) is said on the page and tried again.
      window.dispatchEvent(new CustomEvent('rockcal:offline', {detail: e.message || String(e)}));
      again = true;
    }
    if (again && !(signal && signal.aborted)) timer = setTimeout(run, period());
  };
  const onVisible = () => {
    if (!document.hidden && parked) {
      parked = false;
      run();
    }
  };
  document.addEventListener('visibilitychange', onVisible);
  if (signal) {
    signal.addEventListener('abort', () => {
      if (timer) clearTimeout(timer);
      document.removeEventListener('visibilitychange', onVisible);
    });
  }
  return run();
}

// Polls a JSON resource while live(value) holds; show(value) runs when it changed, missing(error)
// when it does not exist (404, which ends the polling). With `resize`, show() runs again when the
// page's width changes (plots are drawn for the width they have, so their text keeps its size).
// `slower(value)` adds milliseconds to the period (a big campaign's page fetches more per update).
export function watchJson(url, {signal, show, live, missing, resize, slower = () => 0}) {
  let last = '';
  let latest;
  if (resize) {
    let width = resize.clientWidth;
    let timer = null;
    const onResize = () => {
      clearTimeout(timer);
      timer = setTimeout(() => {
        if (Math.abs(resize.clientWidth - width) < 24 || latest === undefined) return;
        width = resize.clientWidth;
        show(latest);
      }, 200);
    };
    window.addEventListener('resize', onResize);
    if (signal) signal.addEventListener('abort', () => window.removeEventListener('resize', onResize));
  }
  return startPolling(async () => {
    let value;
    try {
      value = await getJson(url, {signal});
    } catch (e) {
      if (e instanceof ApiError && e.status === 404 && missing) {
        missing(e);
        return false;
      }
      throw e;
    }
    const text = JSON.stringify(value);
    if (text !== last) {
      last = text;
      latest = value;
      await show(value);
    }
    return live(value);
  }, {signal, period: () => POLL_MS + (latest === undefined ? 0 : slower(latest))});
}
