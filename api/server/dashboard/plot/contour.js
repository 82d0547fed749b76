// Iso-lines on a grid by marching squares. values[iy][ix] (null where missing), grid coordinates:
// the cell centres sit at integer (ix, iy). Returns segments [[x0, y0], [x1, y1]] where the
// linearly interpolated field crosses `level`; squares with a missing corner are skipped.
export function isoSegments(values, level) {
  const out = [];
  const ny = values.length;
  const nx = ny ? values[0].length : 0;
  const cross = (a, b, va, vb) => {
    const t = (level - va) / (vb - va);
    return [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t];
  };
  for (let iy = 0; iy + 1 < ny; ++iy) {
    for (let ix = 0; ix + 1 < nx; ++ix) {
      // Corners counter-clockwise from the lower left.
      const c = [[ix, iy], [ix + 1, iy], [ix + 1, iy + 1], [ix, iy + 1]];
      const v = c.map(([x, y]) => values[y][x]);
      if (v.some((u) => typeof u !== 'number' || !Number.isFinite(u))) continue;
      const above = v.map((u) => u >= level);
      const points = [];
      for (let k = 0; k < 4; ++k) {
        const k1 = (k + 1) % 4;
        if (above[k] !== above[k1]) points.push(cross(c[k], c[k1], v[k], v[k1]));
      }
      if (points.length === 2) {
        out.push(points);
      } else if (points.length === 4) {
        // A saddle: the centre's mean value decides which corners the lines separate.
        const centreAbove = (v[0] + v[1] + v[2] + v[3]) / 4 >= level;
        if (centreAbove === above[0]) {
          out.push([points[0], points[1]], [points[2], points[3]]);
        } else {
          out.push([points[3], points[0]], [points[1], points[2]]);
        }
      }
    }
  }
  return out;
}
