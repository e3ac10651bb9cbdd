#!/usr/bin/env bash
# Runs our BSP benchmark and the peers (manifold-3d, JSCAD) on the cases of
# tests/bench/bsp/CASES.md and prints a table with time and memory ratios.
#   tests/bench/compare.sh [--ours PROGRAM] [--ours-file FILE] [--peers-file FILE] [--stat median|min]
#                          [--rounds R] [--case NAME] [--n N] [--pin CPU] [peer run.sh options]
# --ours: our bench program (default: build/release/tests/bench/bsp/bench_bsp);
#         it must print the "bench key=value ..." lines of CASES.md.
# --ours-file / --peers-file: use lines saved from an earlier run instead of running.
# --save PREFIX: also keep this run's lines in PREFIX.ours.txt and PREFIX.peers.txt.
# --stat: compare median times (default), minimum times (less sensitive to a busy machine), or
#         cpu / min_cpu: median / minimum CPU time (ours: the thread's; peers: node's process, user +
#         system), the least sensitive to other processes on a loaded machine.
# --rounds R: interleaved, R rounds: each round runs every case once with ours, then with each
#         peer, case by case, so a change in the machine's speed (this virtual machine's can change
#         by 1.4x within minutes) falls on both sides alike; the table shows each side's best over
#         the rounds (the chosen stat's minimum) and the median of the per-round ratios.
# --case NAME / --n N: only these cases (with --rounds; without, they go to the peers' run.sh).
# --pin CPU: every program runs on that CPU alone (taskset), ours and the peers alike: the two
#         CPUs of a virtual machine need not be equally fast.
# Ratios > 1 mean ours is faster (peer time / our time) or smaller (peer rss / our rss).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/../.." && pwd)
ours=""
ours_file=""
peers_file=""
stat=median
save=""
rounds=0
runs=7  # per case and program, as the peers' run.sh
only_case=""
only_n=""
pin=()
peer_args=()
while (($#)); do
  case "$1" in
    --ours) ours="$2"; shift 2 ;;
    --ours-file) ours_file="$2"; shift 2 ;;
    --peers-file) peers_file="$2"; shift 2 ;;
    --stat) stat="$2"; shift 2 ;;
    --save) save="$2"; shift 2 ;;
    --rounds) rounds="$2"; shift 2 ;;
    --case) only_case="$2"; peer_args+=(--case "$2"); shift 2 ;;
    --n) only_n="$2"; peer_args+=(--n "$2"); shift 2 ;;
    --pin) pin=(taskset -c "$2"); shift 2 ;;
    --runs) runs="$2"; peer_args+=(--runs "$2"); shift 2 ;;
    *) peer_args+=("$1"); shift ;;
  esac
done

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

if [ -z "$ours" ]; then
  for candidate in "$root"/build/release/tests/bench/bsp/bench_bsp; do
    [ -x "$candidate" ] && { ours="$candidate"; break; }
  done
fi
if ((rounds > 0)); then
  # Interleaved rounds (see --rounds): the case list of bench_bsp's main() and the peers' run.sh.
  [ -n "$ours_file" ] || [ -n "$peers_file" ] && { echo "compare.sh: --rounds runs both sides; not with --ours-file/--peers-file" >&2; exit 2; }
  [ -x "$ours" ] || { echo "compare.sh: our bench program was not found (build it with scripts/bench.sh or pass --ours)" >&2; exit 1; }
  cases=("sphere_minus_cube 32" "sphere_minus_cube 64" "sphere_minus_cube 128" "sphere_minus_cube 256"
         "menger 3" "boxes 1000" "sphere_minus_sphere 32" "sphere_minus_sphere 64" "sphere_minus_sphere 128"
         "sphere_minus_tilted_cube 64" "drilled_plate 100" "rotated_boxes 200")
  : > "$tmp/ours.txt"; : > "$tmp/peers.txt"
  for ((r = 1; r <= rounds; ++r)); do
    for c in "${cases[@]}"; do
      set -- $c
      [ -n "$only_case" ] && [ "$only_case" != "$1" ] && continue
      [ -n "$only_n" ] && [ "$only_n" != "$2" ] && continue
      echo "compare.sh: round $r/$rounds: $1 $2" >&2
      "${pin[@]}" "$ours" "$1" "$2" "$runs" | grep '^bench ' | sed "s/\$/ round=$r/" >> "$tmp/ours.txt" || true
      "${pin[@]}" "$here/peers/run.sh" "${peer_args[@]}" --case "$1" --n "$2" | grep '^bench ' |
        sed "s/\$/ round=$r/" >> "$tmp/peers.txt" || true
    done
  done
