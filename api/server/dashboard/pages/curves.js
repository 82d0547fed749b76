// Load-displacement curves of engine jobs (curve.csv: step, time_s, displacement_m, load_n,
// broken_bonds, lateral_strain), in model units with the lab's beside them when the campaign maps
// to a lab case.
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
    // UCT and triaxial runs measure it (older curves have no column).
    lateral: col('lateral_strain') >= 0 ? rows.map((r) => r[col('lateral_strain')]) : null,
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

// Axial stress against the strains of a UCT or triaxial job. The stress is the load over the
// strength's cross-section as the engine applied it (strength / peak load: F / A); the axial strain
// the platen closure over the specimen's height, the lateral strain the mid-height third's, the
// volumetric strain axial + 2 lateral, all compression positive. lab.stress: model -> lab stress.
export function stressStrainPlot({title, r, curve, height, width, lab}) {
  const perNewton = r.strength / r.peak_load;
  const strain = (d) => d / height;
  const stress = (i) => curve.load[i] * perNewton;
  const points = curve.displacement.map((d, i) => ({x: strain(d), y: stress(i),
    label: `axial strain ${num(strain(d))}` + (curve.lateral ? `, lateral ${num(curve.lateral[i])}, volumetric ${num(strain(d) + 2 * curve.lateral[i])}` : '') +
      `, axial stress ${num(stress(i))} Pa` + (lab ? ` (lab ${num(stress(i) * lab.stress / 1e6)} MPa)` : '')}));
  const series = [{name: 'axial', line: true, marker: null, cursor: true, points}];
  if (curve.lateral) {
    series.push({name: 'lateral', line: true, marker: null, points: curve.lateral.map((e, i) => ({x: e, y: stress(i)}))},
      {name: 'volumetric', line: true, marker: null, points: curve.lateral.map((e, i) => ({x: strain(curve.displacement[i]) + 2 * e, y: stress(i)}))});
  }
  const hlines = Number.isFinite(r.strength) && r.peak_reached !== false
    ? [{y: r.strength, label: `${r.strength_definition ? r.strength_definition.name : 'strength'} ${num(r.strength)} Pa`, dash: '2 3'}] : [];
  return linePlot({title, width, height: 300, hlines, series,
    caption: curve.lateral ? 'compression positive: lateral strain of the mid-height third, volumetric = axial + 2 lateral'
      : 'lateral and volumetric strain: not in this curve (a run before the engine measured them)',
    x: {label: 'strain (compression positive)', include: [0]},
    y: {label: 'axial stress (Pa, model units)', include: [0],
      second: lab ? {factor: lab.stress / 1e6, label: 'lab stress (MPa)'} : undefined}});
}
