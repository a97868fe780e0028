#!/usr/bin/python3
"""Summarize tumble_micro's results: ratios against the project's performance goals.

Interface (standard library only; for /usr/bin/python3 or any python >= 3.8)
---------------------------------------------------------------------------
Summarize a result file written by tumble_micro:

    tumble_micro --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \\
                 --benchmark_out=micro.json --benchmark_out_format=json
    micro/summarize.py micro.json [--markdown] [--csv times.csv] [--summary-json ratios.json]

Or let the script run tumble_micro first (this is what tumble_bench, the main job, calls for its
per-call table, reading the medians from --csv):

    micro/summarize.py --run PATH/TO/tumble_micro --quick --out DIR/micro.json

  --quick   only the benchmarks the ratios need (QUICK_FILTER below), --benchmark_min_time=0.05
            and 3 repetitions: about 5 s of CPU time (longer in wall time on a busy machine)
  (default) every benchmark, --benchmark_min_time=0.1 and 5 repetitions: a few minutes
  --min-time S, --repetitions N, --filter REGEX override those.

Output: a plain-text table on stdout (Markdown with --markdown). Exit status 0 whether targets
are met or not (--strict: 1 when one is missed), 2 when tumble_micro fails or the file cannot be
read. --summary-json writes the ratios as a list of objects {"group", "name", "value", "target",
"met"} (met is null when there is no target or the data is missing) for a caller's own table.

Times: the median over repetitions (the mean when the file has no median) of the CPU time per
call, in ns. CPU time rather than wall time because the machine may be shared: a process that is
descheduled accrues wall time but not CPU time. Every ratio compares benchmarks of one run.

Benchmark names (see micro*.cpp): <what>/<parameterization>[/<centroid|offset>], e.g.
qddot/EulerParameters/centroid; baselines hand_written[_loads]/EulerParameters/centroid and
dense_lu/<P>/<ref>; peers pinocchio_aba/<ref>, pinocchio_crba_nle[_solve]/<ref>,
mujoco_forward/<ref> (present only when built with Pinocchio or MuJoCo).
"""

import argparse
import csv
import json
import math
import os
import subprocess
import sys

QUICK_FILTER = (
    "^(qddot|qddot_loads)/(EulerParameters|RodriguesParameters|ModifiedRodriguesParameters|"
    "RotationVector|EulerZYX|EulerZXZ)/(centroid|offset)$"
    "|^hand_written"
    "|^pinocchio_aba/|^pinocchio_crba_nle_solve/|^mujoco_forward/"
    "|^dense_lu/(EulerParameters|EulerZYX)/"
    "|^chain_(rhs|projection)/(1|10|100|1000|10000)$"
)
CHAIN_SIZES = [1, 10, 100, 1000, 10000]

EP = "EulerParameters"
THREE_PARAMETER_ORDER = [
    "RodriguesParameters", "ModifiedRodriguesParameters", "RotationVector",
    "EulerXYZ", "EulerXZY", "EulerYXZ", "EulerYZX", "EulerZXY", "EulerZYX",
    "EulerXYX", "EulerXZX", "EulerYXY", "EulerYZY", "EulerZXZ", "EulerZYZ",
]
REFS = ["centroid", "offset"]

# The project's performance goals (ratios of times measured in one run; docs/benchmarks/per-call.md).
FLOOR_MAX = 1.2       # tumble's centroidal EP qddot / the hand-written closed form
PINOCCHIO_MIN = 8.0   # Pinocchio's aba / tumble's EP qddot
OFFSET_MAX = 2.0      # offset / centroid, per parameterization
THREE_PARAM_MAX = 2.5  # each 3-parameter set / Euler parameters
CHAIN_SLOPE_MAX = 1.05  # log-log slope of a mechanism chain's cost, 100 to 10^4 bodies


def to_ns(value, unit):
    return value * {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}[unit]


