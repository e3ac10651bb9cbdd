// Checks of the case definitions (run by run.sh before the benchmarks; exits non-zero on failure).
import assert from 'node:assert/strict';
import {
  TILTED_CUBE, drillCentres, lcg, mengerBars, randomBoxes, rotatedBoxes, rotationAbout, unionVolume,
} from './cases.mjs';

// LCG: the first outputs of Numerical Recipes' ranqd1 from seed 1 (1664525 + 1013904223, ...).
const next = lcg(1);
assert.equal(next(), 1015568748);
assert.equal(next(), 1586005467);

// Menger level 3: 3 * (1 + 9 + 81) bars; level-1 bars are the central cross.
assert.equal(mengerBars(3).length, 273);
assert.deepEqual(mengerBars(1)[0], { lo: [-0.5, 1 / 3, 1 / 3], hi: [1.5, 2 / 3, 2 / 3] });
assert.equal(mengerBars(2).length, 30);
assert.deepEqual(mengerBars(2)[4].lo, [-0.5, 1 / 9, 4 / 9]);  // level 2, axis x, i = 1, j = 4

// unionVolume against voxel counting on integer boxes.
const rnd = lcg(7);
for (let trial = 0; trial < 50; ++trial) {
  const boxes = [];
  for (let k = 0; k < 1 + (trial % 12); ++k) {
    const lo = [0, 1, 2].map(() => rnd() % 6), size = [0, 1, 2].map(() => 1 + (rnd() % 3));
    boxes.push({ lo, hi: lo.map((x, i) => x + size[i]) });
  }
  let voxels = 0;
  for (let x = 0; x < 9; ++x) for (let y = 0; y < 9; ++y) for (let z = 0; z < 9; ++z) {
    if (boxes.some((b) => b.lo[0] <= x && x < b.hi[0] && b.lo[1] <= y && y < b.hi[1] && b.lo[2] <= z && z < b.hi[2])) ++voxels;
  }
  assert.equal(unionVolume(boxes), voxels);
}

// randomBoxes: coordinates on the 2^-12 grid, sizes in [0.5, 2.5).
for (const b of randomBoxes(1000)) {
  for (let i = 0; i < 3; ++i) {
    assert.equal(b.lo[i] * 4096, Math.round(b.lo[i] * 4096));
    assert.ok(b.hi[i] - b.lo[i] >= 0.5 && b.hi[i] - b.lo[i] < 2.5);
  }
}
// Rotations: orthonormal with determinant 1, the axis fixed, the centre fixed, a quarter turn about z exact
// up to rounding.
const apply = (m, p) => [0, 1, 2].map((i) => m[i] * p[0] + m[4 + i] * p[1] + m[8 + i] * p[2] + m[12 + i]);
const close = (a, b) => a.every((x, i) => Math.abs(x - b[i]) < 1e-12);
for (const m of [TILTED_CUBE, ...rotatedBoxes(200).map((b) => b.matrix)]) {
  const col = (j) => [m[4 * j], m[4 * j + 1], m[4 * j + 2]];
  const dot = (u, v) => u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  for (let i = 0; i < 3; ++i) for (let j = 0; j < 3; ++j) assert.ok(Math.abs(dot(col(i), col(j)) - (i === j ? 1 : 0)) < 1e-12);
  const [a, b, c] = [col(0), col(1), col(2)];
  assert.ok(Math.abs(dot(a, [b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2], b[0] * c[1] - b[1] * c[0]]) - 1) < 1e-12);
}
assert.ok(close(apply(TILTED_CUBE, [1, 2, 3]), [1, 2, 3]));
assert.ok(close(apply(rotationAbout([0, 0, 1], 90, [1, 1, 0]), [2, 1, 5]), [1, 2, 5]));
for (const b of rotatedBoxes(200)) {
  const centre = b.lo.map((x, i) => (x + b.hi[i]) / 2);
  assert.ok(close(apply(b.matrix, centre), centre));
}
assert.equal(drillCentres(100).length, 100);
assert.deepEqual(drillCentres(100)[11], [1.5, 1.5]);
console.log('# selftest: case definitions ok');
