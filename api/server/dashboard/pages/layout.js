// Plot widths from the space the page has: two plots side by side on a wide screen, one per row on
// a narrow one (a phone), so that text in the plots stays at its own size.
const GAP = 24;

export function plotWidth(main, {columns = 2, min = 340, max = 1100} = {}) {
  const style = getComputedStyle(main);
  const inner = main.clientWidth - parseFloat(style.paddingLeft) - parseFloat(style.paddingRight);
  const width = inner >= columns * min + (columns - 1) * GAP ? (inner - (columns - 1) * GAP) / columns : inner;
  return Math.max(260, Math.min(max, Math.floor(width)));
}
