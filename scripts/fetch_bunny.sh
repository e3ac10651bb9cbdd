#!/usr/bin/env bash
# Writes models/bunny.off from the npm package `bunny` (1.0.1, Mikola Lysenko; package.json says
# "Public Domain"; the data is the Stanford bunny, Stanford 3D Scanning Repository), used by the
# from_mesh benchmark and tests (docs/benchmarks.md, "Trees from meshes"). Coordinates are written
# with JavaScript's shortest round-trip decimal form, so the doubles are exactly the package's.
#   bash scripts/fetch_bunny.sh [out.off]       (default models/bunny.off; needs npm and node)
set -euo pipefail
out=${1:-"$(cd "$(dirname "$0")/.." && pwd)/models/bunny.off"}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
(cd "$tmp" && npm install --silent --no-audit --no-fund bunny@1.0.1 >/dev/null)
NODE_PATH="$tmp/node_modules" node -e '
const b = require("bunny");
const lines = ["OFF", `${b.positions.length} ${b.cells.length} 0`];
for (const p of b.positions) lines.push(p.map(String).join(" "));
for (const c of b.cells) lines.push(`${c.length} ${c.join(" ")}`);
process.stdout.write(lines.join("\n") + "\n");
' > "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
