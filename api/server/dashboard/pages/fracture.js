// Where the specimen broke: every broken bond (breaks.csv: step, x, y, z, mode at the bond's
// midpoint) projected on the x-z plane (the loading axis z up; a cylinder seen from the side, a
// Brazilian disc face on), by mode (the largest term of the failure criterion), at the peak load
// and at the end of the run.
import {getText} from '../api.js';
import {h, note, section} from '../dom.js';
import {specimenMap} from '../plot/specimen_map.js';

const MODES = ['tension', 'shear', 'twist', 'bending'];

async function fetchBreaks(url, ctx) {
  const key = `breaks:${url}`;
  if (ctx.cache && ctx.cache.has(key)) return ctx.cache.get(key);
  const lines = (await getText(url, {signal: ctx.signal})).split('\n').filter((l) => l.trim() !== '');
  const columns = lines[0].split(',');
  const at = (name) => columns.indexOf(name);
  const breaks = lines.slice(1).map((l) => {
    const f = l.split(',');
    return {step: Number(f[at('step')]), x: Number(f[at('x')]), z: Number(f[at('z')]), mode: f[at('mode')]};
  });
  if (ctx.cache) ctx.cache.set(key, breaks);
  return breaks;
}

// The step of the peak load: the result's, or (older results) the curve's step at the peak's
// displacement.
function peakStep(r, curve) {
  if (Number.isInteger(r.peak_step)) return r.peak_step;
  if (!curve) return null;
  let best = 0;
  curve.displacement.forEach((d, i) => {
    if (Math.abs(d - r.peak_displacement) < Math.abs(curve.displacement[best] - r.peak_displacement)) best = i;
  });
  return curve.step[best];
}

function byMode(breaks) {
  return MODES.map((mode) => ({name: mode, points: breaks.filter((b) => b.mode === mode).map((b) => [b.x, b.z])}));
}

export async function fractureSection(j, curve, width, ctx) {
  const r = j.result || {};
  if (!j.files || !j.files.breaks_csv) return section('Fracture', note('The run left no breaks.csv.'));
  const breaks = await fetchBreaks(j.files.breaks_csv, ctx);
  const sample = (j.spec && j.spec.sample) || {};
  const disc = j.test === 'btt';
  // A flattened disc's flats sit at |z| = D/2 cos(alpha), 2 alpha its loading angle.
  const loading = (j.spec && j.spec.loading) || {};
  const flatY = disc && loading.btt_geometry === 'flattened' && Number.isFinite(loading.flat_angle_deg)
    ? (sample.diameter / 2) * Math.cos((loading.flat_angle_deg / 2) * Math.PI / 180) : null;
  const outline = {shape: disc ? 'circle' : 'rect', halfWidth: sample.diameter / 2,
    halfHeight: (disc ? sample.diameter : sample.height) / 2, flatY};
  const axesLabels = {xLabel: 'x (m, model units)', yLabel: 'z, loading axis (m)'};
  const peak = peakStep(r, curve);
  const maps = [];
  if (r.peak_reached !== false && Number.isInteger(peak)) {
    const before = breaks.filter((b) => b.step <= peak);
    maps.push(specimenMap({title: 'Broken bonds at the peak load', width, outline, ...axesLabels,
      caption: `${before.length} of ${breaks.length}, up to step ${peak}`, groups: byMode(before)}));
  }
  maps.push(specimenMap({title: 'Broken bonds at the end', width, outline, ...axesLabels,
    caption: `${breaks.length}, up to step ${r.steps}`, groups: byMode(breaks)}));
  return section('Fracture',
    note(`Every broken bond at its midpoint, projected on the x-z plane (${disc ? 'the disc face on' : 'the cylinder from the side'}; the loading axis z up), ` +
      'by mode, the largest term of the failure criterion when it broke: tension (normal pull over F_r0), shear (shear force over F_s0), ' +
      'twist (torque over G_t0) or bending (bending moment over G_b0).'),
    h('div', {class: 'plots'}, ...maps));
}
