#!/usr/bin/env python3
"""Summarise a benchmarks/build_time.sh run (docs/build.md): CPU seconds per tree, per target and
per file, the phases' wall times, the tests' own times and the machine's load."""
import csv
import os
import re
import sys
from collections import defaultdict

USAGE = "usage: build_time_summary.py OUT_DIR   (a directory benchmarks/build_time.sh wrote)"


def read(path, default=""):
    try:
        with open(path) as f:
            return f.read().strip()
    except FileNotFoundError:
        return default


def tree_of(directory, out):
    rel = os.path.relpath(directory, out)
    return rel.split(os.sep)[0]


def target_of(kind, output):
    m = re.search(r"CMakeFiles/([^/]+)\.dir/", output)
    if m:
        return m.group(1)
    return os.path.basename(output) if kind == "link" else "?"


def main():
    if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
        print(USAGE)
        return 0 if len(sys.argv) == 2 else 2
    out = os.path.abspath(sys.argv[1])
    steps_path = os.path.join(out, "steps.csv")
    if not os.path.exists(steps_path):
        print(f"build_time_summary.py: {steps_path} is missing: run benchmarks/build_time.sh first",
              file=sys.stderr)
        return 2

    per_tree = defaultdict(lambda: {"compile": [0, 0.0], "link": [0, 0.0]})
    per_target = defaultdict(float)
    files = []
    with open(steps_path) as f:
        for row in csv.DictReader(f):
            try:
                cpu = float(row["user_s"]) + float(row["sys_s"])
            except (TypeError, ValueError):
                continue  # a line /usr/bin/time wrote for a failed command ("Command exited ...")
            tree = tree_of(row["dir"], out)
            kind = row["kind"]
            per_tree[tree][kind][0] += 1
            per_tree[tree][kind][1] += cpu
            per_target[(tree, target_of(kind, row["output"]))] += cpu
            if kind == "compile":
                files.append((cpu, tree, row["output"]))

    lines = []
    start, end = read(os.path.join(out, "start")), read(os.path.join(out, "end"))
    # GNU time writes "Command exited with non-zero status N" before its numbers when make fails.
    time_lines = read(os.path.join(out, "make_test.time")).splitlines()
    tm = time_lines[-1].split() if time_lines else []
    rc = read(os.path.join(out, "make_test.rc"), "?")
    if start and end and len(tm) >= 2:
        lines.append(f"make test: exit {rc}, wall {int(end) - int(start)} s, "
                     f"CPU {float(tm[0]) + float(tm[1]):.0f} s (user+sys of make and everything it ran)")
    loads = [float(l.split()[1]) for l in read(os.path.join(out, "load.txt")).splitlines() if l]
    if loads:
        lines.append(f"load average (1 min) during the run: mean {sum(loads) / len(loads):.1f}, "
                     f"min {min(loads):.1f}, max {max(loads):.1f} ({len(loads)} samples)")

    # Phases: make echoes each recipe line before it runs it, and the test recipe says "make test:"
    # where the sanitizer tree's tests start beside the optimised tree's build and where each of the
    # two ends; every line of the log has its time.
    phases = []
    for line in read(os.path.join(out, "make_test.log")).splitlines():
        stamp, _, text = line.partition(" ")
        text = text.strip()  # a continuation line of a recipe starts with a tab
        if text.startswith("cmake --build ") or text.startswith("ctest --output-on-failure") or (
                "ctest " in text and text.startswith("cd ")) or text.startswith("make test: "):
            phases.append((float(stamp), text[:90]))
    if phases and end:
        lines.append("phases (wall):")
        bounds = [p[0] for p in phases[1:]] + [float(end)]
        for (t0, text), t1 in zip(phases, bounds):
            lines.append(f"  {t1 - t0:7.0f} s  {text}")
    for line in read(os.path.join(out, "make_test.log")).splitlines():
        m = re.search(r"(\d+% tests passed.*|Total Test time \(real\) = .*)", line)
        if m:
            lines.append("  ctest: " + m.group(1))

    lines.append("CPU seconds of compiles and links (user+sys):")
    total = 0.0
    for tree in sorted(per_tree):
        c, l = per_tree[tree]["compile"], per_tree[tree]["link"]
        total += c[1] + l[1]
        lines.append(f"  {tree:12s} {c[0]:4d} compiles {c[1]:8.0f} s   {l[0]:4d} links {l[1]:6.0f} s")
    lines.append(f"  {'all':12s} {total:.0f} s")
    lines.append("top 20 files (CPU s, tree, object):")
    for cpu, tree, output in sorted(files, reverse=True)[:20]:
        lines.append(f"  {cpu:6.1f}  {tree:10s} {output}")
    lines.append("top 15 targets (CPU s of their compiles and link):")
    for (tree, target), cpu in sorted(per_target.items(), key=lambda x: -x[1])[:15]:
        lines.append(f"  {cpu:7.1f}  {tree:10s} {target}")

    text = "\n".join(lines) + "\n"
    with open(os.path.join(out, "summary.txt"), "w") as f:
        f.write(text)
    sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
