#!/usr/bin/env python3
"""Mutation testing for polysim: does the test suite notice one-line bugs?

Applies each mutant of tests/mutation/mutants.txt in turn to a copy of the source tree,
rebuilds the test binary incrementally, runs the suite (without the 60-second stacks,
stopping at the first failure) and reports which mutants the suite killed and which
survived. Nothing in the working tree is touched: the copy and its build live under
--work (default /tmp/polysim-mutation) and are reused between runs.

    tests/mutation/run_mutants.py                 # every mutant
    tests/mutation/run_mutants.py --only NAME ... # some of them
    tests/mutation/run_mutants.py --list          # names and whether each still applies

Exit status: 0 when the share killed is at least --min-score percent (default 90) and
no mutant is stale or fails to build, 1 otherwise. A mutant marked `equivalent:` (no
test can tell it from the original: it changes only speed, or guards against what
cannot happen) is run like the others but left out of the score; should one be killed,
the mark is wrong and the run says so. Runs on demand, not in CI: each
mutant costs an incremental build and a run of the suite (about a minute here).
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
MUTANTS = Path(__file__).resolve().parent / "mutants.txt"
# Tests left out of every mutant's run: the 60-second stacks take minutes, and the
# pyramid and shorter stacks exercise the same code.
SLOW_TESTS = "*StandsFor60s*"
# The soak as ctest runs it (tests/soak/CMakeLists.txt).
SOAK_ARGUMENTS = ["--steps", "3000", "--report-every", "3000", "--flat-memory-from", "1000", "--memory-slack", "4"]


@dataclass
class Mutant:
    name: str
    file: str = ""
    why: str = ""
    equivalent: str = ""  # why no test can tell it from the original (it is then left out of the score)
    edits: list = field(default_factory=list)  # (find, replace) pairs


def parse_mutants(path):
    mutants, current, pending_find = [], None, None
    for number, raw in enumerate(path.read_text().splitlines(), 1):
        line = raw.rstrip("\n")
        if line.startswith("#") or not line.strip():
            continue
        if line.startswith("=== "):
            current = Mutant(line[4:].strip())
            mutants.append(current)
        elif current is None:
            sys.exit(f"{path}:{number}: text before the first '=== name'")
        elif line.startswith("file:"):
            current.file = line[5:].strip()
        elif line.startswith("why:"):
            current.why = line[4:].strip()
        elif line.startswith("equivalent:"):
            current.equivalent = line[11:].strip()
        elif line.startswith("- "):
            pending_find = line[2:]
        elif line.startswith("+"):
            if pending_find is None:
                sys.exit(f"{path}:{number}: '+' without a '-' before it")
            current.edits.append((pending_find, line[2:] if line.startswith("+ ") else ""))
            pending_find = None
        else:
            sys.exit(f"{path}:{number}: not a mutant line: {line!r}")
    for m in mutants:
        if not m.file or not m.edits:
            sys.exit(f"{path}: mutant {m.name} needs a file and at least one -/+ pair")
    names = [m.name for m in mutants]
    if len(set(names)) != len(names):
        sys.exit(f"{path}: mutant names must be unique")
    return mutants


def mutated_text(source, mutant):
    """The file's text with the mutant applied, or None when a find does not occur
    exactly once (the mutant is stale)."""
    text = source
    for find, replace in mutant.edits:
        if text.count(find) != 1:
            return None
        text = text.replace(find, replace)
    return text


def sync_tree(src):
    """Copies the files git knows (tracked and untracked, not ignored) into src, writing
    only those that differ so that the build there stays incremental."""
    listed = subprocess.run(["git", "ls-files", "-z", "-co", "--exclude-standard"], cwd=REPO,
                            check=True, capture_output=True).stdout.decode().split("\0")
    for rel in filter(None, listed):
        origin, copy = REPO / rel, src / rel
        if not origin.is_file():
            continue
        data = origin.read_bytes()
        if copy.is_file() and copy.read_bytes() == data:
            continue
        copy.parent.mkdir(parents=True, exist_ok=True)
        copy.write_bytes(data)


def build(src, build_dir, log):
    # Configured every time (quick once cached): targets added since the last run exist.
    subprocess.run(["cmake", "-S", str(src), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                    "-DPOLYSIM_BUILD_TESTS=ON", "-DPOLYSIM_BUILD_BENCHMARKS=OFF"],
                   check=True, stdout=log, stderr=subprocess.STDOUT)
    result = subprocess.run(["cmake", "--build", str(build_dir), "-j2", "--target", "polysim_tests", "polysim_soak"],
                            stdout=log, stderr=subprocess.STDOUT)
    return result.returncode == 0


def run_suite(build_dir, timeout, include_slow):
    """(passed, first failing test or reason, seconds)."""
    command = [str(build_dir / "tests" / "polysim_tests"), "--gtest_fail_fast", "--gtest_brief=1"]
    if not include_slow:
        command.append(f"--gtest_filter=-{SLOW_TESTS}")
    start = time.monotonic()
    try:
        result = subprocess.run(command, cwd=build_dir, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return False, f"timed out after {timeout:.0f} s", time.monotonic() - start
    seconds = time.monotonic() - start
    if result.returncode != 0:
        failed = re.findall(r"^\[  FAILED  \] (\S+)", result.stdout, re.MULTILINE)
        return False, failed[0] if failed else f"exit status {result.returncode}", seconds
    # Then the soak, as ctest runs it (Soak.RefilledPileShort): what only a long busy run
    # shows (an island stuck at the event bound) is caught there.
    try:
        soak = subprocess.run([str(build_dir / "tests" / "soak" / "polysim_soak")] + SOAK_ARGUMENTS, cwd=build_dir,
                              capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return False, f"the soak timed out after {timeout:.0f} s", time.monotonic() - start
    if soak.returncode != 0:
        return False, "Soak.RefilledPileShort", time.monotonic() - start
    return True, "", time.monotonic() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--work", type=Path, default=Path("/tmp/polysim-mutation"))
    parser.add_argument("--only", nargs="+", metavar="NAME", help="run only these mutants")
    parser.add_argument("--list", action="store_true", help="list the mutants and whether each applies; run nothing")
    parser.add_argument("--all-tests", action="store_true", help="include the 60-second stacks")
    parser.add_argument("--min-score", type=float, default=90.0, help="percent killed needed for exit status 0")
    args = parser.parse_args()

    mutants = parse_mutants(MUTANTS)
    if args.only:
        unknown = set(args.only) - {m.name for m in mutants}
        if unknown:
            sys.exit(f"no such mutant: {', '.join(sorted(unknown))}")
        mutants = [m for m in mutants if m.name in args.only]
    if args.list:
        for m in mutants:
            path = REPO / m.file
            applies = path.is_file() and mutated_text(path.read_text(), m) is not None
            print(f"{m.name:40} {m.file:36} {'applies' if applies else 'STALE'}")
        return 0

    src, build_dir = args.work / "src", args.work / "build"
    src.mkdir(parents=True, exist_ok=True)
    sync_tree(src)
    log_path = args.work / "build.log"
    with open(log_path, "w") as log:
        print("building the unmutated tree ...", flush=True)
        if not build(src, build_dir, log):
            sys.exit(f"the unmutated tree does not build: see {log_path}")
    passed, reason, baseline = run_suite(build_dir, 3600, args.all_tests)
    if not passed:
        sys.exit(f"the unmutated suite fails ({reason}): fix it before mutating")
    timeout = max(120.0, 5 * baseline)
    print(f"baseline suite: {baseline:.1f} s; a mutant's run times out after {timeout:.0f} s", flush=True)

    results = []
    for m in mutants:
        path = src / m.file
        original = path.read_text()
        text = mutated_text(original, m)
        if text is None:
            results.append((m, "stale", "a '-' text does not occur exactly once", 0.0))
        else:
            path.write_text(text)
            try:
                with open(args.work / f"build-{m.name}.log", "w") as log:
                    built = build(src, build_dir, log)
                if not built:
                    results.append((m, "no-build", f"see {args.work}/build-{m.name}.log", 0.0))
                else:
                    passed, reason, seconds = run_suite(build_dir, timeout, args.all_tests)
                    results.append((m, "survived" if passed else "killed", reason, seconds))
            finally:
                path.write_text(original)
                os.utime(path)  # newer than the mutant's objects: the next build recompiles it
        m_, outcome, reason, seconds = results[-1]
        print(f"{outcome:9} {m.name:40} {reason} ({seconds:.1f} s)", flush=True)

    with open(log_path, "a") as log:  # leave the copy's build unmutated
        build(src, build_dir, log)

    ran = [r for r in results if r[1] in ("killed", "survived")]
    counted = [r for r in ran if not r[0].equivalent]
    killed = sum(r[1] == "killed" for r in counted)
    score = 100.0 * killed / len(counted) if counted else 0.0
    print(f"\n{killed} of {len(counted)} mutants killed ({score:.0f}%); "
          f"{sum(r[1] == 'killed' for r in ran)} of {len(ran)} counting the {len(ran) - len(counted)} marked equivalent")
    for m, outcome, reason, seconds in results:
        if outcome == "survived" and m.equivalent:
            print(f"  equivalent: {m.name} ({m.file}): {m.equivalent}")
        elif outcome == "killed" and m.equivalent:
            print(f"  MARKED EQUIVALENT BUT KILLED: {m.name} by {reason}: remove the mark")
        elif outcome != "killed":
            print(f"  {outcome}: {m.name} ({m.file}): {m.why}")
    broken = any(r[1] in ("stale", "no-build") or (r[1] == "killed" and r[0].equivalent) for r in results)
    return 0 if score >= args.min_score and not broken else 1


if __name__ == "__main__":
    sys.exit(main())
