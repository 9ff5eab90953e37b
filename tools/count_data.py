"""Reading the counted runs of tools/count_traffic.sh (imported by tools/count_report.py).

Per run directory D (D/run: sphfsi's output with -decomp_log_stats; D/mpi: tools/count_mpi.c's
rank<r>.csv; D/setup: the same run with -max_steps 0): the counts per rank and step are
(D/mpi - D/setup/mpi) / steps, so the set-up (first partition, migration, ghosts, ISPH's start) is
left out and the rebuilds, rebalancing and output of the time loop stay in."""
import csv, glob, json, math, os

PPE = ("PPE assembly", "PPE solve", "AMG setup", "AMG V-cycle")  # the last two: hypre's, inside PPE solve
TREE = ("allreduce", "bcast", "reduce", "scan", "allgather", "gather", "barrier", "ibarrier", "other_coll")  # latency ~ log2 P each


def mpi_counts(d):
    """rank -> stage -> {field: count} from D/rank*.csv."""
    out = {}
    for f in sorted(glob.glob(f"{d}/rank*.csv")):
        r = int(os.path.basename(f)[4:9])
        out[r] = {row["stage"]: {k: float(v) for k, v in row.items() if k != "stage"}
                  for row in csv.DictReader(line for line in open(f) if not line.startswith("#"))}
    return out


def loop_counts(d, nsteps):
    """rank -> group -> {field: per step}, groups: 'halo' (every stage but the PPE's and Output),
    'ppe' (PPE assembly + solve), 'output'."""
    full, setup = mpi_counts(f"{d}/mpi"), mpi_counts(f"{d}/setup/mpi")
    res = {}
    for r, st in full.items():
        g = {"halo": {}, "ppe": {}, "output": {}}
        for name, c in st.items():
            grp = "ppe" if name in PPE else "output" if name == "Output" else "halo"
            s0 = setup.get(r, {}).get(name, {})
            for k, v in c.items():
                g[grp][k] = g[grp].get(k, 0.0) + (v - s0.get(k, 0.0)) / max(nsteps, 1)
        res[r] = g
    return res


def stat(vals):
    return (max(vals), sum(vals) / len(vals)) if vals else (0.0, 0.0)


def partition_log(run, P, nsteps):
    """Time averages of partition_stats.csv (each rebuild's state weighted by the steps it lasted):
    ghosts max and per owned particle, neighbour ranks, work imbalance; and the PPE-row imbalance."""
    path = f"{run}/partition_stats.csv"
    if not os.path.exists(path):
        return {}
    rows = list(csv.DictReader(line for line in open(path) if not line.startswith("#")))
    rows = [{k: float(v) for k, v in r.items()} for r in rows]
    acc, wsum, imb_max = {}, 0.0, 0.0
    for i, r in enumerate(rows):
        nxt = rows[i + 1]["step"] if i + 1 < len(rows) else nsteps
        w = max(nxt - r["step"], 0.0)
        if i + 1 == len(rows) and nsteps == 0: w = 1.0
        mean_owned, mean_work = r["owned_sum"] / P, r["work_sum"] / P
        vals = dict(ghosts_max=r["ghosts_max"], ghosts_mean=r["ghosts_sum"] / P, owned_mean=mean_owned, owned_max=r["owned_max"],
                    ghosts_per_owned=r["ghosts_sum"] / max(r["owned_sum"], 1), ghosts_per_owned_max=r["ghosts_per_owned_max"],
                    nbr_max=r["nbr_ranks_max"], nbr_mean=r["nbr_ranks_sum"] / P, imbalance=r["work_max"] / max(mean_work, 1e-300))
        imb_max = max(imb_max, vals["imbalance"]) if w > 0 else imb_max
        for k, v in vals.items(): acc[k] = acc.get(k, 0.0) + w * v
        wsum += w
    res = {k: v / max(wsum, 1e-300) for k, v in acc.items()}
    res["imbalance_peak"] = imb_max
    res["rebuilds_per_step"] = sum(1 for r in rows[1:] if r["step"] < nsteps) / max(nsteps, 1)  # the first is the set-up's
    path = f"{run}/ppe_rows.csv"
    if os.path.exists(path):
        rr = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(line for line in open(path) if not line.startswith("#"))]
        rr = [r for r in rr if r["ppe_rows_sum"] > 0]
        if rr:
            res["ppe_imbalance"] = sum(r["ppe_rows_max"] * P / r["ppe_rows_sum"] for r in rr) / len(rr)
            res["ppe_rows_mean"] = sum(r["ppe_rows_sum"] for r in rr) / len(rr) / P
            res["ppe_rows_max"] = sum(r["ppe_rows_max"] for r in rr) / len(rr)
    return res


