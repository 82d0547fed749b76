// Colours: the Okabe-Ito palette for series (distinct for the common colour-vision deficiencies;
// every series also has its own marker and dash) and viridis for values (ordered in lightness, so
// it reads in grey too).

export const SERIES = ['#0072B2', '#D55E00', '#009E73', '#CC79A7', '#E69F00', '#56B4E9', '#000000', '#F0E442'];
export const MARKERS = ['circle', 'square', 'triangle', 'diamond', 'cross', 'star'];
export const DASHES = [null, '6 3', '2 3', '8 3 2 3', '1 2'];

const VIRIDIS = [
  [68, 1, 84], [72, 35, 116], [64, 67, 135], [52, 94, 141], [41, 120, 142],
  [32, 144, 140], [34, 167, 132], [68, 190, 112], [121, 209, 81], [189, 222, 38], [253, 231, 37],
];

// t in [0, 1] -> "rgb(...)".
export function viridis(t) {
  const u = Math.max(0, Math.min(1, t)) * (VIRIDIS.length - 1);
  const i = Math.min(VIRIDIS.length - 2, Math.floor(u));
  const f = u - i;
  const c = VIRIDIS[i].map((v, k) => Math.round(v + (VIRIDIS[i + 1][k] - v) * f));
  return `rgb(${c[0]},${c[1]},${c[2]})`;
}

// Dark text on the light end of viridis, light text on the dark end.
export function textOn(t) {
  return t > 0.55 ? '#111' : '#fff';
}
