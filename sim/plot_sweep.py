#!/usr/bin/python3
"""Speed against accuracy: the CSV of `polysim sweep` drawn as error against cost.

Usage: /usr/bin/python3 sim/plot_sweep.py SWEEP.csv OUT   (writes OUT.png and OUT.svg)

One panel per scene and measure. x: CPU time per simulated second (the stepping thread's,
so runs sharing a machine do not inflate it; wall time for a CSV from before the sweep
recorded CPU time); y: error against the analytic answer. Each line is one engine setting (solver and its parameter) through the
steps it was run at, smallest step at the costly end. Errors below 1e-12 are drawn at
1e-12 (the panels are logarithmic), but for figures with no analytic answer (the time to
rest, the run's length when the scene never came to rest), drawn as they are on a linear
scale. Runs with ODE solver warnings are drawn hollow.
Needs Debian's python3-matplotlib; run with /usr/bin/python3.
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ERROR_FLOOR = 1e-12
COLUMNS = ["scene", "engine", "solver", "parameter_name", "parameter", "dt", "cost_s_per_s", "metric", "error",
           "solver_warnings"]
UNITS = {"first_contact_time": "s", "rest_height": "m", "bounce_apex": "m", "slide_distance": "m",
         "stack_drift": "m", "max_penetration": "m", "displacement": "m", "energy_gain": "J", "time_to_rest": "s"}
# Figures with no analytic answer: the sweep writes 0 for it, so the "error" is the figure.
NO_ANALYTIC_ANSWER = {"time_to_rest"}
COLOURS = {("polysim", "bisection"): "tab:blue", ("polysim", "regula-falsi"): "tab:green",
           ("polysim", "regula-falsi", "solver_sweeps"): "tab:purple",
           ("ode", "quickstep"): "tab:red", ("ode", "worldstep"): "tab:orange"}
MARKERS = "osD^v<>"


def read_rows(path):
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        missing = [c for c in COLUMNS if c not in (reader.fieldnames or [])]
        if missing:
            raise ValueError(f"{path}: not a sweep CSV, no column {missing[0]!r}")
        rows = []
        for line, row in enumerate(reader, start=2):
            try:
                for key in ("parameter", "dt", "cost_s_per_s", "error", "solver_warnings"):
                    row[key] = float(row[key])
                key = "cpu_cost_s_per_s"
                row["cost"] = float(row[key]) if key in row else row["cost_s_per_s"]
            except ValueError:
                raise ValueError(f"{path}: line {line}: column {key!r} is not a number: {row[key]!r}")
            rows.append(row)
        if not rows:
            raise ValueError(f"{path}: no rows")
        return rows


def series_key(row):
    """Engine and solver, and the parameter's name where one solver sweeps two (polysim)."""
    if row["parameter_name"] == "solver_sweeps":
        return (row["engine"], row["solver"], "solver_sweeps")
    return (row["engine"], row["solver"])


def label(row):
    if row["parameter_name"] == "tolerance_m":
        return f"{row['engine']} {row['solver']}, tol {row['parameter']:g} m"
    if row["parameter_name"] == "solver_sweeps":
        return f"{row['engine']} {row['solver']}, {int(row['parameter'])} solver sweeps"
    if row["parameter_name"] == "iterations":
        return f"{row['engine']} {row['solver']} {int(row['parameter'])} it."
    return f"{row['engine']} {row['solver']}"


def plot(rows, out):
    cost_kind = "CPU" if "cpu_cost_s_per_s" in rows[0] else "wall"
    panels = list(dict.fromkeys((r["scene"], r["metric"]) for r in rows))
    columns = min(3, len(panels))
    lines_of_panels = (len(panels) + columns - 1) // columns
    fig, axes = plt.subplots(lines_of_panels, columns, figsize=(5.2 * columns, 4.2 * lines_of_panels), squeeze=False)
    parameters = defaultdict(list)  # per series key: its parameter values, for the markers
    for r in rows:
        key = series_key(r)
        if r["parameter"] not in parameters[key]:
            parameters[key].append(r["parameter"])
    handles = {}
    for ax, (scene, metric) in zip(axes.flat, panels):
        no_answer = metric in NO_ANALYTIC_ANSWER
        series = defaultdict(list)
        for r in rows:
            if (r["scene"], r["metric"]) == (scene, metric):
                series[(series_key(r), r["parameter"])].append(r)
        for (key, parameter), points in series.items():
            points.sort(key=lambda r: -r["dt"])
            colour = COLOURS.get(key, "black")
            marker = MARKERS[parameters[key].index(parameter) % len(MARKERS)]
            xs = [p["cost"] for p in points]
            ys = [max(p["error"], 0.0 if no_answer else ERROR_FLOOR) for p in points]
            (line,) = ax.plot(xs, ys, color=colour, marker=marker, linewidth=1, markersize=5, label=label(points[0]))
            warned = [(x, y) for x, y, p in zip(xs, ys, points) if p["solver_warnings"] > 0]
            if warned:
                ax.scatter(*zip(*warned), s=90, facecolors="none", edgecolors="black", linewidths=1, zorder=3)
            handles.setdefault(label(points[0]), line)
        ax.set_xscale("log")
        ax.set_yscale("linear" if no_answer else "log")  # a time to rest may be 0
        ax.set_title(f"{scene}: {metric.replace('_', ' ')}")
        ax.set_xlabel(f"cost ({cost_kind} s per simulated s)")
        what = "no analytic answer: the figure itself" if no_answer else "error"
        ax.set_ylabel(f"{what} ({UNITS.get(metric, '')})")
        ax.grid(True, which="major", alpha=0.3)
    for ax in list(axes.flat)[len(panels):]:
        ax.axis("off")
    fig.legend(handles.values(), handles.keys(), loc="lower center", ncol=4, fontsize="small", frameon=False)
    fig.suptitle("polysim and ODE: error against analytic answers versus cost; circled: ODE solver warnings")
    fig.tight_layout(rect=(0, 0.04 + 0.025 * ((len(handles) + 3) // 4), 1, 0.97))
    for extension in ("png", "svg"):
        fig.savefig(f"{out}.{extension}", dpi=110)


def main(argv):
    if len(argv) != 3:
        print("usage: /usr/bin/python3 sim/plot_sweep.py SWEEP.csv OUT  (writes OUT.png and OUT.svg)", file=sys.stderr)
        return 2
    try:
        plot(read_rows(argv[1]), argv[2])
    except (OSError, ValueError) as e:
        print(f"plot_sweep: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
