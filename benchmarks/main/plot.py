#!/usr/bin/env python3
"""Work-precision diagrams and scaling plots from tumble_bench's CSV files.

Usage: main/plot.py RESULTS_DIR

Reads, in RESULTS_DIR (written by tumble_bench, see benchmarks/main/csv.cpp):
  work_precision_<problem>.csv  one row per method x tolerance (or RK4 step size)
  problems.csv                  id, title, reference, reference_uncertainty_rad
  scaling.csv                   the chain of N bodies (optional)
  mechanism_<problem>.csv       study (e), one row per method x tolerance (optional), with
  mechanisms.csv                each mechanism's title and error measure
and writes work_precision_<problem>.png (max attitude error on x, run time on y, log-log, one
line per method; Adams on the left, BDF on the right, RK4 on both), scaling.png and
mechanisms.png (one panel per mechanism: its error on x, run time on y, one line per method).
Needs matplotlib only (python3-matplotlib on Debian).
"""

import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TARGET_ERRORS = (1e-3, 1e-6, 1e-9)


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def number(text):
    try:
        x = float(text)
    except (TypeError, ValueError):
        return math.nan
    return x


def curves(rows):
    """method -> [(error, time)] in the order of the sweep (tolerance or step size), ok rows with
    a finite positive error."""
    out = {}
    for r in rows:
        err, t = number(r["max_attitude_error_rad"]), number(r["time_s"])
        if r["ok"] != "1" or not (err > 0 and math.isfinite(err) and t > 0):
            continue
        out.setdefault(r["method"], {"family": r["family"], "scheme": r["scheme"],
                                     "points": []})["points"].append((err, t))
    return out


FLOOR_STYLES = [("black", "s"), ("dimgray", "o"), ("tab:olive", "^"), ("tab:cyan", "v"),
                ("tab:pink", "D")]


def style(method, family, index):
    if family == "floor":
        color, marker = FLOOR_STYLES[index % len(FLOOR_STYLES)]
        return dict(color=color, linestyle="--", linewidth=2.0, marker=marker, markersize=4,
                    label=method)
    if family in ("pinocchio", "peer"):
        mujoco, exudyn = method.startswith("MuJoCo"), method.startswith("Exudyn")
        color = "black" if mujoco else "tab:purple" if exudyn else "tab:brown"
        return dict(color=color, linestyle=":", linewidth=2.2,
                    marker="s" if mujoco else "v" if exudyn else "D", markersize=4, label=method)
    if family == "rk4":
        return dict(color="dimgray", linestyle="-.", linewidth=1.8, marker="x", markersize=5,
                    label=method)
    colors = plt.get_cmap("tab20").colors
    markers = "o^vsPX*<>dph"
    return dict(color=colors[(2 * index) % 20 if index < 10 else (2 * index + 1) % 20],
                linestyle="-", linewidth=1.3, marker=markers[index % len(markers)],
                markersize=4, label=method.replace("tumble ", ""))


def plot_problem(results, problem_id, info):
    rows = read_csv(os.path.join(results, f"work_precision_{problem_id}.csv"))
    data = curves(rows)
    if not data:
        return None
    tumble_names, floor_names = [], []
    for m, c in data.items():
        names = {"tumble": tumble_names, "floor": floor_names}.get(c["family"])
        if names is not None:
            name = m.rsplit(" ", 1)[0]
            if name not in names:
                names.append(name)
    fig, axes = plt.subplots(1, 2, figsize=(15, 6.5), sharey=True)
    for ax, scheme in zip(axes, ("adams", "bdf")):
        for m, c in data.items():
            # BDF on the right; Adams and the explicit methods (RK4, ARKODE, Odeint) on the left
            if (c["scheme"] == "bdf") != (scheme == "bdf"):
                continue
            names = {"tumble": tumble_names, "floor": floor_names}.get(c["family"])
            index = names.index(m.rsplit(" ", 1)[0]) if names is not None else 0
            errs, times = zip(*c["points"])
            ax.loglog(errs, times, **style(m, c["family"], index))
        for e in TARGET_ERRORS:
            ax.axvline(e, color="lightgray", linewidth=0.8, zorder=0)
        unc = number(info.get("reference_uncertainty_rad", "0"))
        if unc > 1e-15:
            ax.axvspan(1e-17, 3 * unc, color="mistyrose", zorder=0,
                       label="below 3x the reference's uncertainty")
        ax.set_xlabel("max attitude error over the output times (rad, geodesic angle)")
        ax.set_title("CVODE Adams, explicit Runge-Kutta (ARKODE, Odeint) and fixed-step RK4"
                     if scheme == "adams" else "CVODE BDF (rtol = atol = tol)", fontsize=9)
        ax.grid(True, which="major", alpha=0.3)
        ax.invert_xaxis()
        ax.legend(fontsize=7, loc="upper left", ncol=1)
    axes[0].set_ylabel("run time (s, best of several runs)")
    xs = [e for c in data.values() for e, _ in c["points"]]
    lo, hi = min(xs), max(xs)
    for ax in axes:
        ax.set_xlim(max(hi * 2, 1), max(lo / 2, 1e-16))
    fig.suptitle(f"{problem_id}: {info.get('title', '')}\nreference: {info.get('reference', '')}",
                 fontsize=9)
    fig.tight_layout()
    out = os.path.join(results, f"work_precision_{problem_id}.png")
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out


