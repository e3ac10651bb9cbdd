// Benchmark cases shared by the peer programs (definitions: tests/bench/bsp/CASES.md).
// Each case is described as plain data (boxes and spheres in double coordinates), so that
// every implementation builds exactly the same inputs.

/** 32-bit LCG (Numerical Recipes): state' = 1664525 * state + 1013904223 mod 2^32. */
export function lcg(seed) {
  let state = seed >>> 0;
  return () => {
    state = (Math.imul(1664525, state) + 1013904223) >>> 0;
    return state;
  };
}

/** Menger sponge level `level` by differences: the unit cube minus 3 * sum_{l=1..level} 9^(l-1)
 * bars. A bar at level l has cross-section [i/3^l, (i+1)/3^l] x [j/3^l, (j+1)/3^l] (i, j = 1 mod 3)
 * and runs along one axis over [-0.5, 1.5]. Cross-section bounds are i / 3^l computed as one
 * division (so 3/9 and 1/3 are the same double). */
export function mengerBars(level) {
  const bars = [];
  for (let l = 1; l <= level; ++l) {
    const m = 3 ** l;
    for (let axis = 0; axis < 3; ++axis) {
      for (let i = 1; i < m; i += 3) {
        for (let j = 1; j < m; j += 3) {
          const lo = [0, 0, 0], hi = [0, 0, 0];
          const u = (axis + 1) % 3, v = (axis + 2) % 3;
          lo[axis] = -0.5; hi[axis] = 1.5;
          lo[u] = i / m; hi[u] = (i + 1) / m;
          lo[v] = j / m; hi[v] = (j + 1) / m;
          bars.push({ lo, hi });
        }
      }
    }
  }
  return bars;
}

/** `count` random boxes from lcg(seed): for each box, three draws give the corner
 * (h / 4096, h = draw >>> 16, in [0, 16)) and three give the size (0.5 + (h >>> 5) / 1024, in
 * [0.5, 2.5)); coordinates are multiples of 2^-12, so every implementation gets them exactly. */
export function randomBoxes(count, seed = 1) {
  const next = lcg(seed);
  const boxes = [];
  for (let k = 0; k < count; ++k) {
    const lo = [0, 1, 2].map(() => (next() >>> 16) / 4096);
    const size = [0, 1, 2].map(() => 0.5 + ((next() >>> 16) >>> 5) / 1024);
    boxes.push({ lo, hi: lo.map((x, i) => x + size[i]) });
  }
  return boxes;
}

/** Exact volume of a union of axis-aligned boxes (coordinate compression along x, then y,
 * interval merge along z). Exact in doubles for dyadic coordinates like randomBoxes'. */
export function unionVolume(boxes) {
  const xs = [...new Set(boxes.flatMap((b) => [b.lo[0], b.hi[0]]))].sort((a, b) => a - b);
  let volume = 0;
  for (let i = 0; i + 1 < xs.length; ++i) {
    const x0 = xs[i], x1 = xs[i + 1];
    const slab = boxes.filter((b) => b.lo[0] <= x0 && b.hi[0] >= x1);
    if (!slab.length) continue;
    const ys = [...new Set(slab.flatMap((b) => [b.lo[1], b.hi[1]]))].sort((a, b) => a - b);
    let area = 0;
    for (let j = 0; j + 1 < ys.length; ++j) {
      const y0 = ys[j], y1 = ys[j + 1];
      const zs = slab.filter((b) => b.lo[1] <= y0 && b.hi[1] >= y1).map((b) => [b.lo[2], b.hi[2]]);
      zs.sort((a, b) => a[0] - b[0]);
      let length = 0, start = 0, end = 0, open = false;
      for (const [z0, z1] of zs) {
        if (!open || z0 > end) {
          if (open) length += end - start;
          start = z0; end = z1; open = true;
        } else if (z1 > end) end = z1;
      }
      if (open) length += end - start;
      area += (y1 - y0) * length;
    }
    volume += (x1 - x0) * area;
  }
  return volume;
}

