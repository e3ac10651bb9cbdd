// Seeded random set operations over rotated and translated primitives (issue 14, "Clean output"),
// written as sculpt expressions together with manifold-3d's volume of the same solids: the
// reference the fuzz test (tests/language/clean_output_test.cpp) checks our results against.
//   node tests/bench/peers/csg_fuzz.mjs [--count N] [--seed S] > cases.txt
// (tests/bench/peers/run.sh installs manifold-3d; scripts/make_csg_cases.sh regenerates
// models/fuzz/csg_cases.txt.)
//
// Every primitive is convex, so both sides build the same polyhedron: sculpt from its own
// definition (docs/language.md: box, cylinder, cone, sphere with `segments`), manifold-3d as the
// hull of the same vertices computed here with the same formulas. Transforms (rotations about
// random axes by random angles, translations) act on primitives and on whole subtrees; some cases
// share faces and edges exactly (boxes side by side) or repeat an operand.
// Output, one case per line:
//   case <id> volume=<manifold volume> area=<sum of the primitives' areas> expr=<sculpt expression>
import { readFileSync } from 'node:fs';
import { lcg } from './cases.mjs';

let count = 300, seed = 1;
const argv = process.argv.slice(2);
for (let i = 0; i < argv.length; i += 2) {
  if (argv[i] === '--count') count = Number(argv[i + 1]);
  else if (argv[i] === '--seed') seed = Number(argv[i + 1]);
  else { console.error('usage: node csg_fuzz.mjs [--count N] [--seed S]'); process.exit(2); }
}

const { default: Module } = await import('manifold-3d');
const wasm = await Module();
wasm.setup();
const { Manifold } = wasm;

const next = lcg(seed);
const uniform = () => next() / 4294967296;            // [0, 1)
const pick = (n) => Math.floor(uniform() * n);
const dyadic = (lo, hi) => lo + Math.round(uniform() * (hi - lo) * 256) / 256;  // exact on the grid
const num = (v) => (Number.isInteger(v) ? v.toFixed(1) : String(v));  // shortest round-trip text
const vec = (v) => `[${v.map(num).join(', ')}]`;

// The regular n-gon of radius r, first vertex at angle 0 (sculpt's circular_path).
const ngon = (r, n) => Array.from({ length: n }, (_, k) => {
  const t = (2 * Math.PI * k) / n;
  return [r * Math.cos(t), r * Math.sin(t)];
});

function primitive() {
  switch (pick(4)) {
    case 0: {
      const lo = [dyadic(-1, 0.5), dyadic(-1, 0.5), dyadic(-1, 0.5)];
      const hi = lo.map((x) => x + dyadic(0.25, 1.25));
      const pts = [];
      for (const x of [lo[0], hi[0]]) for (const y of [lo[1], hi[1]]) for (const z of [lo[2], hi[2]]) pts.push([x, y, z]);
      return { text: `box(${vec(lo)}, ${vec(hi)})`, pts, box: { lo, hi } };
    }
    case 1: {
      const r = dyadic(0.25, 1), h = dyadic(0.25, 1.5), n = 5 + pick(20);
      const pts = ngon(r, n).flatMap(([x, y]) => [[x, y, 0], [x, y, h]]);
      return { text: `cylinder(${num(r)}, ${num(h)}, segments=${n})`, pts };
    }
    case 2: {
      const r = dyadic(0.25, 1), h = dyadic(0.25, 1.5), n = 5 + pick(20);
      const pts = [...ngon(r, n).map(([x, y]) => [x, y, 0]), [0, 0, h]];
      return { text: `cone(${num(r)}, ${num(h)}, segments=${n})`, pts };
    }
    default: {
      const r = dyadic(0.3, 1), n = 5 + pick(20), rings = Math.floor((n + 1) / 2);
      const pts = [];
      for (let k = 0; k < rings; ++k) {
        const phi = ((k + 0.5) * Math.PI) / rings;
        for (const [x, y] of ngon(r * Math.sin(phi), n)) pts.push([x, y, r * Math.cos(phi)]);
      }
      pts.push([0, 0, -r], [0, 0, r]);  // the poles
      return { text: `sphere(${num(r)}, segments=${n})`, pts };
    }
  }
}

