#!/usr/bin/env bash
# The sculpt executable's command line: -e, -, -D, -o, --help, --version, files, exit codes 0/1/2,
# Ctrl-C in a batch run (130), --memory-limit.
set -u
sculpt=$1
failures=0
check() {  # check NAME EXPECTED_STATUS EXPECTED_OUTPUT COMMAND...
  local name=$1 want_status=$2 want_output=$3
  shift 3
  local output status
  output=$("$@" 2>&1)
  status=$?
  if [ "$status" != "$want_status" ] || [ "$output" != "$want_output" ]; then
    echo "FAIL $name: status $status (want $want_status)"
    echo "--- got:"; echo "$output"; echo "--- want:"; echo "$want_output"
    failures=$((failures + 1))
  fi
}
first_line() {  # first_line COMMAND...: the first line of its output, with its exit status
  local output status
  output=$("$@" 2>&1)
  status=$?
  printf '%s\n' "${output%%$'\n'*}"
  return $status
}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

check e_code 0 "3" "$sculpt" -e 'print(1 + 2)'
check e_twice_shared_scope 0 "5" "$sculpt" -e 'x = 5' -e 'print(x)'
check define_number 0 "4 number" "$sculpt" -D n=2 -e 'print(n * 2, type(n))'
check define_forms 0 "abc [1, 2] true q string" "$sculpt" -D s=abc -Dv='[1, 2]' -D b=true -D 'q="q"' -e 'print(s, v, b, q, type(q))'
check stdin_dash 0 "7" bash -c "echo 'print(3 + 4)' | '$sculpt' -"
check stdin_implicit 0 "8" bash -c "echo 'print(4 * 2)' | '$sculpt'"
check script_error 1 "<command line>:1:7: error: unknown name 'y'
print(y)
      ^" "$sculpt" -e 'print(y)'
