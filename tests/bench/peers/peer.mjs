// Runs one benchmark case with one peer library and prints one line of key=value pairs:
//   node peer.mjs <manifold|jscad> <case> <n> [--runs R] [--budget-ms B] [--eager]
// (cases: tests/bench/bsp/CASES.md)
// --eager (manifold): evaluate after every operation instead of letting Manifold batch its lazy
// CSG tree in menger and drilled_plate (JSCAD is always eager).
// time: median over the runs of building the inputs, doing the set operations and getting
// the result's boundary mesh (Manifold: getMesh(); JSCAD: geom3.toPolygons()).
// peak_rss_kb is the process's peak resident set (node + the library) and base_rss_kb the
// same just before the first run, so the case's own peak is roughly their difference.
import { loadavg } from 'node:os';
import {
  SPHERE_OFFSET, TILTED_CUBE, drillCentres, mengerBars, randomBoxes, rotatedBoxes, unionVolume,
} from './cases.mjs';

const [impl, caseName, nText, ...rest] = process.argv.slice(2);
const n = Number(nText);
let runs = 5, budgetMs = 30000, eager = false;
for (let i = 0; i < rest.length; i += 2) {
  if (rest[i] === '--runs') runs = Number(rest[i + 1]);
  else if (rest[i] === '--budget-ms') budgetMs = Number(rest[i + 1]);
  else if (rest[i] === '--eager') { eager = true; --i; }  // manifold: evaluate after every operation
}
const caseNames = ['sphere_minus_cube', 'menger', 'boxes', 'sphere_minus_sphere', 'sphere_minus_tilted_cube',
  'drilled_plate', 'rotated_boxes'];
if (!['manifold', 'jscad'].includes(impl) || !caseNames.includes(caseName) || !(n > 0)) {
  console.error(`usage: node peer.mjs <manifold|jscad> <${caseNames.join('|')}> <n> [--runs R] [--budget-ms B]`);
  process.exit(2);
}

// Each library as the same few operations; `track` collects manifold-3d's objects so that a run
// frees them (WASM memory), JSCAD needs nothing.
async function manifoldOps() {
  const { default: Module } = await import('manifold-3d');
  const wasm = await Module();
  wasm.setup();
  const { Manifold } = wasm;
  let temps = [];
  const track = (m) => { temps.push(m); return m; };
  return {
    sphere: (segments) => track(Manifold.sphere(1, segments)),
    box: (b) => track(track(Manifold.cube([b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]], false)).translate(b.lo)),
    cylinder: (r, h, segments, at) => track(track(Manifold.cylinder(h, r, r, segments, false)).translate(at)),
    transform: (m, g) => track(g.transform(m)),
    translate: (v, g) => track(g.translate(v)),
    subtract: (a, b) => track(a.subtract(b)),
    intersect: (a, b) => track(a.intersect(b)),
    unionAll: (list) => track(Manifold.union(list)),
    evaluate: (g) => g.numTri(),  // forces evaluation of the lazy CSG tree now (--eager)
    volume: (g) => g.volume(),
    mesh(g) {
      const mesh = g.getMesh();
      return { faces: mesh.triVerts.length / 3, vertices: mesh.vertProperties.length / mesh.numProp };
    },
    release() { for (const t of temps) t.delete(); temps = []; },
  };
}

async function jscadOps() {
  const jscad = await import('@jscad/modeling');
  const { primitives, booleans, measurements, geometries, transforms } = jscad.default ?? jscad;
  return {
    sphere: (segments) => primitives.sphere({ radius: 1, segments }),
    box: (b) => primitives.cuboid({
      size: [0, 1, 2].map((i) => b.hi[i] - b.lo[i]),
      center: [0, 1, 2].map((i) => (b.hi[i] + b.lo[i]) / 2),
    }),
    cylinder: (r, h, segments, at) => primitives.cylinder({ radius: r, height: h, segments, center: [at[0], at[1], at[2] + h / 2] }),
    transform: (m, g) => transforms.transform(m, g),
    translate: (v, g) => transforms.translate(v, g),
    subtract: (a, b) => booleans.subtract(a, b),
    intersect: (a, b) => booleans.intersect(a, b),
    unionAll: (list) => booleans.union(list),
    evaluate: () => {},
    volume: (g) => measurements.measureVolume(g),
    mesh(g) {
      const polygons = geometries.geom3.toPolygons(g);
      const vertices = new Set();
      for (const p of polygons) for (const v of p.vertices) vertices.add(`${v[0]},${v[1]},${v[2]}`);
      return { faces: polygons.length, vertices: vertices.size };
    },
    release() {},
  };
}