// Rotation matrix about a unit axis (right-handed, Rodrigues; Eigen's AngleAxis).
function rotation(axis, degrees) {
  const n = Math.hypot(...axis), [x, y, z] = axis.map((a) => a / n);
  const t = (degrees * Math.PI) / 180, c = Math.cos(t), s = Math.sin(t), C = 1 - c;
  return [[c + x * x * C, x * y * C - z * s, x * z * C + y * s],
          [y * x * C + z * s, c + y * y * C, y * z * C - x * s],
          [z * x * C - y * s, z * y * C + x * s, c + z * z * C]];
}
const mat4 = (R, t) => [R[0][0], R[1][0], R[2][0], 0, R[0][1], R[1][1], R[2][1], 0,
                        R[0][2], R[1][2], R[2][2], 0, t[0], t[1], t[2], 1];

// A node: { text, make() -> Manifold (owned by the caller), area }.
function leaf() {
  const p = primitive();
  const hull = Manifold.hull(p.pts);
  const area = hull.surfaceArea();
  hull.delete();
  return { text: p.text, make: () => Manifold.hull(p.pts), area, box: p.box };
}

function transformed(node) {
  if (uniform() < 0.5) {
    const t = [dyadic(-0.75, 0.75), dyadic(-0.75, 0.75), dyadic(-0.75, 0.75)];
    return { ...node, box: undefined, text: `translate(${node.text}, ${vec(t)})`,
             make: () => { const m = node.make(); const r = m.translate(t); m.delete(); return r; } };
  }
  let axis;
  do axis = [pick(7) - 3, pick(7) - 3, pick(7) - 3]; while (axis.every((a) => a === 0));
  const degrees = Math.round(uniform() * 3600) / 10;
  const R = rotation(axis, degrees);
  return { ...node, box: undefined, text: `rotate(${node.text}, ${vec(axis)}, ${num(degrees)})`,
           make: () => { const m = node.make(); const r = m.transform(mat4(R, [0, 0, 0])); m.delete(); return r; } };
}

// A box that shares a face (or, with both offsets, only an edge) with box b, exactly.
function neighbour(b) {
  const axis = pick(3), lo = [...b.lo], hi = [...b.hi];
  const size = hi[axis] - lo[axis];
  lo[axis] = b.hi[axis];
  hi[axis] = b.hi[axis] + size / 2;
  if (uniform() < 0.3) {  // slide sideways by its full width: edge contact only
    const u = (axis + 1) % 3, w = hi[u] - lo[u];
    lo[u] += w; hi[u] += w;
  } else if (uniform() < 0.5) {
    const u = (axis + 1) % 3;
    lo[u] += (hi[u] - lo[u]) / 4;
  }
  const pts = [];
  for (const x of [lo[0], hi[0]]) for (const y of [lo[1], hi[1]]) for (const z of [lo[2], hi[2]]) pts.push([x, y, z]);
  const m = Manifold.hull(pts), area = m.surfaceArea();
  m.delete();
  return { text: `box(${vec(lo)}, ${vec(hi)})`, make: () => Manifold.hull(pts), area };
}

const ops = [['|', (a, b) => a.add(b)], ['-', (a, b) => a.subtract(b)], ['&', (a, b) => a.intersect(b)]];

function operand(depth) {
  if (depth === 0 || uniform() < 0.35) {
    const n = leaf();
    return uniform() < 0.7 ? transformed(n) : n;
  }
  return tree(depth - 1);
}

function tree(depth) {
  const a = operand(depth);
  let b;
  const r = uniform();
  if (a.box && r < 0.3) b = neighbour(a.box);       // shared face or edge
  else if (r < 0.4) b = transformed(a);              // a moved copy of the same operand
  else if (r < 0.45) b = a;                          // the operand itself
  else b = operand(depth);
  const [sym, fn] = ops[pick(3)];
  let node = { text: `(${a.text} ${sym} ${b.text})`, area: a.area + b.area,
               make: () => { const x = a.make(), y = b.make(), z = fn(x, y); x.delete(); y.delete(); return z; } };
  if (uniform() < 0.3) node = transformed(node);
  return node;
}

console.log(`# ${count} cases, seed ${seed}: node tests/bench/peers/csg_fuzz.mjs --count ${count} --seed ${seed}` +
            ` (manifold-3d ${JSON.parse(readFileSync(new URL('./node_modules/manifold-3d/package.json', import.meta.url))).version})`);
for (let id = 0; id < count; ++id) {
  const node = tree(1 + pick(2));
  const m = node.make();
  const volume = m.volume();
  m.delete();
  console.log(`case ${id} volume=${volume} area=${node.area} expr=${node.text}`);
}