def levels(d):
    """BoomerAMG's levels and rows per level from tools/count_traffic.sh's levels.txt."""
    path = f"{d}/levels.txt"
    if not os.path.exists(path):
        return None
    n, rows = None, []
    for line in open(path):
        if "Num levels" in line: n = int(line.split("=")[1])
        else:
            p = line.split()
            if len(p) > 2 and p[0].isdigit(): rows.append(int(p[1]))
    return dict(levels=n, rows=rows)


def run_stats(d):
    """Everything counted about one run directory, or None if it is not complete."""
    try:
        s = json.load(open(f"{d}/run/summary.json"))
    except (OSError, ValueError):
        return None
    if s.get("status") != "completed" or not os.path.exists(f"{d}/setup/mpi"):
        return None
    P, n = s["ranks"], s["steps"]
    lc = loop_counts(d, n)
    st = dict(P=P, steps=n, particles=s["particles"], dim=s["dim"], fluid=s["fluid"], t_end=s["t_end"], dx=s["dx"],
              repartitions=s.get("repartitions", 0), its=s.get("ksp_its_mean"), its_max=s.get("ksp_its_max"))
    for grp in ("halo", "ppe"):
        for k in ("sends", "send_bytes", "rounds"):
            st[f"{grp}_{k}_max"], st[f"{grp}_{k}_mean"] = stat([lc[r][grp].get(k, 0.0) for r in lc])
        st[f"{grp}_tree"] = max(sum(lc[r][grp].get(k, 0.0) for k in TREE) for r in lc)
        st[f"{grp}_allreduce"] = max(lc[r][grp].get("allreduce", 0.0) for r in lc)
        st[f"{grp}_a2a"] = max(lc[r][grp].get("alltoall", 0.0) + lc[r][grp].get("alltoallv", 0.0) for r in lc)
        st[f"{grp}_a2a_pairs"] = max(lc[r][grp].get("a2a_pairs", 0.0) for r in lc)
        st[f"{grp}_a2av_dests_max"] = max(lc[r][grp].get("a2av_dests", 0.0) for r in lc)
        st[f"{grp}_coll_bytes_max"] = max(lc[r][grp].get("coll_bytes", 0.0) for r in lc)
        # what a rank puts on the network: point to point and its share of the collectives (below 9
        # ranks migration and ghosts go by MPI_Alltoallv, a collective)
        st[f"{grp}_bytes_max"], st[f"{grp}_bytes_mean"] = stat([lc[r][grp].get("send_bytes", 0.0) + lc[r][grp].get("coll_bytes", 0.0) for r in lc])
    st.update(partition_log(f"{d}/run", P, n))
    return st


def partition_row(path, P):
    """The row of bin/partition_model's CSV for P ranks (P = 1: the whole problem on one rank)."""
    if not os.path.exists(path):
        return None
    rows = [r for r in csv.DictReader(open(path)) if r.get("ranks") and r.get("case")]
    for r in rows:
        if int(r["ranks"]) == P:
            return {k: (float(v) if k != "case" else v) for k, v in r.items()}
    return None


def amg_levels(rows):
    """The scaling model's AMG levels for `rows` PPE rows in all: log4(rows / 10), at least 1."""
    return max(1, math.ceil(math.log(max(rows / 10, 2), 4)))
