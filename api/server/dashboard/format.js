// Numbers, durations and dates as people read them.

// Four significant digits; exponent notation outside 1e-3 .. 1e6. Missing values are a dash.
export function num(x, digits = 4) {
  if (x === null || x === undefined || Number.isNaN(x)) return '–';
  if (typeof x !== 'number') return String(x);
  if (!Number.isFinite(x)) return x > 0 ? '∞' : '−∞';
  if (x === 0) return '0';
  const a = Math.abs(x);
  let text;
  if (a >= 1e6 || a < 1e-3) {
    text = x.toExponential(digits - 1).replace(/\.?0+e/, 'e').replace('e+', 'e');
  } else {
    text = String(Number(x.toPrecision(digits)));
  }
  return text.replaceAll('-', '−');
}

export function signed(x, digits = 3) {
  if (typeof x !== 'number' || !Number.isFinite(x)) return num(x);
  return (x > 0 ? '+' : '') + num(x, digits);
}

export function pct(fraction, digits = 1) {
  if (typeof fraction !== 'number' || !Number.isFinite(fraction)) return '–';
  return `${(fraction * 100).toFixed(digits)}%`;
}

// "mean ± sd"
export function pm(mean, sd, digits = 4) {
  if (typeof sd !== 'number' || !Number.isFinite(sd)) return num(mean, digits);
  return `${num(mean, digits)} ± ${num(sd, 2)}`;
}

export function duration(seconds) {
  if (typeof seconds !== 'number' || !Number.isFinite(seconds)) return '–';
  const s = Math.round(seconds);
  if (s < 60) return `${s} s`;
  const m = Math.floor(s / 60);
  if (m < 60) return `${m} min ${String(s % 60).padStart(2, '0')} s`;
  return `${Math.floor(m / 60)} h ${String(m % 60).padStart(2, '0')} min`;
}

export function dateTime(unixSeconds) {
  if (typeof unixSeconds !== 'number') return '–';
  const d = new Date(unixSeconds * 1000);
  const two = (n) => String(n).padStart(2, '0');
  return `${d.getFullYear()}-${two(d.getMonth() + 1)}-${two(d.getDate())} ` +
    `${two(d.getHours())}:${two(d.getMinutes())}:${two(d.getSeconds())}`;
}

// A load in newtons with a unit that keeps the number short (N, kN, MN).
export function newtons(x) {
  if (typeof x !== 'number' || !Number.isFinite(x)) return '–';
  const a = Math.abs(x);
  if (a >= 1e6) return `${num(x / 1e6)} MN`;
  if (a >= 1e3) return `${num(x / 1e3)} kN`;
  return `${num(x)} N`;
}

// A stress in pascals (Pa, kPa, MPa, GPa).
export function pascals(x) {
  if (typeof x !== 'number' || !Number.isFinite(x)) return '–';
  const a = Math.abs(x);
  for (const [f, u] of [[1e9, 'GPa'], [1e6, 'MPa'], [1e3, 'kPa']]) {
    if (a >= f) return `${num(x / f)} ${u}`;
  }
  return `${num(x)} Pa`;
}

// How a strength follows from its peak load, from a result's "strength_definition" (the engine's
// one definition): "UCS = F / A", "BTS = k 2P / (π D t), k = 0.9131".
export function strengthFormula(d) {
  if (!d || typeof d.formula !== 'string') return '';
  const text = `${d.name} = ${d.formula.replace('pi', 'π')}`;
  return d.formula.startsWith('k ') ? `${text}, k = ${num(d.factor)}` : text;
}