check output_before_error 1 "1
<command line>:2:1: error: 'return' outside a function
return 2
^" "$sculpt" -e 'print(1)
return 2'
check missing_file 1 "sculpt: $tmp/none.bsp: cannot open for reading" "$sculpt" "$tmp/none.bsp"
# Usage errors are one line each (exit 2).
check unknown_option 2 "sculpt: unknown option '--frobnicate'; try 'sculpt --help'" "$sculpt" --frobnicate
check e_without_code 2 "sculpt: -e needs code; try 'sculpt --help'" "$sculpt" -e
check bad_define 2 "sculpt: -D needs NAME=VALUE, got '1x=2'; try 'sculpt --help'" "$sculpt" -D 1x=2
check help 0 "usage: sculpt [options] [FILE.bsp ... | -]" first_line "$sculpt" --help
check version 0 "sculpt 0.1.0" "$sculpt" --version
# --grid STEP: the world range of the run's solids (docs/kernel.md, "World range").
check grid_power 0 "3e+05 0.0001220703125" "$sculpt" --grid 2^-13 -e 'print(volume(box([0, 0, 0], [3000, 10, 10])), grid())'
check grid_decimal 0 "<solid: 6 nodes, height 6, grid 2^-13>" "$sculpt" --grid=0.0001220703125 -e 'print(box([0, 0, 0], [3000, 1, 1]))'
check grid_not_a_power 2 "sculpt: grid step must be a power of two (2^k, k in [-64, 32]), got 0.001; the nearest is 2^-10 = 0.000976562; try 'sculpt --help'" "$sculpt" --grid 0.001
check grid_missing 2 "sculpt: --grid: '' is not a number or 2^K; try 'sculpt --help'" "$sculpt" --grid
check threads_one 0 "8" "$sculpt" --threads 1 -e 'print(volume(box([0, 0, 0], [2, 2, 2])))'
check threads_equals 0 "8" "$sculpt" --threads=2 -e 'print(volume(box([0, 0, 0], [2, 2, 2])))'
check threads_zero 2 "sculpt: --threads needs a positive integer, got '0'; try 'sculpt --help'" "$sculpt" --threads 0
check threads_environment 0 "8" env SCULPT_THREADS=1 "$sculpt" -e 'print(volume(box([0, 0, 0], [2, 2, 2])))'
check threads_environment_bad 2 "sculpt: SCULPT_THREADS must be an integer from 1 to 4096, got 'two'; try 'sculpt --help'" env SCULPT_THREADS=two "$sculpt" -e 'print(1)'
check port_bad 2 "sculpt: --port needs a port number in [0, 65535], got 'x'; try 'sculpt --help'" "$sculpt" --port x
check view_with_code 2 "sculpt: --view needs one script file (FILE.bsp); try 'sculpt --help'" "$sculpt" --view -e 'print(1)'
check view_with_output 2 "sculpt: --view and -o do not go together; try 'sculpt --help'" "$sculpt" --view -o "$tmp/x.stl" "$tmp/none.bsp"
# A port in use: the second view says so and names --port (the first is ended by its id).
printf 'box([0, 0, 0], [1, 1, 1])\n' > "$tmp/view.bsp"
"$sculpt" --view --port 0 "$tmp/view.bsp" > "$tmp/view.out" 2>&1 &
view_pid=$!
for _ in $(seq 100); do grep -q "view: run 1" "$tmp/view.out" && break; sleep 0.1; done
view_port=$(sed -n 's|^view: http://127.0.0.1:\([0-9]*\)/.*|\1|p' "$tmp/view.out")
check view_port_in_use 1 "sculpt: --view: port $view_port on 127.0.0.1 is in use (another sculpt view, or another program); choose a free port with --port N, or --port 0 for any free port" "$sculpt" --view --port "$view_port" "$tmp/view.bsp"
kill -INT "$view_pid"
wait "$view_pid"
check view_ends_on_interrupt 0 "view: stopped" tail -n 1 "$tmp/view.out"
# Files followed: an included script and a mesh import() reads each run the script again when they
# change; a file the script writes and reads back (export, then import) does not.
mkdir -p "$tmp/follow"
printf 'size = 1\n' > "$tmp/follow/part.bsp"
"$sculpt" -e 'export(box([0, 0, 0], [1, 1, 1]), "'"$tmp"'/follow/tool.off")'
printf 'include "part.bsp"\nexport(box([0, 0, 0], [size, 1, 1]), "own.off")\nb = import("own.off")\nt = import("tool.off")\nprint(volume(b | t))\n' > "$tmp/follow/main.bsp"
"$sculpt" --view --port 0 "$tmp/follow/main.bsp" > "$tmp/follow.out" 2>&1 &
view_pid=$!
runs_seen() { grep -c "^view: run " "$tmp/follow.out"; }
wait_runs() { for _ in $(seq 100); do [ "$(runs_seen)" -ge "$1" ] && break; sleep 0.1; done; }
wait_runs 1
sleep 1.2  # ten polls: the script's own export must not run it again
check view_own_export_not_followed 0 "1" runs_seen
sleep 1.1  # a time stamp one second later whatever the file system's resolution
printf 'size = 3\n' > "$tmp/follow/part.bsp"
wait_runs 2
check view_follows_include 0 "2" runs_seen
sleep 1.1
"$sculpt" -e 'export(box([0, 0, 0], [2, 2, 2]), "'"$tmp"'/follow/tool.off")'
wait_runs 3
check view_follows_import 0 "3" runs_seen
kill -INT "$view_pid"
wait "$view_pid"
check view_follow_volumes 0 "1
3
9" grep -E '^[0-9]+$' "$tmp/follow.out"
check grid_outside 2 "sculpt: grid step 2^-70 is outside the supported steps 2^-64 .. 2^32; try 'sculpt --help'" "$sculpt" --grid 2^-70

