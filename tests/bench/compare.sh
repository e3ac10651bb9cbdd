#!/usr/bin/env bash
# Runs our BSP benchmark and the peers (manifold-3d, JSCAD) on the cases of
# tests/bench/bsp/CASES.md and prints a table with time and memory ratios.
#   tests/bench/compare.sh [--ours PROGRAM] [--ours-file FILE] [--peers-file FILE] [--stat median|min]
#                          [peer run.sh options]
# --ours: our bench program (default: build/release/tests/bench/bsp/bench_bsp);
#         it must print the "bench key=value ..." lines of CASES.md.
# --ours-file / --peers-file: use lines saved from an earlier run instead of running.
# --save PREFIX: also keep this run's lines in PREFIX.ours.txt and PREFIX.peers.txt.
# --stat: compare median times (default), minimum times (less sensitive to a busy machine), or
#         cpu / min_cpu: median / minimum CPU time (ours: the thread's; peers: node's process, user +
#         system), the least sensitive to other processes on a loaded machine.
# Ratios > 1 mean ours is faster (peer time / our time) or smaller (peer rss / our rss).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
ours=""
ours_file=""
peers_file=""
stat=median
save=""
peer_args=()
while (($#)); do
  case "$1" in
    --ours) ours="$2"; shift 2 ;;
    --ours-file) ours_file="$2"; shift 2 ;;
    --peers-file) peers_file="$2"; shift 2 ;;
    --stat) stat="$2"; shift 2 ;;
    --save) save="$2"; shift 2 ;;
    *) peer_args+=("$1"); shift ;;
  esac
done

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

if [ -n "$ours_file" ]; then
  cp "$ours_file" "$tmp/ours.txt"
else
  if [ -z "$ours" ]; then
    for candidate in "$root"/build/release/tests/bench/bsp/bench_bsp; do
      [ -x "$candidate" ] && { ours="$candidate"; break; }
    done
  fi
  if [ -z "$ours" ] || [ ! -x "$ours" ]; then
    echo "compare.sh: our BSP bench program was not found (looked for build/release/tests/bench/bsp/bench_bsp;" >&2
    echo "            build it with scripts/setup.sh or pass --ours PROGRAM). Showing the peers only." >&2
    : > "$tmp/ours.txt"
  else
    echo "compare.sh: running $ours" >&2
    "$ours" | grep '^bench ' > "$tmp/ours.txt" || echo "compare.sh: $ours printed no 'bench' lines" >&2
  fi
fi

if [ -n "$peers_file" ]; then
  grep '^bench ' "$peers_file" > "$tmp/peers.txt" || true
else
  "$here/peers/run.sh" "${peer_args[@]}" | tee "$tmp/peers_raw.txt" >&2
  grep '^bench ' "$tmp/peers_raw.txt" > "$tmp/peers.txt" || true
fi

if [ -n "$save" ]; then
  cp "$tmp/ours.txt" "$save.ours.txt"
  cp "$tmp/peers.txt" "$save.peers.txt"
fi

# Table: one row per (case, n); columns per implementation.
cat "$tmp/peers.txt" "$tmp/ours.txt" | awk -v stat="$stat" '
function val(key,   i, kv) {
  for (i = 2; i <= NF; ++i) { split($i, kv, "="); if (kv[1] == key) return substr($i, length(key) + 2) }
  return ""
}
{
  impl = val("impl"); if (impl != "manifold-3d" && impl != "jscad") impl = "ours"
  key = val("case") " " val("n")
  if (!(key in seen)) { seen[key] = 1; order[++rows] = key }
  t[key, impl] = val("time_ms")
  if (stat == "min" && val("min_ms") != "") t[key, impl] = val("min_ms")
  if (stat == "cpu" && val("cpu_ms") != "") t[key, impl] = val("cpu_ms")
  if (stat == "min_cpu" && val("min_cpu_ms") != "") t[key, impl] = val("min_cpu_ms")
  v[key, impl] = val("volume"); m[key, impl] = val("peak_rss_kb")
  if (val("status") != "") t[key, impl] = val("status")
  if (impl == "ours" && val("tree_nodes") != "") nodes[key] = val("tree_nodes")
}
function ratio(a, b) { return (a + 0 > 0 && b + 0 > 0) ? sprintf("%.2f", a / b) : "-" }
function show(x) { return x == "" ? "-" : x }
END {
  printf "%-22s %10s %12s %12s %9s %9s %16s %16s %16s %10s %10s %10s\n", "case", "ours_ms", "manifold_ms", "jscad_ms",
         "man/ours", "jscad/ours", "vol_ours", "vol_manifold", "vol_jscad", "rss_ours", "rss_man", "rss_jscad"
  for (r = 1; r <= rows; ++r) {
    k = order[r]
    printf "%-22s %10s %12s %12s %9s %9s %16s %16s %16s %10s %10s %10s\n", k, show(t[k, "ours"]), show(t[k, "manifold-3d"]),
           show(t[k, "jscad"]), ratio(t[k, "manifold-3d"], t[k, "ours"]), ratio(t[k, "jscad"], t[k, "ours"]),
           show(v[k, "ours"]), show(v[k, "manifold-3d"]), show(v[k, "jscad"]),
           show(m[k, "ours"]), show(m[k, "manifold-3d"]), show(m[k, "jscad"])
  }
  for (r = 1; r <= rows; ++r) if (order[r] in nodes) printf "tree_nodes %s: %s\n", order[r], nodes[order[r]]
  print "(times: " stat " ms; man/ours, jscad/ours > 1: ours faster; rss: peak resident set, kB, whole process)"
}'
