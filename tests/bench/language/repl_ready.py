#!/usr/bin/env python3
"""Time from starting `sculpt` on a pseudo-terminal to its first prompt (the REPL is ready),
median of N runs; also the child's CPU time. Target <= 50 ms (docs/benchmarks.md, Language).
   repl_ready.py path/to/sculpt [runs=15]"""
import os, pty, resource, select, statistics, sys, tempfile, time

sculpt = sys.argv[1]
runs = int(sys.argv[2]) if len(sys.argv) > 2 else 15
home = tempfile.mkdtemp()
walls, cpus = [], []
for _ in range(runs):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    pid, fd = pty.fork()
    if pid == 0:
        os.environ["HOME"] = home
        os.execv(sculpt, [sculpt])
    screen = b""
    while b"sculpt> " not in screen:
        ready, _, _ = select.select([fd], [], [], 5)
        if not ready:
            sys.exit("no prompt")
        screen += os.read(fd, 4096)
    walls.append(time.perf_counter() - start)
    os.write(fd, b":quit\r")
    os.waitpid(pid, 0)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpus.append((after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime))
print("REPL ready: wall median %.1f ms (min %.1f), CPU median %.1f ms, %d runs"
      % (1e3 * statistics.median(walls), 1e3 * min(walls), 1e3 * statistics.median(cpus), runs))
