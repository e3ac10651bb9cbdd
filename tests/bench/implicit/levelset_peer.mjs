// manifold-3d's Manifold.levelSet (marching tetrahedra on a body-centred cubic grid) on the torus
// R = 1, r = 0.4 of tests/bench/implicit/solid.cpp, for a list of edge lengths. Run by
// tests/bench/implicit/peers.sh, which installs manifold-3d with tests/bench/peers' package.json.
// For each edge length and each vertex mode (interpolated, the default tolerance -1; or refined
// to 1e-4 of the surface by levelSet's own root search): median CPU time of 5 runs (process CPU,
// user + system: the WASM module is single-threaded), the mesh written as OFF, and a line
// "<name>|<setting>|<ms>|<file>" appended to <dir>/peers.txt for `implicit_solid --peers <dir>`.
//   node levelset_peer.mjs <dir> <edge length>...
import { appendFileSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const { default: Module } = await import(pathToFileURL(join(here, '../peers/node_modules/manifold-3d/manifold.js')).href);
const wasm = await Module();
wasm.setup();
const { Manifold } = wasm;

const [dir, ...edges] = process.argv.slice(2);
if (!dir || edges.length === 0) {
  console.error('usage: node levelset_peer.mjs <dir> <edge length>...');
  process.exit(2);
}
// levelSet wants a signed distance, positive inside: the torus's exact one (its best case; the
// polynomial form that polygonize evaluates is not a distance).
const R = 1.0, r = 0.4;
const sdf = ([x, y, z]) => r - Math.hypot(Math.hypot(x, y) - R, z);
const bounds = { min: [-1.5, -1.5, -0.5], max: [1.5, 1.5, 0.5] };

for (const [mode, tolerance] of [['interpolated', -1], ['refined 1e-4', 1e-4]]) {
  for (const edgeText of edges) {
    const edge = Number(edgeText);
    const times = [];
    let mesh;
    for (let run = 0; run < 5; ++run) {
      const start = process.cpuUsage();
      const m = Manifold.levelSet(sdf, bounds, edge, 0, tolerance);
      mesh = m.getMesh();
      m.delete();
      const used = process.cpuUsage(start);
      times.push((used.user + used.system) / 1000);
    }
    times.sort((a, b) => a - b);
    const n = mesh.numProp, verts = mesh.vertProperties, tris = mesh.triVerts;
    const lines = [`OFF`, `${verts.length / n} ${tris.length / 3} 0`];
    for (let i = 0; i < verts.length; i += n) lines.push(`${verts[i]} ${verts[i + 1]} ${verts[i + 2]}`);
    for (let i = 0; i < tris.length; i += 3) lines.push(`3 ${tris[i]} ${tris[i + 1]} ${tris[i + 2]}`);
    const file = join(dir, `manifold_${tolerance < 0 ? 'interp' : 'refined'}_${edge}.off`);
    writeFileSync(file, lines.join('\n') + '\n');
    appendFileSync(join(dir, 'peers.txt'),
      `manifold-3d levelSet, ${mode}|edge length ${edge}|${times[2].toFixed(1)}|${file}\n`);
    console.log(`manifold ${mode} edge ${edge}: ${tris.length / 3} triangles, ${times[2].toFixed(1)} ms`);
  }
}
