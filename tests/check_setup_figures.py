#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""The README's set-up figures: recorded and written by tests/measure-setup.sh, checked by the suite.

  record FIGURES PART --seconds S --log LOG --packages N --disk-kib K --download-kib D --commit C
  write FIGURES README      renders FIGURES (docs/setup-figures.json) into README's marked blocks
  check README [SOURCE]     (the `setup-figures` test) README's blocks are FIGURES' rendering; the lists'
                            sizes it states are tests/bootstrap.sh's; its build steps are within 10 % of
                            what the tree needs now (a dry run of ninja in a scratch build directory)
"""
import argparse
import datetime
import json
import os
import re
import subprocess
import sys
import tempfile

FIGURES = "docs/setup-figures.json"
STEP_DRIFT = 0.10  # beyond this, the build has changed enough that the figures must be measured again
BLOCK = re.compile(r"<!-- setup-figures (\w+) -->\n(.*?)<!-- /setup-figures -->", re.S)


def build_steps(log_lines):
    """Sum of the totals of the ninja runs in a log ("[x/N]" lines; a run starts again at x <= 1). Meson's
    "[0/1] Regenerating build files" is not a build step (the dry run does not count it either)."""
    total, current = 0, 0
    for line in log_lines:
        m = re.search(r"\[(\d+)/(\d+)\] ", line)
        if not m or "Regenerating build files" in line:
            continue
        if int(m.group(1)) <= 1:
            total += current
        current = int(m.group(2))
    return total + current


def phases(log_lines):
    """run-debian13.sh's phase summary: the "   NAME   N s" lines after "== Debian 13 run: phases" (each log
    line starts with a Unix time)."""
    found, inside = {}, False
    for line in log_lines:
        if "== Debian 13 run: phases" in line:
            inside = True
            continue
        m = re.match(r"\d+ +(\S.*?)\s+(\d+) s$", line)
        if inside and m:
            found[m.group(1)] = int(m.group(2))
    return found


def tests_seconds(log_lines):
    """Seconds from meson test's first result to the end of the log (lines start with a Unix time)."""
    first = next((ln for ln in log_lines if re.match(r"\d+ +1/\d+ ", ln)), None)
    if first is None or not log_lines:
        return None
    return int(log_lines[-1].split()[0]) - int(first.split()[0])


def record(args):
    figures = json.load(open(args.figures)) if os.path.exists(args.figures) else {}
    lines = open(args.log, errors="replace").read().splitlines()
    figures[args.part] = {
        "date": datetime.date.today().isoformat(), "commit": args.commit, "seconds": args.seconds,
        "packages": args.packages, "disk_kib": args.disk_kib, "download_kib": args.download_kib,
        "build_steps": build_steps(lines), "tests_seconds": tests_seconds(lines), "phases": phases(lines)}
    json.dump(figures, open(args.figures, "w"), indent=1, sort_keys=True)


def minutes(seconds):
    return f"{seconds // 60} min {seconds % 60} s"


def gb(kib):
    return f"{kib / 1024 / 1024:.1f} GB"


def mb(kib):
    return f"{kib / 1024:.0f} MB"


def render(part, f):
    when = f"on {f['date']} (commit {f['commit']})"
    if part == "demo":
        return (f"Measured by `tests/measure-setup.sh` {when} in a fresh `debootstrap --variant=minbase bookworm`\n"
                f"chroot (plus `git` and `ca-certificates` to clone, not counted), on a 2-core machine shared with\n"
                f"other work: {f['packages']} packages with their dependencies, {mb(f['download_kib'])} to download,"
                f" {gb(f['disk_kib'])} on disk\nwith apt's cache, {f['build_steps']} build steps,"
                f" {minutes(f['seconds'])} in all.\n")
    if part == "tests":
        alone = f", the tests alone {minutes(f['tests_seconds'])}" if f.get("tests_seconds") else ""
        return (f"Measured by `tests/measure-setup.sh` after the demo in the same chroot, {when}:\n"
                f"{f['packages']} more packages, {mb(f['download_kib'])} to download, {gb(f['disk_kib'])} more on"
                f" disk with apt's cache\nand node-mavlink, {f['build_steps']} build steps;"
                f" {minutes(f['seconds'])} in all{alone}.\n")
    aside = f"`tests/measure-setup.sh` on {f['date']}, commit {f['commit']}, a 2-core machine shared with other work"
    if part == "sanitized":
        return f"{minutes(f['seconds'])} and {gb(f['disk_kib'])} more, {f['build_steps']} build steps; {aside}"
    if part == "debian13":
        order = ["debootstrap", "copy", "packages and build", "tests"]
        names = sorted(f["phases"], key=lambda n: order.index(n) if n in order else len(order))
        steps = ", ".join(f"{name} {minutes(f['phases'][name])}" for name in names)
        return f"{minutes(f['seconds'])} and {gb(f['disk_kib'])} from nothing ({steps}; {aside})"
    raise SystemExit(f"unknown part {part}")


