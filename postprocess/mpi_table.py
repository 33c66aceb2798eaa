#!/usr/bin/python3
"""Table and chart of scripts/bench_mpi.sh.

Usage: mpi_table.py OUT [CHART.png]
OUT holds one directory per config (hemker, moving_hump_paper, ...), each with one
directory per variant (umfpack, umfpack_1thread, mumps, mpi2, ...) holding a run's
loops.csv (further rounds of a variant in VARIANT.2, VARIANT.3, ...; each loop's row
is the variant's fastest round). Prints, per config, whether every variant (every
round) has the serial run's N_space, N_t and J (1e-8 relative) on every loop, and
Markdown tables of the last loop and of the
loop four before it (two sizes): phase times (s), the loop's sum, the largest peak
memory over the ranks up to that loop (MB) and the speed-up against the serial default
(umfpack) and against one single-threaded process. With CHART, draws the last loop's
phase times as stacked bars.
"""
import csv
import os
import sys

PHASES = ["t_primal", "t_adjoint", "t_estimate", "t_refine"]
ORDER = ["umfpack_1thread", "umfpack", "mumps", "mpi2", "mpi2_umfpack", "mpi4"]
LABEL = {
    "umfpack_1thread": "1 process, 1 thread, UMFPACK",
    "umfpack": "1 process, 2 threads, UMFPACK",
    "mumps": "1 process, 2 threads, MUMPS",
    "mpi2": "2 ranks x 1 thread, MUMPS",
    "mpi2_umfpack": "2 ranks x 1 thread, UMFPACK on each rank",
    "mpi4": "4 ranks, MUMPS",
}


def loop_time(row):
    return sum(float(row[p]) for p in PHASES)


def load(path):
    return list(csv.DictReader(open(path)))


def main():
    out = sys.argv[1]
    chart = sys.argv[2] if len(sys.argv) > 2 else None
    bars = []
    for config in sorted(os.listdir(out)):
        cdir = os.path.join(out, config)
        # all rounds of a variant (v, v.2, v.3, ...): the table uses the fastest round
        # of each loop
        def is_round(d, v):
            return d == v or (d.startswith(v + ".") and d[len(v) + 1:].isdigit())

        rounds = {v: [load(os.path.join(cdir, d, "loops.csv")) for d in sorted(os.listdir(cdir))
                      if is_round(d, v) and os.path.exists(os.path.join(cdir, d, "loops.csv"))]
                  for v in ORDER}
        rounds = {v: r for v, r in rounds.items() if r}
        runs = {v: r[0] for v, r in rounds.items()}
        if "umfpack" not in runs:
            continue
        ref = runs["umfpack"]
        for v, r in rounds.items():
            for k, rows in enumerate(r):
                same = len(rows) == len(ref) and all(
                    x["N_space"] == y["N_space"] and x["N_t"] == y["N_t"]
                    and abs(float(x["J"]) - float(y["J"])) <= 1e-8 * max(1.0, abs(float(x["J"])))
                    for x, y in zip(ref, rows))
                if v != "umfpack" or k > 0:
                    print(f"{config}, {v} round {k + 1}: same N_space, N_t, J as umfpack round 1 "
                          f"on all {len(ref)} loops: {same}")
        # two sizes: the last loop and the loop four before it (N_tot about 5x smaller)
        for k in ([len(ref) - 5] if len(ref) > 5 else []) + [len(ref) - 1]:
            at = ref[k]
            print(f"\n{config}, loop {at['loop']}: N_space {at['N_space']}, N_t {at['N_t']}, "
                  f"N_tot {at['N_tot']}\n")
            print("| variant | primal s | adjoint s | estimate s | refine s | loop s "
                  "| peak MB (largest rank) | speed-up | against 1 thread |")
            print("|---|---|---|---|---|---|---|---|---|")
            def fastest(v):  # the variant's fastest round of loop k
                return min((r[k] for r in rounds[v] if len(r) > k), key=loop_time)
            base = loop_time(fastest("umfpack"))
            base1 = loop_time(fastest("umfpack_1thread" if "umfpack_1thread" in rounds
                                      else "umfpack"))
            for v in ORDER:
                if v not in runs or len(runs[v]) <= k:
                    continue
                row = fastest(v)
                t = [float(row[p]) for p in PHASES]
                print(f"| {LABEL[v]} | " + " | ".join(f"{x:.2f}" for x in t) +
                      f" | {sum(t):.2f} | {float(row['mem_peak']):.0f} | {base / sum(t):.2f}"
                      f" | {base1 / sum(t):.2f} |")
                if k == len(ref) - 1:
                    bars.append((f"{config}\n{v}", t))
        print()
    if chart and bars:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(1.1 * len(bars) + 2, 4))
        bottom = [0.0] * len(bars)
        for i, p in enumerate(PHASES):
            h = [b[1][i] for b in bars]
            ax.bar(range(len(bars)), h, bottom=bottom, label=p[2:])
            bottom = [x + y for x, y in zip(bottom, h)]
        ax.set_ylim(0, 1.08 * max(bottom))
        ax.set_xticks(range(len(bars)))
        ax.set_xticklabels([b[0] for b in bars], fontsize=7)
        ax.set_ylabel("wall time of the last DWR loop [s]")
        ax.set_title("Serial against 2 MPI ranks (2 cores)")
        ax.legend(loc="upper left", fontsize=8, framealpha=0.9)
        fig.tight_layout()
        fig.savefig(chart, dpi=110)
        print(f"chart: {chart}")


main()
