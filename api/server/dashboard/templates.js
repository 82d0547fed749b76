// Starting points for the submit page: two small requests that run in seconds to a minute on tiny
// specimens. The repository's own examples (examples/*.json) are listed beside them, fetched from
// the server (/ui/examples/index.json).

const TINY_JOB = {
  sample: {diameter: 8, height: 16, radius: 1, packing: 'fcc', seed: 1},
  material: {kr: 8000, nu: 0.2, density: 1},
  contact: {friction: 0.6},
  loading: {platen_velocity: 0.05, dt: 'auto', max_strain: 0.2, slow_factor: 0.25},
};

export const TEMPLATES = {
  sweep: {
    title: 'Sweep: UCT and BTT over a 4 × 4 grid of strengths (tiny specimens, seconds)',
    request: {
      kind: 'sweep',
      name: 'UCT and BTT over a 4 x 4 grid of bond strengths',
      tests: ['uct', 'btt'],
      job: TINY_JOB,
      grid: {fr0: [32, 64, 128, 256], fs0: [32, 64, 128, 256]},
    },
  },
  calibration: {
    title: 'Calibration: tiny specimens toward model-unit targets (seconds)',
    request: {
      kind: 'calibration',
      name: 'tiny calibration toward model-unit targets',
      job: TINY_JOB,
      // Loads the tiny model reaches: its own (packing seed 1) at F_r0 = 64 N, F_s0 = 128 N, the
      // centre of the bounds in log space, where the search starts. Its packings scatter by tens of
      // per cent, so the report explains why the answer is not unique.
      targets: {uct: {peak_load: 5640}, btt: {peak_load: 506}},
      bounds: {fr0: [32, 128], fs0: [64, 256]},
      max_evaluations: 24,
      tolerance: 0.02,
      seeds: [2, 3],
    },
  },
};