def rendered(readme, figures):
    def one(m):
        part = m.group(1)
        if part not in figures:
            raise SystemExit(f"{FIGURES} has no figures for the README's '{part}' block")
        return f"<!-- setup-figures {part} -->\n{render(part, figures[part])}<!-- /setup-figures -->"
    return BLOCK.sub(one, readme)


def write(args):
    figures = json.load(open(args.figures))
    repo = os.path.dirname(os.path.abspath(args.readme))
    with open(os.path.join(repo, FIGURES), "w") as out:
        json.dump(figures, out, indent=1, sort_keys=True)
        out.write("\n")
    text = open(args.readme).read()
    open(args.readme, "w").write(rendered(text, figures))


def listed(bootstrap, name):
    """The number of packages in one of tests/bootstrap.sh's lists."""
    body = re.search(name + r"=\((.*?)\)", bootstrap, re.S).group(1)
    return len([w for ln in body.splitlines() for w in ln.split("#")[0].split()])


def dry_run_steps(source):
    """Build steps of the demo's first build and of the test command's build after it, by ninja's dry run."""
    with tempfile.TemporaryDirectory() as build:
        def run(*cmd):
            return subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
        run("meson", "setup", build, source, "-Dtests=false", "-Dbenchmarks=false")
        demo_targets = ["gst/libgstcolortrack.so", "examples/colortrack-demo"]
        demo = len(run("ninja", "-C", build, "-t", "commands", *demo_targets).splitlines())
        run("meson", "configure", build, "-Dtests=true", "-Dbenchmarks=true", "-Dexamples=true")
        run("ninja", "-C", build, "build.ninja")  # meson configure regenerates on ninja's next run
        everything = len(run("ninja", "-C", build, "-t", "commands").splitlines())
        return {"demo": demo, "tests": everything - demo}


def check(args):
    source = args.source or os.path.dirname(os.path.abspath(args.readme))
    if os.environ.get("COLORTRACK_MEASURING_SETUP"):
        print("SKIPPED: tests/measure-setup.sh is measuring the figures this test checks")
        return 77
    readme = open(args.readme).read()
    figures = json.load(open(os.path.join(source, FIGURES)))
    problems = []
    if rendered(readme, figures) != readme:
        problems.append(f"README's set-up blocks differ from {FIGURES} (edited by hand?): they are written by"
                        f" tests/measure-setup.sh, or from the JSON by `tests/check_setup_figures.py write {FIGURES}"
                        f" README.md`")
    bootstrap = open(os.path.join(source, "tests/bootstrap.sh")).read()
    stated = re.search(r"installs the (\d+) packages `tests/bootstrap.sh` lists for the demo", readme)
    if not stated or int(stated.group(1)) != listed(bootstrap, "demo_packages"):
        problems.append(f"README should say the demo list has {listed(bootstrap, 'demo_packages')} packages")
    for part, now in dry_run_steps(source).items():
        measured = figures[part]["build_steps"]
        print(f"{part}: {measured} build steps measured, {now} now")
        if abs(now - measured) > STEP_DRIFT * measured:
            problems.append(f"{part}: the build has {now} steps now, {measured} when measured: run"
                            f" tests/measure-setup.sh {part} (as root) to measure the figures again")
    for p in problems:
        print("FAIL:", p)
    return 1 if problems else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    r = sub.add_parser("record")
    r.add_argument("figures")
    r.add_argument("part", choices=["demo", "tests", "sanitized", "debian13"])
    for name in ("seconds", "packages", "disk-kib", "download-kib"):
        r.add_argument("--" + name, type=int, required=True)
    r.add_argument("--log", required=True)
    r.add_argument("--commit", required=True)
    w = sub.add_parser("write")
    w.add_argument("figures")
    w.add_argument("readme")
    c = sub.add_parser("check")
    c.add_argument("readme")
    c.add_argument("source", nargs="?")
    args = parser.parse_args()
    return {"record": record, "write": write, "check": check}[args.command](args) or 0


if __name__ == "__main__":
    sys.exit(main())
