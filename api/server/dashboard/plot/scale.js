// Linear and logarithmic scales with readable ticks (1, 2, 5 x 10^k).

function niceStep(span, count) {
  const raw = span / Math.max(1, count);
  const power = 10 ** Math.floor(Math.log10(raw));
  const f = raw / power;
  return (f < 1.5 ? 1 : f < 3 ? 2 : f < 7 ? 5 : 10) * power;
}

export function linearTicks(lo, hi, count = 5) {
  if (!(hi > lo)) return [lo];
  const step = niceStep(hi - lo, count);
  const out = [];
  for (let v = Math.ceil(lo / step - 1e-9) * step; v <= hi + step * 1e-9; v += step) {
    out.push(Math.abs(v) < step * 1e-9 ? 0 : Number(v.toPrecision(12)));
  }
  return out;
}

// Decades first, then 1-3, 1-2-5 and 1..9 per decade until there are at least two ticks; a range
// narrower than that gets linear ticks.
export function logTicks(lo, hi, count = 5) {
  const a = Math.floor(Math.log10(lo));
  const b = Math.ceil(Math.log10(hi));
  const within = (m) => {
    const out = [];
    for (let e = a; e <= b; ++e) {
      for (const k of m) {
        const v = Number((k * 10 ** e).toPrecision(12));
        if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) out.push(v);
      }
    }
    return out;
  };
  const decades = within([1]);
  if (decades.length > count + 2) {
    const every = Math.ceil(decades.length / (count + 1));
    return decades.filter((_, i) => i % every === 0);
  }
  for (const m of [[1], [1, 3], [1, 2, 5], [1, 2, 3, 4, 5, 6, 7, 8, 9]]) {
    const out = within(m);
    if (out.length >= 3 || (out.length >= 2 && m.length > 1)) return out;
  }
  return linearTicks(lo, hi, count).filter((v) => v > 0);
}

// [min, max] of the finite values, widened a little so that marks do not sit on the frame.
export function extent(values, {pad = 0.05, log = false, include = []} = {}) {
  const v = values.concat(include).filter((x) => Number.isFinite(x) && (!log || x > 0));
  if (v.length === 0) return log ? [1, 10] : [0, 1];
  let lo = Math.min(...v);
  let hi = Math.max(...v);
  if (log) {
    if (hi / lo < 1.0001) {
      lo /= 1.5;
      hi *= 1.5;
    }
    const f = (hi / lo) ** pad;
    return [lo / f, hi * f];
  }
  if (hi - lo < 1e-12 * Math.max(1, Math.abs(hi))) {
    const d = Math.abs(hi) * 0.1 || 1;
    return [lo - d, hi + d];
  }
  const d = (hi - lo) * pad;
  return [lo - d, hi + d];
}

// domain [d0, d1] -> range [r0, r1]; `log` maps in log10.
export function scale([d0, d1], [r0, r1], {log = false} = {}) {
  const t = log ? Math.log10 : (x) => x;
  const t0 = t(d0);
  const t1 = t(d1);
  const k = t1 === t0 ? 0 : (r1 - r0) / (t1 - t0);
  const map = (x) => r0 + (t(x) - t0) * k;
  map.domain = [d0, d1];
  map.range = [r0, r1];
  map.log = log;
  map.ticks = (count = 5) => (log ? logTicks(d0, d1, count) : linearTicks(d0, d1, count));
  map.invert = (y) => {
    const u = t0 + (y - r0) / (k || 1);
    return log ? 10 ** u : u;
  };
  return map;
}
