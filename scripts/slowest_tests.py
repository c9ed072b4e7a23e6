#!/usr/bin/env python3
"""Pass `cargo test` output through unchanged, then print the slowest tests.

    cargo test --release 2>&1 | python3 scripts/slowest_tests.py [COUNT]

Stable libtest prints a test when it ends, not how long it took. It runs
the tests in the order of their names, at most N at once (N: the
RUST_TEST_THREADS variable, else the cores this process may use), and
starts the next one the moment one ends; so each test's start is the end
of the test that freed its place, and its time is its end less that
start. The times are wall clock, as long as the machine's load makes them
(a loaded machine stretches them all); the ranking is what they are for.
"""

import os
import re
import sys
import time

# `Running tests/it.rs (target/release/deps/it-0123456789abcdef)`: `it`
RUNNING = re.compile(r"^\s*Running .*\((?:.*/)?([^/)]+?)(?:-[0-9a-f]{16})?\)$")
DOCTESTS = re.compile(r"^\s*Doc-tests (\S+)")
STARTS = re.compile(r"^running (\d+) tests?$")
ENDS = re.compile(r"^test (.+?) \.\.\. (ok|FAILED|ignored)(?:, .*)?$")


def threads():
    n = os.environ.get("RUST_TEST_THREADS")
    if n and n.isdigit() and int(n) > 0:
        return int(n)
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:
        return max(1, os.cpu_count() or 1)


def durations(start, ends, n):
    """Each test's time from the binary's start and its tests' ends."""
    queue = sorted(name for name, _ in ends)
    began = {}
    waiting = iter(queue)
    for _ in range(min(n, len(queue))):
        began[next(waiting)] = start
    out = []
    for name, t in ends:
        out.append((t - began.get(name, start), name))
        nxt = next(waiting, None)
        if nxt is not None:
            began[nxt] = t
    return out


def main():
    count = int(sys.argv[1]) if len(sys.argv) > 1 else 10
    n = threads()
    binary, start, ends, every = None, None, [], []

    def close():
        if binary is not None and start is not None and ends:
            every.extend((d, binary, name) for d, name in durations(start, ends, n))

    for line in iter(sys.stdin.readline, ""):
        now = time.monotonic()
        sys.stdout.write(line)
        sys.stdout.flush()
        text = line.rstrip("\n")
        m = RUNNING.match(text) or DOCTESTS.match(text)
        if m:
            close()
            binary, start, ends = m.group(1), None, []
            continue
        m = STARTS.match(text)
        if m and binary is not None:
            start, ends = now, []
            continue
        m = ENDS.match(text)
        if m and start is not None:
            ends.append((m.group(1), now))
    close()
    every.sort(reverse=True)
    print(f"\nThe {min(count, len(every))} slowest tests ({n} at a time; wall clock):")
    for d, binary, name in every[:count]:
        print(f"  {d:7.1f} s  {binary}: {name}")


if __name__ == "__main__":
    main()