/** 4x4 column-major matrix (manifold-3d's Mat4 and JSCAD's mat4 layout) of the rotation by
 * `degrees` about the axis through `centre` with direction `axis` (right-handed; Rodrigues'
 * formula on the normalized axis): x -> R (x - centre) + centre. */
export function rotationAbout(axis, degrees, centre = [0, 0, 0]) {
  const len = Math.hypot(axis[0], axis[1], axis[2]);
  const [x, y, z] = axis.map((a) => a / len);
  const t = degrees * Math.PI / 180, c = Math.cos(t), s = Math.sin(t), k = 1 - c;
  const r = [  // rows
    [c + x * x * k, x * y * k - z * s, x * z * k + y * s],
    [y * x * k + z * s, c + y * y * k, y * z * k - x * s],
    [z * x * k - y * s, z * y * k + x * s, c + z * z * k],
  ];
  const tr = [0, 1, 2].map((i) => centre[i] - (r[i][0] * centre[0] + r[i][1] * centre[1] + r[i][2] * centre[2]));
  return [r[0][0], r[1][0], r[2][0], 0, r[0][1], r[1][1], r[2][1], 0, r[0][2], r[1][2], r[2][2], 0, tr[0], tr[1], tr[2], 1];
}

/** sphere_minus_sphere: the second sphere (same radius 1 and segments) is centred here. */
export const SPHERE_OFFSET = [0.5, 0.375, 0.25];

/** sphere_minus_tilted_cube: the unit cube [0,1]^3 turned by 30 degrees about (1, 2, 3) through
 * the origin (its corner at the sphere's centre). */
export const TILTED_CUBE = rotationAbout([1, 2, 3], 30);

/** drilled_plate n: the plate [0,10] x [0,10] x [0,1] minus n holes (n = 100: a 10 x 10 grid),
 * cylinders of radius 0.3 with 32 segments, z over [-0.5, 1.5], axes at (i + 0.5, j + 0.5). */
export function drillCentres(count) {
  const side = Math.ceil(Math.sqrt(count));
  const centres = [];
  for (let k = 0; k < count; ++k) centres.push([(k % side) + 0.5, Math.floor(k / side) + 0.5]);
  return centres;
}

/** rotated_boxes n: `count` boxes from lcg(seed), each turned about its own centre. Per box, three
 * draws give the corner lo[k] = h / 8192 (h = draw >>> 16, in [0, 8)), three the size
 * 0.5 + (h >>> 5) / 1024 (in [0.5, 2.5)), three the axis a[k] = h / 32768 - 1 (in [-1, 1)) and one
 * the angle h * 360 / 65536 degrees. `matrix` is rotationAbout(axis, degrees, centre of the box). */
export function rotatedBoxes(count, seed = 1) {
  const next = lcg(seed);
  const boxes = [];
  for (let k = 0; k < count; ++k) {
    const lo = [0, 1, 2].map(() => (next() >>> 16) / 8192);
    const size = [0, 1, 2].map(() => 0.5 + ((next() >>> 16) >>> 5) / 1024);
    let axis = [0, 1, 2].map(() => (next() >>> 16) / 32768 - 1);
    if (axis.every((a) => a === 0)) axis = [0, 0, 1];
    const degrees = (next() >>> 16) * 360 / 65536;
    const hi = lo.map((x, i) => x + size[i]);
    boxes.push({ lo, hi, axis, degrees, matrix: rotationAbout(axis, degrees, lo.map((x, i) => (x + hi[i]) / 2)) });
  }
  return boxes;
}

/** The cases: name, parameter, and the expected volume where one is known independently. */
export const CASES = [
  ...[32, 64, 128, 256].map((n) => ({ name: 'sphere_minus_cube', n })),
  { name: 'menger', n: 3, expected: (20 / 27) ** 3 },
  { name: 'boxes', n: 1000 },
  ...[32, 64, 128].map((n) => ({ name: 'sphere_minus_sphere', n })),
  { name: 'sphere_minus_tilted_cube', n: 64 },
  { name: 'drilled_plate', n: 100 },
  { name: 'rotated_boxes', n: 200 },
];
