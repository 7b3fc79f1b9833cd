"""CPU time of one cold `scenewright generate village --seed 7 -o DIR`, as a user runs it.

Each run is a new process (the console command), so the interpreter's start-up and
every import count. The CPU time (user + system, the command's own and its children's)
is split three ways:

- start-up: the interpreter's own start and importing every module the command loads;
- stages: the stage times the command writes to timings.json (expand, layout,
  describe, render, export), in a run whose modules are already imported;
- writing: the rest of that run (the output files, the plan image, the summary line);
- exit: the process's end (exit functions, and the interpreter's teardown where the
  command does not skip it).

The split comes from a second process per run that imports the command's modules
first, then runs it in-process and ends as the command does; the total is the plain
command's.

The figures are medians over --runs runs; the first run is thrown away, since it may
compile bytecode. Usage: python benchmarks/bench_startup.py [--runs 7] [--rules village]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path


def child_cpu(command: list[str]) -> float:
    """CPU seconds (user + system) that running ``command`` to its end costs."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


# A child that runs the command in-process in three timed steps: what the interpreter
# costs before the first line, importing every module the command will load (the names
# come from a first run) with the environment the console command sets itself, then the
# command itself with nothing left to import; then it ends as the console command does
# (``scenewright.cli.run``, where the code has it), so that its whole CPU time less the
# three steps is what the command's end costs.
SPLIT = """
import json, sys, time
started = time.process_time()
import scenewright.cli as cli
if hasattr(cli, "set_process_defaults"):
    cli.set_process_defaults()
modules = json.loads(sys.argv[1])
for name in modules:
    __import__(name)
imported = time.process_time()
if hasattr(cli, "run"):
    from scenewright.core.collector import collect_less
    collect_less()
try:
    code = cli.main(sys.argv[2:])
except SystemExit as done:
    code = done.code
print(json.dumps([started, imported - started, time.process_time() - imported]), flush=True)
if hasattr(cli, "exit_now"):
    cli.exit_now(code)
sys.exit(code)
"""

LOADED = """
import json, sys
from scenewright.cli import main
try:
    main(sys.argv[1:])
except SystemExit:
    pass
print(json.dumps(list(sys.modules)))
"""


def loaded_modules(arguments: list[str]) -> list[str]:
    """The modules a run of the command with ``arguments`` has loaded by its end."""
    done = subprocess.run(
        [sys.executable, "-c", LOADED, *arguments], capture_output=True, text=True, check=True
    )
    # The project's own modules in the order they were first imported: they import the
    # libraries as the command does (the renderer's OpenGL platform is chosen before
    # OpenGL is first imported).
    names = json.loads(done.stdout.splitlines()[-1])
    return [name for name in names if name.split(".")[0] == "scenewright"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--rules", default="village")
    parser.add_argument("--seed", type=int, default=7)
    args = parser.parse_args()

    command = Path(sys.executable).with_name("scenewright")
    totals, startups, stages, rests, exits = [], [], [], [], []
    with tempfile.TemporaryDirectory() as scratch:
        arguments = ["generate", args.rules, "--seed", str(args.seed), "-o"]
        modules = loaded_modules([*arguments, os.path.join(scratch, "loaded")])
        for run in range(args.runs + 1):
            out = os.path.join(scratch, f"run{run}")
            total = child_cpu([str(command), *arguments, out])
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            split = subprocess.run(
                [sys.executable, "-c", SPLIT, json.dumps(modules), *arguments, out + "-split"],
                capture_output=True,
                text=True,
                check=True,
            )
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            whole = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
            started, imported, ran = json.loads(split.stdout.splitlines()[-1])
            stage = sum(json.loads(Path(out + "-split", "timings.json").read_text()).values())
            if run == 0:
                continue
            totals.append(total)
            startups.append(started + imported)
            stages.append(stage)
            rests.append(ran - stage)
            exits.append(whole - started - imported - ran)
    total, startup, stage, rest, end = (
        statistics.median(v) for v in (totals, startups, stages, rests, exits)
    )
    print(f"cold `scenewright generate {args.rules} --seed {args.seed} -o DIR`, {args.runs} runs")
    print(f"  CPU total         {total:6.2f} s  (min {min(totals):.2f}, max {max(totals):.2f})")
    print(f"  start-up          {startup:6.2f} s  (the interpreter and every import)")
    print(f"  stages            {stage:6.2f} s  (timings.json: expand ... export)")
    print(f"  writing           {rest:6.2f} s")
    print(f"  exit              {end:6.2f} s")


if __name__ == "__main__":
    main()
