// Load-displacement curves of engine jobs (curve.csv: step, time_s, displacement_m, load_n,
// broken_bonds), in model units with the lab's beside them when the campaign maps to a lab case.
import {getText, parseCsv} from '../api.js';
import {num} from '../format.js';
import {linePlot} from '../plot/line_plot.js';

export async function fetchCurve(jobId, ctx) {
  const key = `curve:${jobId}`;
  if (ctx.cache && ctx.cache.has(key)) return ctx.cache.get(key);
  const {columns, rows} = parseCsv(await getText(`/api/v1/jobs/${jobId}/curve`, {signal: ctx.signal}));
  const col = (name) => columns.indexOf(name);
  const curve = {
    displacement: rows.map((r) => r[col('displacement_m')]),
    load: rows.map((r) => r[col('load_n')]),
    broken: rows.map((r) => r[col('broken_bonds')]),
    step: rows.map((r) => r[col('step')]),
  };
  if (ctx.cache) ctx.cache.set(key, curve);
  return curve;
}

// lab: {force, length} factors model -> lab (lab = model x factor), or null.
function secondAxes(lab) {
  if (!lab) return {};
  return {x: {factor: lab.length * 1e3, label: 'lab displacement (mm)'}, y: {factor: lab.force / 1e3, label: 'lab load (kN)'}};
}

// One curve (or several: [{name, curve}]) of load against displacement, with the target's line.
export function loadCurvePlot({title, curves, target, lab, width, caption, peak}) {
  const second = secondAxes(lab);
  const series = curves.map(({name, curve}) => ({
    name, line: true, marker: null, cursor: true,
    points: curve.displacement.map((d, i) => ({x: d, y: curve.load[i],
      label: `${name}: displacement ${num(d)} m, load ${num(curve.load[i])} N, ${curve.broken[i]} broken bonds` +
        (lab ? ` (lab ${num(d * lab.length * 1e3)} mm, ${num(curve.load[i] * lab.force / 1e3)} kN)` : '')})),
  }));
  const hlines = [];
  if (Number.isFinite(target)) {
    hlines.push({y: target, label: `target ${num(target)} N`, legend: `target peak load ${num(target)} N`});
  }
  if (Number.isFinite(peak)) hlines.push({y: peak, label: `peak ${num(peak)} N`, dash: '2 3'});
  return linePlot({title, caption, width, height: 300, series, hlines,
    x: {label: 'platen displacement (m, model units)', min: 0, second: second.x},
    y: {label: 'load (N, model units)', include: [0], second: second.y}});
}

export function brokenBondsPlot({title, curve, width, lab, bonds}) {
  const second = secondAxes(lab);
  return linePlot({title, width, height: 300,
    caption: Number.isFinite(bonds) ? `of ${bonds} bonds` : '',
    series: [{name: 'broken bonds', line: true, marker: null, cursor: true, step: true,
      points: curve.displacement.map((d, i) => ({x: d, y: curve.broken[i],
        label: `displacement ${num(d)} m: ${curve.broken[i]} broken bonds, load ${num(curve.load[i])} N`}))}],
    x: {label: 'platen displacement (m, model units)', min: 0, second: second.x},
    y: {label: 'broken bonds (count)', include: [0]}});
}

// Axial stress against axial strain of a UCT or triaxial job. The stress is the load over the
// strength's cross-section as the engine applied it (strength / peak load: F / A), the strain the
// platen closure over the loaded length (the specimen's height). lab.stress: model -> lab stress.
export function stressStrainPlot({title, r, curve, height, width, lab}) {
  const perNewton = r.strength / r.peak_load;
  const strain = (d) => d / height;
  const points = curve.displacement.map((d, i) => {
    const stress = curve.load[i] * perNewton;
    return {x: strain(d), y: stress,
      label: `axial strain ${num(strain(d))}, axial stress ${num(stress)} Pa` + (lab ? ` (lab ${num(stress * lab.stress / 1e6)} MPa)` : '')};
  });
  const hlines = Number.isFinite(r.strength) && r.peak_reached !== false
    ? [{y: r.strength, label: `${r.strength_definition ? r.strength_definition.name : 'strength'} ${num(r.strength)} Pa`, dash: '2 3'}] : [];
  return linePlot({title, width, height: 300, hlines,
    caption: 'lateral and volumetric strain: not measured by this test (the engine records the platen load and closure)',
    series: [{name: 'axial', line: true, marker: null, cursor: true, points}],
    x: {label: 'axial strain (closure / height)', min: 0},
    y: {label: 'axial stress (Pa, model units)', include: [0],
      second: lab ? {factor: lab.stress / 1e6, label: 'lab stress (MPa)'} : undefined}});
}