# -D overrides the script's own assignments outside functions (OpenSCAD's rule), not a
# function's locals nor a for variable.
printf 'size = 10\nprint(size)\nif true { size = 11 }\nprint(size)\n' > "$tmp/size.bsp"
check define_overrides_script 0 "3
3" "$sculpt" -D size=3 "$tmp/size.bsp"
check define_without_override 0 "10
11" "$sculpt" "$tmp/size.bsp"
check define_function_local 0 "1 3" "$sculpt" -D size=3 -e 'fn f() { size = 1; return size }' -e 'print(f(), size)'
check define_for_variable 0 "0 1 3" "$sculpt" -D i=3 -e 's = []' -e 'for i in range(0, 2) { s = append(s, i) }' -e 'print(s[0], s[1], i + 2)'
check help_mentions_override 0 "1" bash -c "'$sculpt' --help | grep -c 'overrides the scripts'"

# -o FILE: the last solid made (a solid expression statement or a global bound to a solid,
# whichever came later) exported by the file's extension, folders created.
volume_of() { "$sculpt" -e "print(volume(import(\"$1\")))"; }
check output_global 0 "" "$sculpt" -o "$tmp/out/deep/b.stl" -e 'b = box([0, 0, 0], [1, 2, 3])' -e 'n = 5'
check output_global_volume 0 "6" volume_of "$tmp/out/deep/b.stl"
check output_expression_later 0 "" "$sculpt" -o "$tmp/e.off" -e 'a = box([0, 0, 0], [1, 1, 1])' -e 'a | box([0, 0, 0], [2, 1, 1])'
check output_expression_volume 0 "2" volume_of "$tmp/e.off"
check output_global_later 0 "" "$sculpt" -o "$tmp/g.obj" -e 'box([0, 0, 0], [2, 2, 2])' -e 'b = box([0, 0, 0], [1, 1, 3])'
check output_global_later_volume 0 "3" volume_of "$tmp/g.obj"
check output_function_local_ignored 0 "" "$sculpt" -o "$tmp/f.ply" -e 'fn f() { inner = box([0, 0, 0], [4, 4, 4]); box([0, 0, 0], [1, 1, 1]) }' -e 'b = box([0, 0, 0], [1, 1, 5])' -e 'v = volume(f())'
check output_function_local_volume 0 "5" volume_of "$tmp/f.ply"
# With show(): the union of the shown solids (two unit cubes side by side, volume 2), not the last
# solid made (a box of volume 30).
check output_shown 0 "2" bash -c "'$sculpt' -o '$tmp/shown.off' -e 'show(box([0, 0, 0], [1, 1, 1]), name=\"a\")' \
  -e 'show(box([1, 0, 0], [2, 1, 1]), name=\"b\")' -e 'c = box([0, 0, 0], [2, 3, 5])' && '$sculpt' -e 'print(volume(import(\"$tmp/shown.off\")))'"
check output_no_solid 1 "sculpt: -o: the scripts made no solid to export" "$sculpt" -o "$tmp/none.stl" -e 'x = 1'
check output_not_after_error 1 "<command line>:1:33: error: unknown name 'y'
b = box([0, 0, 0], [1, 1, 1]) | y
                                ^" "$sculpt" -o "$tmp/err.stl" -e 'b = box([0, 0, 0], [1, 1, 1]) | y'
check output_not_written 1 "" test -e "$tmp/err.stl"
check output_bad_extension 2 "sculpt: -o: $tmp/x.jpg: unknown mesh format '.jpg' (use .off, .obj, .stl, .ply, .om, .3mf or .glb); try 'sculpt --help'" "$sculpt" -o "$tmp/x.jpg" -e 'b = 1'
check output_missing_name 2 "sculpt: -o needs a file name; try 'sculpt --help'" "$sculpt" -e 'b = 1' -o

