#!/usr/bin/python3
"""Charts from anisodwr output tables (Debian's python3-matplotlib; run with /usr/bin/python3).

Every chart reads only files a run writes, so any run can be charted:
  loops.csv / probes.csv (study.mode = dwr), convergence.csv (study.mode = convergence),
  loop-NNNN.cells.csv (with output.vtu_loops > 0), cut_<line>_loop-NNNN.csv (hemker).

Usage:
  charts.py work-precision OUT.png RUN[=LABEL] ...   J error against cumulative wall time and N_tot
  charts.py goal-values OUT.png RUN[=LABEL] ...      J_i per loop against N_tot (scenes without exact J)
  charts.py goal-errors OUT.png RUN[=LABEL] ...      per goal: J_i against N_space with the reference
                                                     band (goal.reference or the exact value), and
                                                     |eta_i| (own adjoint) against |J_i error|
  charts.py history OUT.png RUN                      |eta_h,x|, |eta_h,y|, |eta_tau|, |J error|, I_eff per loop
  charts.py convergence OUT.png CSV[=LABEL] ...      errors against h or tau from convergence.csv tables
  charts.py mesh OUT.png RUN LOOP [FIELD] [x0 x1 y0 y1]   (LOOP -1: the last)
                                                     cells of a loop coloured by FIELD (aspect_ratio,
                                                     eta_hx, eta_hy, eta_tau, u); optional zoom window
  charts.py cutlines OUT.png RUN LOOP[,LOOP...]      u along the cut lines of hemker
  charts.py compare-cut OUT.png LINE LOOP RUN[=LABEL] ...
                                                     one cut line of several runs at one loop (-1: last)
  charts.py all OUTDIR RUN ...                       history, mesh (last and middle loop), cut lines of
                                                     each run, and work-precision of all runs
"""
import csv
import glob
import math
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from matplotlib.colors import LogNorm, Normalize  # noqa: E402


def read(path):
    with open(path) as f:
        return [{k: (float(v) if v not in ("", None) else math.nan) for k, v in r.items()}
                for r in csv.DictReader(f)]


def split_label(arg):
    path, _, label = arg.partition("=")
    return path, (label or os.path.basename(os.path.normpath(path)))


