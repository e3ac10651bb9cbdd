// Runs one benchmark case with one peer library and prints one line of key=value pairs:
//   node peer.mjs <manifold|jscad> <sphere_minus_cube|menger|boxes> <n> [--runs R] [--budget-ms B] [--eager]
// --eager (manifold): evaluate after every operation instead of letting Manifold batch its lazy
// CSG tree (JSCAD is always eager).
// time: median over the runs of building the inputs, doing the set operations and getting
// the result's boundary mesh (Manifold: getMesh(); JSCAD: geom3.toPolygons()).
// peak_rss_kb is the process's peak resident set (node + the library) and base_rss_kb the
// same just before the first run, so the case's own peak is roughly their difference.
import { loadavg } from 'node:os';
import { mengerBars, randomBoxes, unionVolume } from './cases.mjs';

const [impl, caseName, nText, ...rest] = process.argv.slice(2);
const n = Number(nText);
let runs = 5, budgetMs = 30000, eager = false;
for (let i = 0; i < rest.length; i += 2) {
  if (rest[i] === '--runs') runs = Number(rest[i + 1]);
  else if (rest[i] === '--budget-ms') budgetMs = Number(rest[i + 1]);
  else if (rest[i] === '--eager') { eager = true; --i; }  // manifold: evaluate after every operation
}
if (!['manifold', 'jscad'].includes(impl) || !['sphere_minus_cube', 'menger', 'boxes'].includes(caseName) || !(n > 0)) {
  console.error('usage: node peer.mjs <manifold|jscad> <sphere_minus_cube|menger|boxes> <n> [--runs R] [--budget-ms B]');
  process.exit(2);
}

async function manifoldRunner() {
  const { default: Module } = await import('manifold-3d');
  const wasm = await Module();
  wasm.setup();
  const { Manifold } = wasm;
  const box = (b) => Manifold.cube([b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]], false)
    .translate(b.lo);
  return {
    sphereVolume(segments) {
      const s = Manifold.sphere(1, segments);
      const v = s.volume();
      s.delete();
      return v;
    },
    run() {
      let result;
      const temps = [];
      if (caseName === 'sphere_minus_cube') {
        const s = Manifold.sphere(1, n), c = Manifold.cube([1, 1, 1], false);
        temps.push(s, c);
        result = s.subtract(c);
      } else if (caseName === 'menger') {
        result = Manifold.cube([1, 1, 1], false);
        for (const b of mengerBars(n)) {
          const bar = box(b);
          const next = result.subtract(bar);
          if (eager) next.numTri();  // forces evaluation of the lazy CSG tree now
          temps.push(bar, result);
          result = next;
        }
      } else {
        const boxes = randomBoxes(n).map(box);
        temps.push(...boxes);
        result = Manifold.union(boxes);
      }
      const mesh = result.getMesh();
      const out = { volume: result.volume(), faces: mesh.triVerts.length / 3, vertices: mesh.vertProperties.length / mesh.numProp };
      for (const t of temps) t.delete();
      result.delete();
      return out;
    },
  };
}

async function jscadRunner() {
  const jscad = await import('@jscad/modeling');
  const { primitives, booleans, measurements, geometries } = jscad.default ?? jscad;
  const box = (b) => primitives.cuboid({
    size: [0, 1, 2].map((i) => b.hi[i] - b.lo[i]),
    center: [0, 1, 2].map((i) => (b.hi[i] + b.lo[i]) / 2),
  });
  return {
    sphereVolume: (segments) => measurements.measureVolume(primitives.sphere({ radius: 1, segments })),
    run() {
      let result;
      if (caseName === 'sphere_minus_cube') {
        result = booleans.subtract(primitives.sphere({ radius: 1, segments: n }),
          primitives.cuboid({ size: [1, 1, 1], center: [0.5, 0.5, 0.5] }));
      } else if (caseName === 'menger') {
        result = primitives.cuboid({ size: [1, 1, 1], center: [0.5, 0.5, 0.5] });
        for (const b of mengerBars(n)) result = booleans.subtract(result, box(b));
      } else {
        result = booleans.union(randomBoxes(n).map(box));
      }
      const polygons = geometries.geom3.toPolygons(result);
      const vertices = new Set();
      for (const p of polygons) for (const v of p.vertices) vertices.add(`${v[0]},${v[1]},${v[2]}`);
      return { volume: measurements.measureVolume(result), faces: polygons.length, vertices: vertices.size };
    },
  };
}

const runner = impl === 'manifold' ? await manifoldRunner() : await jscadRunner();
const baseRss = process.resourceUsage().maxRSS;
const times = [];
let last;
const started = performance.now();
// A first run that is short against the budget only warms up the JIT and is not counted.
let warmup = 0;
{
  const t0 = performance.now();
  last = runner.run();
  const t = performance.now() - t0;
  if (t < budgetMs / 20) warmup = 1;
  else times.push(t);
}
for (let r = times.length; r < runs && performance.now() - started <= budgetMs; ++r) {
  const t0 = performance.now();
  last = runner.run();
  times.push(performance.now() - t0);
}
times.sort((a, b) => a - b);
const median = times.length % 2 ? times[(times.length - 1) / 2] : (times[times.length / 2 - 1] + times[times.length / 2]) / 2;

let expected = '';
if (caseName === 'sphere_minus_cube') expected = 7 / 8 * runner.sphereVolume(n);  // octant symmetry
if (caseName === 'menger') expected = (20 / 27) ** 3;
if (caseName === 'boxes') expected = unionVolume(randomBoxes(n));
const name = impl === 'manifold' ? 'manifold-3d' : 'jscad';
console.log(`bench impl=${name} case=${caseName} n=${n} runs=${times.length} warmup=${warmup} time_ms=${median.toFixed(2)} ` +
  `min_ms=${times[0].toFixed(2)} volume=${last.volume.toPrecision(15)} expected=${expected === '' ? 'na' : expected.toPrecision(15)} ` +
  `times_ms=${times.map((t) => t.toFixed(1)).join(',')} faces=${last.faces} vertices=${last.vertices} peak_rss_kb=${process.resourceUsage().maxRSS} base_rss_kb=${baseRss}`);
