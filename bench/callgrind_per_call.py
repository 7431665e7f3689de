#!/usr/bin/python3
"""Instructions per call of chosen functions, old build against new build, counted by
callgrind: repeatable on a shared machine where wall time is not.

Steps:
1. Run the old and the new benchmark program once each under `valgrind --tool=callgrind`,
   with a filter that selects exactly the benchmarks named on the command line.
2. Read each callgrind output: for every call into a function whose demangled name matches
   the function pattern, from a caller that does not match it (so recursion counts once),
   add the call count and the inclusive instruction count of those calls, per function
   name (the name up to its argument list, so that a changed signature still pairs up).
3. Print a Markdown table: instructions per call of each function on each side and the
   ratio new / old. Counting per call makes the figure independent of how many iterations
   Google Benchmark chose and of the set-up outside the timed loop; name benchmarks that
   call different functions (e.g. one intersect, one distance) to measure several at once.

Usage:
  /usr/bin/python3 bench/callgrind_per_call.py --old OLD/build/release --new build/release \
      --program proxima_bench_narrowphase --function '^proxima::(intersect|distance|collide)\\(' \
      NP/Hull32/Boolean/proxima_plain NP/Hull32/Distance/proxima_plain NP/BoxBox/Manifold/proxima
"""
import argparse
import re
import subprocess
import sys
import tempfile
from pathlib import Path


def short_name(function: str) -> str:
    """The function's name without its arguments and the library's namespaces (the layers
    moved between namespaces in the redesign), e.g. `TriangleMesh::raycast`."""
    function = function.replace("(anonymous namespace)::", "")
    return re.sub(r"^proxima::((midphase|narrow)::)?", "", function.split("(")[0])


def per_call(out_file: Path, pattern: re.Pattern) -> dict[str, list[int]]:
    """Returns {function: [calls, inclusive Ir]} of the calls into functions matching `pattern`."""
    names: dict[str, str] = {}
    found: dict[str, list[int]] = {}
    caller_matches = False
    pending = None  # call count of the `calls=` line whose cost line comes next

    def name_of(spec: str) -> str:
        m = re.match(r"\((\d+)\)(?: (.*))?", spec)
        if not m:
            return spec
        if m.group(2) is not None:
            names[m.group(1)] = m.group(2)
        return names.get(m.group(1), "")

    callee = ""
    for line in out_file.read_text(errors="replace").splitlines():
        if pending is not None:
            fields = line.split()
            if len(fields) >= 2 and pattern.search(callee) and not caller_matches:
                entry = found.setdefault(short_name(callee), [0, 0])
                entry[0] += pending
                entry[1] += int(fields[1])
            pending = None
        elif line.startswith("fn="):
            caller_matches = bool(pattern.search(name_of(line[3:])))
        elif line.startswith("cfn="):
            callee = name_of(line[4:])
        elif line.startswith("calls="):
            pending = int(line[6:].split()[0])
        elif line.startswith(("fl=", "fi=", "fe=", "cfi=", "cfl=", "ob=", "cob=")):
            name_of(line.split("=", 1)[1])  # file and object names share the id space per kind
    return found


def measure(exe: Path, benches: list[str], pattern: re.Pattern, extra: list[str]) -> dict[str, list[int]]:
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "callgrind.out"
        only = "--benchmark_filter=^(" + "|".join(re.escape(b) for b in benches) + ")$"
        subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", "--compress-pos=no", str(exe),
                        only, "--benchmark_min_time=0.01", *extra], capture_output=True, check=True)
        return per_call(out, pattern)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--old", required=True, type=Path)
    ap.add_argument("--new", required=True, type=Path)
    ap.add_argument("--program", required=True)
    ap.add_argument("--function", required=True, help="regex on the demangled callee name")
    ap.add_argument("--workloads", default="")
    ap.add_argument("benchmarks", nargs="+")
    args = ap.parse_args()
    pattern = re.compile(args.function)
    extra = [f"--workloads={args.workloads}"] if args.workloads else []
    sides = [measure(side / "bench" / args.program, args.benchmarks, pattern, extra) for side in (args.old, args.new)]
    for name in sorted(set(sides[0]) | set(sides[1])):
        row = [side[name][1] / side[name][0] if side.get(name) and side[name][0] else float("nan") for side in sides]
        ratio = row[1] / row[0] if row[0] else float("nan")
        program = args.program.removeprefix("proxima_bench_")
        print(f"| {program} | `{name}` | {row[0]:,.0f} | {row[1]:,.0f} | {ratio:.3f} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