def load_times(path):
    """{benchmark name: CPU ns per call} from Google Benchmark's JSON output, and its context."""
    with open(path, encoding="utf-8") as f:
        data = json.load(f)
    medians, means, plain = {}, {}, {}
    for b in data.get("benchmarks", []):
        if b.get("error_occurred"):
            continue
        name = b.get("run_name", b["name"])
        ns = to_ns(b["cpu_time"], b.get("time_unit", "ns"))
        kind = b.get("aggregate_name")
        if b.get("run_type") == "aggregate":
            if kind == "median":
                medians[name] = ns
            elif kind == "mean":
                means[name] = ns
        else:
            plain.setdefault(name, []).append(ns)
    times = {}
    for name, values in plain.items():
        values = sorted(values)
        times[name] = values[len(values) // 2]
    times.update(means)
    times.update(medians)
    return times, data.get("context", {})


class Summary:
    def __init__(self, times):
        self.t = times
        self.rows = []  # (group, name, value, target_text, met)

    def ratio(self, num, den):
        a, b = self.t.get(num), self.t.get(den)
        if a is None or b is None or b <= 0:
            return None
        return a / b

    def add(self, group, name, value, op=None, target=None):
        met = None
        if value is not None and op is not None:
            met = value <= target if op == "<=" else value >= target
        self.rows.append((group, name, value, op, target, met))

    def build(self):
        # 1. the floor
        g = "floor: tumble EP centroidal qddot / hand-written closed form (target <= 1.2x)"
        self.add(g, "wrench given: qddot / hand_written",
                 self.ratio(f"qddot/{EP}/centroid", f"hand_written/{EP}/centroid"),
                 "<=", FLOOR_MAX)
        self.add(g, "loads assembled: qddot_loads / hand_written_loads",
                 self.ratio(f"qddot_loads/{EP}/centroid", f"hand_written_loads/{EP}/centroid"),
                 "<=", FLOOR_MAX)
        # 2. peers
        g = "peers: their time / tumble EP qddot, same body and wrench (aba: target >= 8x)"
        for ref in REFS:
            target = PINOCCHIO_MIN if ref == "centroid" else None
            self.add(g, f"pinocchio aba / tumble qddot ({ref})",
                     self.ratio(f"pinocchio_aba/{ref}", f"qddot/{EP}/{ref}"),
                     ">=" if target else None, target)
        for ref in REFS:
            self.add(g, f"pinocchio crba+nle+cholesky / tumble qddot ({ref})",
                     self.ratio(f"pinocchio_crba_nle_solve/{ref}", f"qddot/{EP}/{ref}"))
        for ref in REFS:
            self.add(g, f"mujoco mj_forward / tumble qddot ({ref})",
                     self.ratio(f"mujoco_forward/{ref}", f"qddot/{EP}/{ref}"))
        self.add(g, "pinocchio aba / hand-written closed form (centroid)",
                 self.ratio("pinocchio_aba/centroid", f"hand_written/{EP}/centroid"))
        # 3. offset vs centroid
        for what in ["qddot", "qddot_loads"]:
            g = f"offset / centroid, {what} (target <= 2x)"
            for p in [EP] + THREE_PARAMETER_ORDER:
                r = self.ratio(f"{what}/{p}/offset", f"{what}/{p}/centroid")
                if r is not None or p == EP:
                    self.add(g, p, r, "<=", OFFSET_MAX)
        # 4. three-parameter sets vs Euler parameters
        for what in ["qddot", "qddot_loads"]:
            for ref in REFS:
                g = f"3-parameter set / Euler parameters, {what} {ref} (target <= 2.5x)"
                for p in THREE_PARAMETER_ORDER:
                    r = self.ratio(f"{what}/{p}/{ref}", f"{what}/{EP}/{ref}")
                    if r is not None:
                        self.add(g, p, r, "<=", THREE_PARAM_MAX)
        # 5. the generic dense route (no target: the saving)
        g = "saving: dense assembly + LU / tumble qddot_loads (same loads; no target)"
        for p in [EP] + THREE_PARAMETER_ORDER:
            for ref in REFS:
                r = self.ratio(f"dense_lu/{p}/{ref}", f"qddot_loads/{p}/{ref}")
                if r is not None:
                    self.add(g, f"{p} {ref}", r)
        # 6. mechanisms: a chain's cost against its length (linear: slope 1)
        g = "mechanisms: log-log slope of a hinged chain's cost, 100 to 10^4 bodies (target <= 1.05)"
        for what in ["chain_rhs", "chain_projection"]:
            r = self.ratio(f"{what}/10000", f"{what}/100")
            self.add(g, what, None if r is None else math.log(r) / math.log(100.0), "<=",
                     CHAIN_SLOPE_MAX)
        return self


def fmt_ratio(v):
    return "n/a (not run)" if v is None else f"{v:.2f}x"


def verdict(met, op):
    if op is None:
        return ""
    if met is None:
        return "n/a"
    return "met" if met else "MISSED"


def print_text(summary, times, context, markdown, out):
    def ns(name):
        v = times.get(name)
        return "-" if v is None else f"{v:.1f}"

    host = context.get("host_name", "?")
    print(f"tumble_micro summary ({context.get('tumble_compiler', '?')}, "
          f"flags '{context.get('tumble_flags', '?')}', {context.get('num_cpus', '?')} CPUs at "
          f"{context.get('mhz_per_cpu', '?')} MHz, host {host}; CPU ns per call, medians)",
          file=out)
    key = [
        ("hand-written closed form, EP centroid", f"hand_written/{EP}/centroid"),
        ("tumble qddot, EP centroid (wrench given)", f"qddot/{EP}/centroid"),
        ("tumble qddot, EP offset (wrench given)", f"qddot/{EP}/offset"),
        ("tumble qddot_loads, EP centroid", f"qddot_loads/{EP}/centroid"),
        ("dense assembly + LU, EP centroid", f"dense_lu/{EP}/centroid"),
        ("pinocchio aba, centroid", "pinocchio_aba/centroid"),
        ("mujoco mj_forward, centroid", "mujoco_forward/centroid"),
    ]
    if markdown:
        print("\n| case | ns |\n| --- | ---: |", file=out)
        for label, name in key:
            print(f"| {label} | {ns(name)} |", file=out)
    else:
        print("", file=out)
        for label, name in key:
            print(f"  {label:<46} {ns(name):>10}", file=out)
    group = None
    for g, name, value, op, target, met in summary.rows:
        if g != group:
            group = g
            if markdown:
                print(f"\n**{g}**\n\n| | ratio | target | |\n| --- | ---: | --- | --- |",
                      file=out)
            else:
                print(f"\n{g}", file=out)
        tgt = "" if op is None else f"{op} {target:g}x"
        if markdown:
            print(f"| {name} | {fmt_ratio(value)} | {tgt} | {verdict(met, op)} |", file=out)
        else:
            print(f"  {name:<52} {fmt_ratio(value):>14} {tgt:>8} {verdict(met, op)}", file=out)
    judged = [r for r in summary.rows if r[3] is not None and r[5] is not None]
    missed = [r for r in judged if not r[5]]
    print(f"\n{len(judged) - len(missed)} of {len(judged)} targets met" +
          (": missed " + "; ".join(f"{r[1]} ({fmt_ratio(r[2])})" for r in missed)
           if missed else ""), file=out)


def print_chain(times, markdown, out):
    """A hinged chain's cost against its number of bodies (micro/chain.cpp), per call and per body."""
    rows = [n for n in CHAIN_SIZES
            if f"chain_rhs/{n}" in times or f"chain_projection/{n}" in times]
    if not rows:
        return

    def cell(name, n, per_body):
        v = times.get(f"{name}/{n}")
        if v is None:
            return "-"
        v = v / n if per_body else v
        return f"{v:.0f} ns" if v < 1e4 else (f"{v / 1e3:.1f} us" if v < 1e6 else f"{v / 1e6:.2f} ms")

    cols = [("right-hand side", "chain_rhs", False), ("per body", "chain_rhs", True),
            ("projection", "chain_projection", False), ("per body", "chain_projection", True)]
    title = ("a chain of n links hinged end to end (micro/chain.cpp): CPU time of a right-hand\n"
             "side (the banded constraint solve included) and of a projection onto the constraints")
    if markdown:
        print(f"\n{title}\n\n| n | " + " | ".join(c[0] for c in cols) + " |", file=out)
        print("| ---: |" + " ---: |" * len(cols), file=out)
        for n in rows:
            print(f"| {n} | " + " | ".join(cell(c[1], n, c[2]) for c in cols) + " |", file=out)
    else:
        print(f"\n{title}", file=out)
        print(f"  {'n':>6}" + "".join(f"{c[0]:>17}" for c in cols), file=out)
        for n in rows:
            print(f"  {n:>6}" + "".join(f"{cell(c[1], n, c[2]):>17}" for c in cols), file=out)


def print_components(times, markdown, out):
    """Every parameterization's component times (the full run)."""
    cols = [("R", "rotation/{p}"), ("G", "G/{p}")]
    for what, label in [("mass_matrix", "M"), ("centrifugal_coriolis", "f_v"),
                        ("generalized_force", "Q"), ("qddot", "qddot"),
                        ("qddot_loads", "qddot+loads"), ("dense_lu", "dense LU")]:
        for ref, short in [("centroid", "c"), ("offset", "o")]:
            cols.append((f"{label} {short}", what + "/{p}/" + ref))
    rows = [p for p in [EP] + THREE_PARAMETER_ORDER
            if any(c[1].format(p=p) in times for c in cols)]
    if not rows:
        return
    print("\ncomponent times, CPU ns per call (c: centroid, o: offset)", file=out)
    if markdown:
        print("\n| parameterization | " + " | ".join(c[0] for c in cols) + " |", file=out)
        print("| --- |" + " ---: |" * len(cols), file=out)
    else:
        print(f"  {'':<28}" + "".join(f"{c[0]:>13}" for c in cols), file=out)
    for p in rows:
        vals = []
        for _, pattern in cols:
            v = times.get(pattern.format(p=p))
            vals.append("-" if v is None else f"{v:.1f}")
        if markdown:
            print(f"| {p} | " + " | ".join(vals) + " |", file=out)
        else:
            print(f"  {p:<28}" + "".join(f"{v:>13}" for v in vals), file=out)


def run_micro(exe, out_json, quick, min_time, repetitions, bench_filter):
    if min_time is None:
        min_time = 0.05 if quick else 0.1
    if repetitions is None:
        repetitions = 3 if quick else 5
    cmd = [exe, f"--benchmark_min_time={min_time}",
           f"--benchmark_repetitions={repetitions}",
           "--benchmark_report_aggregates_only=true",
           f"--benchmark_out={out_json}", "--benchmark_out_format=json"]
    if bench_filter is None and quick:
        bench_filter = QUICK_FILTER
    if bench_filter:
        cmd.append(f"--benchmark_filter={bench_filter}")
    print("running: " + " ".join(cmd), file=sys.stderr, flush=True)
    # tumble_micro's console table goes to stderr so that stdout carries only the summary.
    proc = subprocess.run(cmd, stdout=sys.stderr, stderr=sys.stderr, check=False)
    return proc.returncode


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("json", nargs="?", help="tumble_micro's --benchmark_out JSON file")
    ap.add_argument("--run", metavar="TUMBLE_MICRO", help="run this tumble_micro first")
    ap.add_argument("--out", help="with --run: where the JSON goes (default micro.json)")
    ap.add_argument("--quick", action="store_true", help="with --run: the short list only")
    ap.add_argument("--min-time", type=float, help="with --run: --benchmark_min_time")
    ap.add_argument("--repetitions", type=int, help="with --run: --benchmark_repetitions")
    ap.add_argument("--filter", help="with --run: --benchmark_filter")
    ap.add_argument("--markdown", action="store_true", help="print Markdown tables")
    ap.add_argument("--csv", help="write every benchmark's CPU ns per call to this CSV")
    ap.add_argument("--summary-json", help="write the ratios to this JSON file")
    ap.add_argument("--no-components", action="store_true",
                    help="omit the per-parameterization component table")
    ap.add_argument("--strict", action="store_true", help="exit 1 when a target is missed")
    args = ap.parse_args(argv)

    path = args.json
    if args.run:
        path = args.out or path or "micro.json"
        rc = run_micro(args.run, path, args.quick, args.min_time, args.repetitions, args.filter)
        if rc != 0:
            print(f"micro/summarize.py: {args.run} exited with status {rc}", file=sys.stderr)
            return 2
    if not path:
        ap.error("give a JSON file or --run")
    try:
        times, context = load_times(path)
    except (OSError, ValueError, KeyError) as e:
        print(f"micro/summarize.py: cannot read {path}: {e}", file=sys.stderr)
        return 2

    summary = Summary(times).build()
    print_text(summary, times, context, args.markdown, sys.stdout)
    print_chain(times, args.markdown, sys.stdout)
    if not args.no_components and not args.quick:
        print_components(times, args.markdown, sys.stdout)
    if args.csv:
        with open(args.csv, "w", newline="", encoding="utf-8") as f:
            w = csv.writer(f)
            w.writerow(["benchmark", "cpu_ns"])
            for name in sorted(times):
                w.writerow([name, f"{times[name]:.3f}"])
    if args.summary_json:
        rows = [{"group": g, "name": n, "value": v,
                 "target": None if op is None else f"{op} {t:g}",
                 "met": met} for g, n, v, op, t, met in summary.rows]
        with open(args.summary_json, "w", encoding="utf-8") as f:
            json.dump({"source": os.path.abspath(path), "context": context, "ratios": rows},
                      f, indent=1)
    missed = any(r[3] is not None and r[5] is False for r in summary.rows)
    return 1 if (args.strict and missed) else 0


if __name__ == "__main__":
    sys.exit(main())