# Files run in order; include and relative paths resolve against the including script's folder.
mkdir -p "$tmp/lib"
echo 'fn double(x) { 2 * x }' > "$tmp/lib/helpers.bsp"
echo 'include "lib/helpers.bsp"
print(double(21))' > "$tmp/main.bsp"
echo 'print(double(1))' > "$tmp/second.bsp"
check include_relative 0 "42
2" bash -c "cd / && '$sculpt' '$tmp/main.bsp' '$tmp/second.bsp'"
echo 'include "self.bsp"' > "$tmp/self.bsp"
check include_cycle 1 "$tmp/self.bsp:1:9: error: include: '$tmp/self.bsp' includes itself
include \"self.bsp\"
        ^
$tmp/self.bsp:1:1: note: included from here" "$sculpt" "$tmp/self.bsp"
echo 'export(box([0, 0, 0], [1, 1, 1]), "cube.off")' > "$tmp/export.bsp"
check export_relative 0 "" bash -c "cd / && '$sculpt' '$tmp/export.bsp' && test -s '$tmp/cube.off'"

# Deeply nested input is an error, not a crash.
python3 -c "print('x = ' + '(' * 100000)" > "$tmp/deep.bsp"
check deep_nesting 1 "$tmp/deep.bsp:1:69: error: brackets nested deeper than 64 levels" first_line "$sculpt" "$tmp/deep.bsp"

# Ctrl-C (SIGINT) stops a batch run: the message at the running statement, exit status 130, and no
# export left behind (half-written or temporary); the first statements' export is complete.
interrupted() {  # exports a cube, then unions for far longer than the test; SIGINT once it runs
  cd "$tmp" || return 99
  "$sculpt" -e 'export(box([0, 0, 0], [1, 1, 1]), "first.off")
s = sphere(1, 300)
for i in range(0, 100000) { u = s | translate(s, [0.5 + i / 100000, 0, 0]) }
export(u, "u.off")' 2> interrupted.err &
  local pid=$!
  # The signal goes after the first export is complete, however fast or slow the machine is.
  local waited=0
  while [ ! -s "$tmp/first.off" ] && [ "$waited" -lt 300 ]; do
    sleep 0.1
    waited=$((waited + 1))
  done
  sleep 0.5
  kill -INT $pid
  wait $pid
  local status=$?
  grep -o "error: interrupted" interrupted.err
  ls -A "$tmp" | grep -c "u.off\|\.tmp$"
  test -s "$tmp/first.off" && echo "first.off written"
  return $status
}
check interrupted 130 "error: interrupted
0
first.off written" interrupted

# The memory budget: work that takes more stops with an error at its statement (exit 1), not a
# kill by the system. Where resident memory cannot be read it is not enforced (it says so).
if "$sculpt" --memory-limit 512M -e 'x = 1' 2>&1 | grep -q "not enforced"; then
  echo "memory limit: not enforced in this build, skipped"
else
  # sphere(1, 2000) peaks at about 540 MB since its fragments are stored compactly: so close to a
  # 512 MB limit that the check passed or failed by when the budget was read. Half that is crossed
  # whenever it is read.
  check memory_limit 1 "<command line>:1:5: error: sphere: out of memory: the work needed more than the memory limit of 256 MB (sculpt --memory-limit)" \
    first_line "$sculpt" --memory-limit 256M -e 's = sphere(1, 2000)'
  check memory_limit_units 0 "1" "$sculpt" --memory-limit=2G -e 'print(1)'
fi
check memory_limit_bad 2 "sculpt: --memory-limit: a memory size is a number with K, M, G or T (2G, 500M) or 'none', not '2X'; try 'sculpt --help'" \
  "$sculpt" --memory-limit 2X -e 'print(1)'
check memory_limit_none 0 "1" "$sculpt" --memory-limit none -e 'print(1)'

if [ "$failures" != 0 ]; then
  echo "$failures command-line checks failed"
  exit 1
fi
echo "all command-line checks passed"