def finish(fig, ax, out, xlabel, ylabel, legend_size=8, dpi=110):
    """Labels, grid and legend of a single-axes chart, then writes it."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=legend_size)
    fig.tight_layout()
    fig.savefig(out, dpi=dpi)


def cumulative_time(rows):
    total, out = 0.0, []
    for r in rows:
        total += sum(r.get(k, 0.0) or 0.0 for k in ("t_primal", "t_adjoint", "t_estimate", "t_refine"))
        out.append(total)
    return out


def positive(xs, ys):
    pairs = [(x, y) for x, y in zip(xs, ys) if y == y and y > 0 and x == x and x > 0]
    return [p[0] for p in pairs], [p[1] for p in pairs]


def work_precision(out, runs):
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    for arg in runs:
        path, label = split_label(arg)
        rows = read(os.path.join(path, "loops.csv"))
        err = [r["J_error"] for r in rows]
        for a, x in ((ax[0], cumulative_time(rows)), (ax[1], [r["N_tot"] for r in rows])):
            xs, ys = positive(x, err)
            a.loglog(xs, ys, "o-", ms=3, label=label)
    ax[0].set_xlabel("cumulative wall time [s]")
    ax[1].set_xlabel("$N_{tot}$ (space-time DoFs)")
    for a in ax:
        a.set_ylabel("$|J(u) - J(u_{\\tau h})|$")
        a.grid(True, which="both", alpha=0.3)
        a.legend(fontsize=8)
    fig.suptitle("work-precision")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def goal_values(out, runs):
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for arg in runs:
        path, label = split_label(arg)
        rows = read(os.path.join(path, "probes.csv"))
        for key in [k for k in rows[0] if k.startswith("J_")]:
            ax.semilogx([r["N_tot"] for r in rows], [r[key] for r in rows], "o-", ms=3,
                        label=f"{label}: {key[2:]}")
    finish(fig, ax, out, "$N_{tot}$", "$J_i(u_{\\tau h})$")


def goal_errors(out, runs):
    """Per goal one row of two panels: J_i(u_h) with the reference (and its uncertainty band
    from summary.json), and |eta_i| (per_goal_estimates) beside |err_i| against N_space."""
    import json
    first = runs[0].split("=")[0]
    goals = json.load(open(os.path.join(first, "summary.json")))["goals"]
    fig, ax = plt.subplots(len(goals), 2, figsize=(11, 3.6 * len(goals)), squeeze=False)
    for arg in runs:
        path, label = split_label(arg)
        summary = json.load(open(os.path.join(path, "summary.json")))
        unc = summary.get("reference_uncertainty", [0.0] * len(goals))
        loops = read(os.path.join(path, "loops.csv"))
        probes = read(os.path.join(path, "probes.csv"))
        n = [r["N_space"] for r in loops]
        for g, name in enumerate(goals):
            line = ax[g][0].semilogx(n, [p["J_" + name] for p in probes], "o-", ms=3,
                                     label=label)[0]
            ref = summary["loops"][0]["goals"][name]["J_exact"]
            if ref is not None and ref == ref:
                ax[g][0].axhline(ref, color=line.get_color(), lw=0.8, ls="--")
                if unc and unc[g] > 0:
                    ax[g][0].axhspan(ref - unc[g], ref + unc[g], color=line.get_color(),
                                     alpha=0.15)
            for key, style, lab in (("err_", "o-", "|error|"), ("eta_", "s--", "|eta|")):
                xs, ys = positive(n, [abs(r.get(key + name, math.nan)) for r in loops])
                if ys:
                    ax[g][1].loglog(xs, ys, style, ms=3, color=line.get_color(),
                                    label=f"{label}: {lab}")
            ax[g][0].set_title(name, fontsize=9)
            ax[g][1].set_title(name + ": own estimate against error", fontsize=9)
    for g in range(len(goals)):
        for a in ax[g]:
            a.set_xlabel("$N_{space}$")
            a.grid(True, which="both", alpha=0.3)
            a.legend(fontsize=7)
        ax[g][0].set_ylabel("$J_i(u_{\\tau h})$")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def history(out, run):
    rows = read(os.path.join(run, "loops.csv"))
    loops = [r["loop"] for r in rows]
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    for key, lab in (("eta_hx", "$|\\eta_{h,x}|$"), ("eta_hy", "$|\\eta_{h,y}|$"),
                     ("eta_tau", "$|\\eta_\\tau|$"), ("J_error", "$|J(u)-J(u_{\\tau h})|$")):
        xs, ys = positive(loops, [abs(r[key]) for r in rows])
        if ys:
            ax[0].semilogy(xs, ys, "o-", ms=3, label=lab)
    ax[0].set_xlabel("DWR loop")
    ax[0].legend(fontsize=8)
    ax[0].grid(True, which="both", alpha=0.3)
    ie = [(l, r["I_eff"]) for l, r in zip(loops, rows) if r["I_eff"] == r["I_eff"]]
    if ie:
        ax[1].plot([p[0] for p in ie], [p[1] for p in ie], "o-", ms=3, label="$I_{eff}$")
        ax[1].axhspan(0.8, 1.25, color="g", alpha=0.1)
        ax[1].set_ylabel("$I_{eff}$")
    else:
        ax[1].semilogy(loops, [r["ar_max"] for r in rows], "o-", ms=3, label="max aspect ratio")
    ax[1].set_xlabel("DWR loop")
    ax[1].legend(fontsize=8)
    ax[1].grid(True, alpha=0.3)
    fig.suptitle(f"estimator history: {run}")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def convergence(out, tables):
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for arg in tables:
        path, label = split_label(arg)
        rows = read(path)
        by_h = len({r["h"] for r in rows}) > 1
        x = [r["h"] if by_h else r["tau"] for r in rows]
        for key in ("err_L2L2", "err_L2_T"):
            xs, ys = positive(x, [r[key] for r in rows])
            if ys:
                order = rows[-1].get("order_" + key[4:], math.nan)
                ax.loglog(xs, ys, "o-", ms=3, label=f"{label} {key} (order {order:.2f})")
                break
    finish(fig, ax, out, "h or $\\tau$", "error", legend_size=7)


def loop_files(run, pattern):
    files = sorted(glob.glob(os.path.join(run, pattern)))
    return {int(re.search(r"(\d{4})", os.path.basename(f)).group(1)): f for f in files}


def pick(files, loop):
    """The file of a loop; loop -1 is the last one."""
    return files[max(files)] if int(loop) < 0 else files[int(loop)]


def mesh(out, run, loop, field="aspect_ratio", window=None):
    files = loop_files(run, "loop-*.cells.csv")
    loop = max(files) if int(loop) < 0 else int(loop)
    rows = read(files[loop])
    polys = [[(r[f"x{k}"], r[f"y{k}"]) for k in range(4)] for r in rows]
    if field == "u":
        values = [sum(r[f"u{k}"] for k in range(4)) / 4 for r in rows]
        norm = Normalize(min(values), max(values))
    else:
        values = [abs(r[field]) for r in rows]
        pos = [v for v in values if v > 0]
        norm = LogNorm(max(min(pos), max(pos) * 1e-8), max(pos)) if pos else Normalize()
        values = [max(v, norm.vmin) for v in values]
    fig, ax = plt.subplots(figsize=(8, 4.8))
    # cell edges hide the colours of large meshes: drawn only below 20000 cells
    pc = PolyCollection(polys, array=values, cmap="viridis", norm=norm,
                        edgecolors="k" if len(polys) < 20000 else "face",
                        linewidths=0.1 if len(polys) > 2000 else 0.3, rasterized=True)
    ax.add_collection(pc)
    ax.autoscale_view()
    ax.set_aspect("equal")
    if window:
        ax.set_xlim(window[0], window[1])
        ax.set_ylim(window[2], window[3])
    fig.colorbar(pc, ax=ax, label=field, shrink=0.8)
    ax.set_title(f"{os.path.basename(os.path.normpath(run))}: loop {int(loop)}, {len(polys)} cells, "
                 f"coloured by {field}")
    fig.tight_layout()
    fig.savefig(out, dpi=130)


def cutlines(out, run, loops):
    names = sorted({re.match(r"cut_(.+)_loop", os.path.basename(f)).group(1)
                    for f in glob.glob(os.path.join(run, "cut_*_loop-*.csv"))})
    if not names:
        raise SystemExit(f"charts.py: no cut_*_loop-*.csv in {run}")
    fig, ax = plt.subplots(1, len(names), figsize=(5.5 * len(names), 4.2), squeeze=False)
    for a, name in zip(ax[0], names):
        files = loop_files(run, f"cut_{name}_loop-*.csv")
        for loop in loops:
            loop = max(files) if int(loop) < 0 else int(loop)
            rows = read(files[loop])
            a.plot([r["s"] for r in rows], [r["u"] for r in rows], "-", lw=1, label=f"loop {int(loop)}")
        a.set_xlabel("s along the line")
        a.set_ylabel("$u_h(T)$")
        a.set_title(f"cut line {name}")
        a.grid(True, alpha=0.3)
        a.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def compare_cut(out, line, loop, runs):
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for arg in runs:
        run, label = split_label(arg)
        files = loop_files(run, f"cut_{line}_loop-*.csv")
        chosen = max(files) if int(loop) < 0 else int(loop)
        rows = read(pick(files, chosen))
        ax.plot([r["s"] for r in rows], [r["u"] for r in rows], "-", lw=1, label=f"{label} (loop {chosen})")
    ax.axhline(0, color="k", lw=0.5)
    ax.axhline(1, color="k", lw=0.5)
    finish(fig, ax, out, f"s along cut line {line}", "$u_h(T)$")


def all_charts(outdir, runs):
    os.makedirs(outdir, exist_ok=True)
    written = []
    exact = []
    for arg in runs:
        run, label = split_label(arg)
        name = label.replace(" ", "_")
        history(os.path.join(outdir, f"{name}_history.png"), run)
        written.append(f"{name}_history.png")
        cells = sorted(loop_files(run, "loop-*.cells.csv"))
        for loop in {cells[len(cells) // 2], cells[-1]} if cells else ():
            mesh(os.path.join(outdir, f"{name}_mesh_{loop:04d}.png"), run, loop)
            written.append(f"{name}_mesh_{loop:04d}.png")
        cuts = sorted(loop_files(run, "cut_*_loop-*.csv"))
        if cuts:
            cutlines(os.path.join(outdir, f"{name}_cutlines.png"), run, [cuts[0], cuts[len(cuts) // 2], cuts[-1]])
            written.append(f"{name}_cutlines.png")
        rows = read(os.path.join(run, "loops.csv"))
        if any(r["J_error"] == r["J_error"] for r in rows):
            exact.append(arg)
    if exact:
        work_precision(os.path.join(outdir, "work_precision.png"), exact)
        written.append("work_precision.png")
    print("\n".join(os.path.join(outdir, w) for w in written))


def main(argv):
    if len(argv) < 3:
        raise SystemExit(__doc__)
    cmd, out, rest = argv[1], argv[2], argv[3:]
    if cmd == "work-precision":
        work_precision(out, rest)
    elif cmd == "goal-values":
        goal_values(out, rest)
    elif cmd == "goal-errors":
        goal_errors(out, rest)
    elif cmd == "history":
        history(out, rest[0])
    elif cmd == "convergence":
        convergence(out, rest)
    elif cmd == "mesh":
        window = [float(v) for v in rest[3:7]] if len(rest) >= 7 else None
        mesh(out, rest[0], rest[1], rest[2] if len(rest) > 2 else "aspect_ratio", window)
    elif cmd == "cutlines":
        cutlines(out, rest[0], rest[1].split(","))
    elif cmd == "compare-cut":
        compare_cut(out, rest[0], rest[1], rest[2:])
    elif cmd == "all":
        all_charts(out, rest)
    else:
        raise SystemExit(f"charts.py: unknown chart '{cmd}'\n{__doc__}")


if __name__ == "__main__":
    main(sys.argv)