def plot_scaling(results):
    path = os.path.join(results, "scaling.csv")
    if not os.path.exists(path):
        return None
    rows = [r for r in read_csv(path) if r["ok"] == "1"]
    if not rows:
        return None
    series = {}
    for r in rows:
        series.setdefault(r["measurement"], []).append(
            (int(r["bodies"]), number(r["seconds"]), number(r["seconds_per_body"])))
    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 5))
    if "rhs" in series:
        pts = sorted(series["rhs"])
        left.semilogx([p[0] for p in pts], [p[2] * 1e9 for p in pts], "o-", color="tab:blue",
                      label="right-hand side per body")
        per = [p[2] * 1e9 for p in pts]
        low = min(per)
        left.axhspan(low, 1.2 * low, color="honeydew", label="within 1.2x of the lowest")
        left.set_ylim(0, max(per) * 1.3)
    left.set_xlabel("bodies N")
    left.set_ylabel("ns per body")
    left.set_title("right-hand-side cost per body (flat = O(N))")
    left.grid(True, which="both", alpha=0.3)
    left.legend(fontsize=8)
    labels = {"bdf-dense": ("dense LU, exact Jacobian", "tab:red", "s"),
              "bdf-band": ("band LU, exact Jacobian", "tab:green", "o"),
              "bdf-band-dq": ("band LU, difference quotients", "tab:olive", "x"),
              "bdf-gmres": ("GMRES, block preconditioner", "tab:purple", "^")}
    for key, (label, color, marker) in labels.items():
        if key in series:
            pts = sorted(series[key])
            right.loglog([p[0] for p in pts], [p[1] for p in pts], marker=marker, color=color,
                         label=label)
    band = sorted(series.get("bdf-band", []))
    if len(band) >= 2:
        n0, t0 = band[-1][0], band[-1][1]
        ns = [p[0] for p in band]
        right.loglog(ns, [t0 * n / n0 for n in ns], ":", color="gray", label="slope 1 (linear)")
    right.set_xlabel("bodies N")
    right.set_ylabel("seconds per BDF step")
    right.set_title("cost per BDF step (rtol 1e-6, atol 1e-8)")
    right.grid(True, which="both", alpha=0.3)
    right.legend(fontsize=8)
    fig.suptitle("scaling: a chain of N Euler-parameter bodies joined by spring-dampers",
                 fontsize=10)
    fig.tight_layout()
    out = os.path.join(results, "scaling.png")
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out


def plot_mechanisms(results):
    ids = sorted(n[len("mechanism_"):-len(".csv")] for n in os.listdir(results)
                 if n.startswith("mechanism_") and n.endswith(".csv"))
    if not ids:
        return None
    info = {}
    path = os.path.join(results, "mechanisms.csv")
    if os.path.exists(path):
        info = {r["id"]: r for r in read_csv(path)}
    fig, axes = plt.subplots(1, len(ids), figsize=(5.2 * len(ids), 4.6), squeeze=False)
    for ax, problem_id in zip(axes[0], ids):
        lines = {}
        for r in read_csv(os.path.join(results, f"mechanism_{problem_id}.csv")):
            err, t = number(r["error"]), number(r["time_s"])
            if r["ok"] == "1" and err > 0 and math.isfinite(err) and t > 0:
                lines.setdefault(r["method"], []).append((err, t))
        for index, (method, pts) in enumerate(lines.items()):
            peer = method.startswith(("MuJoCo", "Exudyn"))
            kw = style(method, "peer" if peer else "tumble", index)
            if peer and "default" in method:  # MuJoCo's two settings apart
                kw.update(color="gray", marker="o")
            if peer and "Trapezoidal" in method:  # Exudyn's two solvers apart
                kw.update(color="orchid", marker="^")
            ax.loglog([p[0] for p in pts], [p[1] for p in pts], **kw)
        for e in TARGET_ERRORS:
            ax.axvline(e, color="lightgray", linewidth=0.8, zorder=0)
        ax.invert_xaxis()
        row = info.get(problem_id, {})
        ax.set_title(problem_id + ": " + row.get("title", "").split(":")[0], fontsize=9)
        ax.set_xlabel(row.get("error_measure", "error"), fontsize=7)
        ax.set_ylabel("run time (s)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("(e) mechanisms: work precision of tumble's integrators"
                 " (and MuJoCo's RK4 and Exudyn's implicit solvers, when installed)",
                 fontsize=10)
    fig.tight_layout()
    out = os.path.join(results, "mechanisms.png")
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    results = sys.argv[1]
    info = {}
    problems_csv = os.path.join(results, "problems.csv")
    if os.path.exists(problems_csv):
        info = {r["id"]: r for r in read_csv(problems_csv)}
    written = []
    for name in sorted(os.listdir(results)):
        if name.startswith("work_precision_") and name.endswith(".csv"):
            problem_id = name[len("work_precision_"):-len(".csv")]
            out = plot_problem(results, problem_id, info.get(problem_id, {}))
            if out:
                written.append(out)
    for plot in (plot_scaling, plot_mechanisms):
        out = plot(results)
        if out:
            written.append(out)
    for w in written:
        print(f"plot: {w}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