const ops = impl === 'manifold' ? await manifoldOps() : await jscadOps();
const unitCube = () => ops.box({ lo: [0, 0, 0], hi: [1, 1, 1] });
const plate = () => ops.box({ lo: [0, 0, 0], hi: [10, 10, 1] });
const hole = (c) => ops.cylinder(0.3, 2, 32, [c[0], c[1], -0.5]);

// The operands of the cases that subtract one solid from another (their expected volume is
// vol(a) - vol(a ∩ b), computed untimed by the same library).
function operands() {
  if (caseName === 'sphere_minus_cube') return [ops.sphere(n), unitCube()];
  if (caseName === 'sphere_minus_sphere') return [ops.sphere(n), ops.translate(SPHERE_OFFSET, ops.sphere(n))];
  if (caseName === 'sphere_minus_tilted_cube') return [ops.sphere(n), ops.transform(TILTED_CUBE, unitCube())];
  return null;
}

const runner = {
  run() {
    let result;
    const pair = operands();
    if (pair) {
      result = ops.subtract(pair[0], pair[1]);
    } else if (caseName === 'menger') {
      result = unitCube();
      for (const b of mengerBars(n)) {
        result = ops.subtract(result, ops.box(b));
        if (eager) ops.evaluate(result);
      }
    } else if (caseName === 'drilled_plate') {
      result = plate();
      for (const c of drillCentres(n)) {
        result = ops.subtract(result, hole(c));
        if (eager) ops.evaluate(result);
      }
    } else if (caseName === 'boxes') {
      result = ops.unionAll(randomBoxes(n).map(ops.box));
    } else {
      result = ops.unionAll(rotatedBoxes(n).map((b) => ops.transform(b.matrix, ops.box(b))));
    }
    const out = { volume: ops.volume(result), ...ops.mesh(result) };
    ops.release();
    return out;
  },
  expected() {
    let v = '';
    const pair = operands();
    if (caseName === 'sphere_minus_cube') v = 7 / 8 * ops.volume(pair[0]);  // octant symmetry
    else if (pair) v = ops.volume(pair[0]) - ops.volume(ops.intersect(pair[0], pair[1]));
    else if (caseName === 'menger') v = (20 / 27) ** 3;
    else if (caseName === 'boxes') v = unionVolume(randomBoxes(n));
    else if (caseName === 'drilled_plate') v = 100 - n * ops.volume(hole([0.5, 0.5])) / 2;  // each hole: half its cylinder
    ops.release();
    return v;
  },
};

const baseRss = process.resourceUsage().maxRSS;
const times = [], cpuTimes = [];  // wall clock and the process's CPU time (user + system) per run
let last;
const started = performance.now();
// A first run that is short against the budget only warms up the JIT and is not counted.
let warmup = 0;
{
  const t0 = performance.now(), c0 = process.cpuUsage();
  last = runner.run();
  const t = performance.now() - t0, c = process.cpuUsage(c0);
  if (t < budgetMs / 20) warmup = 1;
  else times.push(t), cpuTimes.push((c.user + c.system) / 1000);
}
for (let r = times.length; r < runs && performance.now() - started <= budgetMs; ++r) {
  const t0 = performance.now(), c0 = process.cpuUsage();
  last = runner.run();
  times.push(performance.now() - t0);
  const c = process.cpuUsage(c0);
  cpuTimes.push((c.user + c.system) / 1000);
}
const median = (xs) => {
  xs.sort((a, b) => a - b);
  return xs.length % 2 ? xs[(xs.length - 1) / 2] : (xs[xs.length / 2 - 1] + xs[xs.length / 2]) / 2;
};
const wall = [...times];
const medianTime = median(times), medianCpu = median(cpuTimes);

const expected = runner.expected();
const name = impl === 'manifold' ? 'manifold-3d' : 'jscad';
console.log(`bench impl=${name} case=${caseName} n=${n} runs=${times.length} warmup=${warmup} time_ms=${medianTime.toFixed(2)} ` +
  `min_ms=${times[0].toFixed(2)} cpu_ms=${medianCpu.toFixed(2)} min_cpu_ms=${cpuTimes[0].toFixed(2)} volume=${last.volume.toPrecision(15)} expected=${expected === '' ? 'na' : expected.toPrecision(15)} ` +
  `times_ms=${wall.map((t) => t.toFixed(1)).join(',')} faces=${last.faces} vertices=${last.vertices} peak_rss_kb=${process.resourceUsage().maxRSS} base_rss_kb=${baseRss}`);