elif [ -n "$ours_file" ]; then
  cp "$ours_file" "$tmp/ours.txt"
else
  if [ -z "$ours" ] || [ ! -x "$ours" ]; then
    echo "compare.sh: our BSP bench program was not found (looked for build/release/tests/bench/bsp/bench_bsp;" >&2
    echo "            build it with scripts/bench.sh or pass --ours PROGRAM). Showing the peers only." >&2
    : > "$tmp/ours.txt"
  else
    echo "compare.sh: running $ours" >&2
    "${pin[@]}" "$ours" | grep '^bench ' > "$tmp/ours.txt" || echo "compare.sh: $ours printed no 'bench' lines" >&2
  fi
fi

if ((rounds > 0)); then
  :
elif [ -n "$peers_file" ]; then
  grep '^bench ' "$peers_file" > "$tmp/peers.txt" || true
else
  "${pin[@]}" "$here/peers/run.sh" "${peer_args[@]}" | tee "$tmp/peers_raw.txt" >&2
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
  x = val("time_ms")
  if (stat == "min" && val("min_ms") != "") x = val("min_ms")
  if (stat == "cpu" && val("cpu_ms") != "") x = val("cpu_ms")
  if (stat == "min_cpu" && val("min_cpu_ms") != "") x = val("min_cpu_ms")
  if (val("status") != "") x = val("status")
  # Several rounds (--rounds): each side keeps its best; the ratios are taken per round.
  if (!((key, impl) in t) || (x + 0 > 0 && x + 0 < t[key, impl] + 0)) t[key, impl] = x
  rd = val("round"); if (rd != "") { rt[key, impl, rd] = x; if (rd + 0 > nrounds) nrounds = rd + 0 }
  v[key, impl] = val("volume"); m[key, impl] = val("peak_rss_kb")
  if (impl == "ours" && val("tree_nodes") != "") nodes[key] = val("tree_nodes")
}
function ratio(a, b) { return (a + 0 > 0 && b + 0 > 0) ? sprintf("%.2f", a / b) : "-" }
function show(x) { return x == "" ? "-" : x }
# Median over the rounds of peer time / our time in the same round.
function round_ratio(k, peer,   i, n, j, tmp, r) {
  n = 0
  for (i = 1; i <= nrounds; ++i)
    if (rt[k, peer, i] + 0 > 0 && rt[k, "ours", i] + 0 > 0) r[++n] = rt[k, peer, i] / rt[k, "ours", i]
  if (n == 0) return "-"
  for (i = 2; i <= n; ++i) for (j = i; j > 1 && r[j - 1] > r[j]; --j) { tmp = r[j]; r[j] = r[j - 1]; r[j - 1] = tmp }
  return sprintf("%.2f", n % 2 ? r[(n + 1) / 2] : (r[n / 2] + r[n / 2 + 1]) / 2)
}
END {
  if (nrounds > 0) {
    printf "per-round ratios (median of %d interleaved rounds; > 1: ours faster):\n", nrounds
    for (r = 1; r <= rows; ++r)
      printf "  %-22s man/ours %6s  jscad/ours %6s\n", order[r], round_ratio(order[r], "manifold-3d"), round_ratio(order[r], "jscad")
  }
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
