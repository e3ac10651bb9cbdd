// Checks of the case definitions (run by run.sh before the benchmarks; exits non-zero on failure).
import assert from 'node:assert/strict';
import { lcg, mengerBars, randomBoxes, unionVolume } from './cases.mjs';

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
console.log('# selftest: case definitions ok');
