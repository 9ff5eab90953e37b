#!/usr/bin/env python3
"""Model of the time per step against the number of ranks, from
  - the partition statistics of real cell graphs (bin/partition_model: partition_CASE.csv), and
  - the costs measured by tools/bench.sh on this machine (the 1-rank and 2-rank runs at ~400k
    particles: time per unit of work, PPE assembly / AMG set-up / V-cycle / CG cost per row,
    PPE iterations, halo messages and reductions per step).
  3D (SPHERIC Test 2): the same model on the 3D cell graph (partition_spheric_test2.csv), with the
    costs of tools/bench3d.sh's 1- and 2-rank runs at dx = 0.01 m (part "efficiency", 1.05 M
    particles, the partition's own size); the PPE rows are the partition's (water and the walls
    within reach of it), and ghost bytes scale with the halo as measured at 2 ranks.
Each case is modelled when its partition and its cost runs are in OUTDIR, and skipped otherwise.
    In 3D two more terms: the ghosts' handling on their rank (c_ghost, measured apart), and the
    compute slowed on many ranks by the factor the 2-rank run shows beyond the model (two ranks
    sharing one memory system; a full cluster node shares it too).
Usage: tools/scaling_model.py OUTDIR [--alpha 2e-6] [--alpha_ar 1.5e-6] [--beta 5e9] [--c_ghost 80e-9]
Writes OUTDIR/scaling_model.md and OUTDIR/scaling_model.png.

Per rank and step (P ranks, max over ranks from the partition):
  compute   c_work * work_max                         (WCSPH; ISPH outside the PPE)
            + (c_asm + c_setup + (its+1) c_vcycle + its c_matmult) * ppe_rows_max   (ISPH)
            (elastic gate: c_work * cost_max, each solid particle costing 4 + n_sub c_solid / c_work
             work units per fluid step, from the partition's cost column)
  exchange  with k neighbour ranks: alpha + k * o + bytes / beta (messages posted together)
  halo      n_msg exchanges per step, ghost bytes scaled from the 2-rank run by halo_max
  rebuilds  per rebuild (migration and ghosts), as the code does ("as is"): below 9 ranks MPI_Alltoall
            of counts (Bruck: alpha_ar log2 P) and MPI_Alltoallv, which Open MPI runs pairwise,
            alpha (P - 1) even for empty messages; from 9 ranks the sparse exchange (exchange.h):
            PETSc's two-sided set-up (an allreduce, alpha_ar log2 P) and two exchanges with the
            neighbour ranks (counts, records).  "MPI_Alltoallv": the earlier code, all-to-all
            at every rank count
  reductions n_red * alpha_ar * log2 P  (time step, checks; ISPH: 3 per CG iteration)
  AMG       levels L = log4(rows / 10): per V-cycle 4 exchanges per level (smoothing, residual,
            restriction, prolongation), per set-up 10 exchanges and 2 reductions per level, each
            with nbr_max neighbours (optimistic: coarse levels have more).
alpha: point-to-point latency, o: overhead per extra message, alpha_ar: latency of one allreduce
stage, beta: bandwidth per rank (assumptions for an InfiniBand cluster, stated in the output).

Counted inputs (issue 46; docs/scaling.md): model_counted() is the same model with what
tools/count_traffic.sh counted on 1..64 ranks in place of the assumptions that the counts contradict:
exchange rounds (alpha each) and messages (o each) instead of -log_view's messages taken as
exchanges; hypre's rounds, messages and collectives per solve instead of the V-cycle formula; the
collectives counted; the flow's halo and imbalance as factors on the partition's; the CG iterations'
growth with P.  tools/count_report.py evaluates it (costs_3d, fit_log2)."""
import csv, json, math, os, re, sys


def stages(path):
    """-log_view: stage -> (seconds, reductions, messages, message bytes) and event table by stage."""
    st, ev, cur = {}, {}, None
    for line in open(path):
        m = re.match(r"\s*\d+:\s+(.+?):\s+(\S+)\s+\S+%\s+\S+\s+\S+%\s+(\S+)\s+\S+%\s+(\S+)\s+\S+%\s+(\S+)\s+\S+%", line)
        if m and cur is None:
            st[m.group(1).strip()] = tuple(float(m.group(k)) for k in (2, 5, 3, 4))
        m = re.match(r"--- Event Stage \d+: (.+)", line)
        if m: cur = m.group(1).strip()
        m = re.match(r"(\w+)\s+(\d+)\s+\S+\s+(\S+)\s+\S+\s+\S+\s+\S+\s+(\S+)\s+(\S+)\s+(\S+)", line)
        if m and cur:
            ev.setdefault(cur, {})[m.group(1)] = dict(count=int(m.group(2)), time=float(m.group(3)), mess=float(m.group(4)), len=float(m.group(5)), red=float(m.group(6)))
    return st, ev


def kinds(log):
    """Particle counts by kind from the 'Particles:' line of a run's log."""
    for line in open(log):
        if line.startswith("Particles:"):
            return {k: int(v) for v, k in [(b, a) for a, b in re.findall(r"(fluid|wall|dummy|solid|clamp) (\d+)", line)]}
    return {}


def work_of(k):
    return 4 * (k.get("fluid", 0) + k.get("solid", 0) + k.get("clamp", 0)) + k.get("wall", 0) + k.get("dummy", 0)


# cost runs of each dimension: scheme -> run name of 1 rank and of 2 ranks (OUTDIR/NAME, OUTDIR/NAME.log)
COST_RUNS = {2: {s: (f"{s}_400k_np1", f"{s}_400k_np2") for s in ("wcsph", "isph")},
             3: {s: (f"s2_eff_{s}_np1", f"s2_eff_{s}_np2") for s in ("wcsph", "isph")}}


def load_costs(out, dim=2, ppe_rows=None):
    """Per-unit costs from the 1-rank runs (bench.sh: ~400k particles in 2D; bench3d.sh: 1.05 M in 3D)
    and message counts of the 2-rank runs.  ppe_rows: the PPE's rows in the measured run, when known
    (the 3D partition's); otherwise the fluid and half the walls."""
    c = {}
    for scheme, (n1, n2) in COST_RUNS[dim].items():
        d1, d2 = f"{out}/{n1}", f"{out}/{n2}"
        s1 = json.load(open(f"{d1}/summary.json"))
        st1, ev1 = stages(f"{d1}/log_view.txt")
        st2, ev2 = stages(f"{d2}/log_view.txt")
        s2 = json.load(open(f"{d2}/summary.json"))
        steps = s1["steps"]
        k = kinds(f"{d1}.log")
        w = work_of(k)
        tot = sum(v[0] for v in st1.values())
        r = dict(steps=steps, particles=s1["particles"], work=w, t_step=s1["wall_s"] / steps,
                 t_step2=s2["wall_s"] / s2["steps"], rows=None)
        # per rank and step on 2 ranks: messages outside the PPE solve, reductions, bytes per message
        msg = sum(v[2] for n, v in st2.items() if n != "PPE solve") / 2 / s2["steps"]
        byt = sum(v[2] * v[3] for n, v in st2.items() if n != "PPE solve") / 2 / s2["steps"]
        red = sum(v[1] for n, v in st2.items() if n != "PPE solve") / s2["steps"]
        r.update(n_msg=msg, bytes_step2=byt, n_red=red)
        if scheme == "isph":
            ppe_s = st1.get("PPE solve", (0,))[0]
            asm = st1.get("PPE assembly", (0,))[0]
            e = ev1.get("PPE solve", {})
            nv = e["PCApply"]["count"]
            its = s1["ksp_its_mean"]
            rows = ppe_rows or k.get("fluid", 0) + 0.5 * (k.get("wall", 0) + k.get("dummy", 0))  # walls within reach of fluid: about half in 2D
            r.update(its=its, rows=rows, c_nonppe=(tot - ppe_s - asm) / steps / w, c_asm=asm / steps / rows,
                     c_setup=e["PCSetUp"]["time"] / steps / rows, c_vcycle=e["PCApply"]["time"] / nv / rows,
                     c_matmult=e["MatMult"]["time"] / e["MatMult"]["count"] / rows, vcycles=nv / steps,
                     c_cg_other=(ppe_s - e["PCSetUp"]["time"] - e["PCApply"]["time"] - e["MatMult"]["time"]) / steps / rows)
            r["n_red"] = red  # outside the PPE; CG adds 3 per iteration
        else:
            r["c_work"] = r["t_step"] / w
        c[scheme] = r
    if dim == 3:
        return c
    # solid: the plate on 2 ranks, time per solid particle-step (a sub-step)
    try:
        sp = json.load(open(f"{out}/plate_np2/summary.json"))
        c["solid"] = dict(c_solid=2.0 / sp["particle_steps_per_s"])  # rank-seconds per particle-step
    except (OSError, KeyError):
        c["solid"] = dict(c_solid=0.0)
    return c


def measured_costs(c, dim):
    ci, cw = c["isph"], c["wcsph"]
    solid = f"solid sub-step {c['solid']['c_solid'] * 1e9:.0f} ns per solid particle." if "solid" in c else "no solid in 3D (not modelled)."
    return (f"Measured costs, {dim}D (1 rank, {cw['particles']} particles): WCSPH {cw['c_work'] * 1e9:.1f} ns per work unit per step "
              f"(fluid 4, wall 1; {cw['t_step'] * 1e3:.1f} ms/step); ISPH outside the PPE {ci['c_nonppe'] * 1e9:.1f} ns per work unit, "
              f"PPE per row: assembly {ci['c_asm'] * 1e9:.0f} ns, AMG set-up {ci['c_setup'] * 1e9:.0f} ns, V-cycle {ci['c_vcycle'] * 1e9:.0f} ns "
              f"({ci['vcycles']:.1f} per step), CG mat-vec {ci['c_matmult'] * 1e9:.0f} ns ({ci['its']:.2f} iterations); "
              f"halo: {cw['n_msg']:.1f} (WCSPH) / {ci['n_msg']:.1f} (ISPH) messages and {cw['n_red']:.1f} / {ci['n_red']:.1f} reductions per step outside the PPE; "
              f"{solid}"
              + "".join(f" {k.upper()} on 2 ranks: {100 * c[k]['eff2']:.0f} % efficient (measured), so compute on more than one rank is taken {c[k]['share']:.3f}x slower (ranks sharing a node's memory);" for k in ("wcsph", "isph") if "share" in c[k])
              + (f" a ghost costs {c['c_ghost'] * 1e9:.0f} ns per step on its rank." if "c_ghost" in c else "") + "\n")


def model(row, c, scheme, a, aar, beta, alltoallv, nsub=0, o=0.5e-6):
    P = int(row["ranks"])
    lg = math.log2(P) if P > 1 else 0
    nbr, halo = float(row["nbr_ranks_max"]), float(row["halo_max"])
    ex = a + o * nbr  # one neighbour exchange
    reb = aar * lg + (a * (P - 1) if alltoallv == "MPI_Alltoallv" or P < 9 else 2 * ex)
    if scheme == "wcsph":
        cw = c["wcsph"]
        # FSI: the partition's cost column counts each solid particle with its sub-steps (bench.sh)
        comp = cw["c_work"] * float(row["cost_max"] if nsub else row["work_max"])
        rebuilds = 1
        n_msg, n_red = cw["n_msg"], cw["n_red"]
        byt = cw["bytes_step2"] / max(cw.get("halo2", halo), 1) * halo if cw.get("halo2") else 0
        ppe = lat_ppe = 0.0
    else:
        ci = c["isph"]
        rows = float(row["ppe_rows_max"])
        comp = ci["c_nonppe"] * float(row["work_max"])
        ppe = (ci["c_asm"] + ci["c_setup"] + ci["vcycles"] * ci["c_vcycle"] + ci["its"] * ci["c_matmult"] + ci["c_cg_other"]) * rows
        L = max(1, math.ceil(math.log(max(float(row["ppe_rows_mean"]) * P / 10, 2), 4)))
        lat_ppe = (ci["vcycles"] * 4 * L * ex + ci["its"] * (ex + 3 * aar * lg)
                   + 10 * L * ex + 2 * L * aar * lg) if P > 1 else 0
        rebuilds = 2
        n_msg, n_red = ci["n_msg"], ci["n_red"]
        byt = ci["bytes_step2"] / max(ci.get("halo2", halo), 1) * halo if ci.get("halo2") else 0
    solid = 0.0  # in comp through the cost column
    if P == 1:
        return dict(comp=comp, ppe=ppe, solid=solid, comm=0.0, total=comp + ppe + solid)
    # handling of the ghosts on the rank (copy, binning, equation of state): c_ghost per ghost
    ghost = c.get("c_ghost", 0.0) * halo
    # ranks that share a node's memory bandwidth: compute slowed by the factor measured on 2 ranks
    comp, ppe = comp * c[scheme].get("share", 1.0), ppe * c[scheme].get("share", 1.0)
    comm = n_msg * ex + byt / beta + n_red * aar * lg + rebuilds * reb + lat_ppe + ghost
    return dict(comp=comp, ppe=ppe, solid=solid, comm=comm, total=comp + ppe + solid + comm, ppe_lat=lat_ppe)


def fit_log2(vals, P, lo=16):
    """A count at P ranks: measured when P was run, else the least-squares line in log2 P through the
    measured points from `lo` ranks on (the sparse exchanges, as at 1024), never below zero."""
    if P in vals: return vals[P]
    pts = [(math.log2(q), v) for q, v in vals.items() if q >= lo]
    if len(pts) < 2: return vals[max(vals)]
    n, sx, sy = len(pts), sum(p[0] for p in pts), sum(p[1] for p in pts)
    sxx, sxy = sum(p[0] ** 2 for p in pts), sum(p[0] * p[1] for p in pts)
    b = (n * sxy - sx * sy) / (n * sxx - sx ** 2)
    return max(0.0, (sy - b * sx) / n + b * math.log2(P))


def model_counted(row, c, scheme, k, a, o, aar, beta):
    """Time per step on the busiest rank with the counted inputs k (tools/count_report.py) instead of the
    assumed ones; row: the partition at P (bin/partition_model).  Corrections against model():
      work      the partition's work_max times the run's imbalance over the partition's (k['imb_ratio']);
      ghosts    halo_max times the run's ghosts over the partition's (k['halo_ratio']); bytes k['bytes_per_ghost'] each;
      exchanges every round of sends between two waits costs alpha, every further message o: counted rounds
                (k['rounds']) and messages (k['sends_per_round_nbr'] x rounds x the partition's neighbour ranks),
                rebuilds' alltoall(v) pairwise steps counted (k['a2a_pairs'], alpha each);
      reductions every counted tree collective (allreduce, bcast, scan, allgather, ibarrier, ...), alpha_ar log2 P;
      PPE       hypre's counted rounds, messages and collectives per solve, and the CG iterations k['its']."""
    P = int(row["ranks"])
    lg = math.log2(P) if P > 1 else 0
    nbr = float(row["nbr_ranks_max"])
    work = float(row["work_max"]) * (k.get("imb_ratio", 1.0) if P > 1 else 1.0)
    ghosts = float(row["halo_max"]) * k.get("halo_ratio", 1.0)
    share = c[scheme].get("share", 1.0) if P > 1 else 1.0
    if scheme == "wcsph":
        comp, ppe = c["wcsph"]["c_work"] * work * share, 0.0
    else:
        ci = c["isph"]
        its = k["its"]
        vc = ci["vcycles"] * (its + 1) / (ci["its"] + 1)  # V-cycles per step follow the iterations
        rows_max = float(row["ppe_rows_max"])
        comp = ci["c_nonppe"] * work * share
        ppe = (ci["c_asm"] + ci["c_setup"] + vc * ci["c_vcycle"] + its * ci["c_matmult"] + ci["c_cg_other"]) * rows_max * share
    if P == 1:
        return dict(comp=comp, ppe=ppe, comm=0.0, ppe_comm=0.0, total=comp + ppe)
    rounds, sends = k["rounds"], k["sends_per_round_nbr"] * k["rounds"] * nbr
    comm = (rounds * a + max(sends - rounds, 0) * o + k["bytes_per_ghost"] * ghosts / beta + k["tree"] * aar * lg
            + k["a2a_pairs"] * a + c.get("c_ghost", 0.0) * ghosts)
    ppe_comm = 0.0
    if scheme == "isph":
        pr, ps = k["ppe_rounds"], k["ppe_sends_per_round_nbr"] * k["ppe_rounds"] * nbr
        ppe_comm = pr * a + max(ps - pr, 0) * o + k["ppe_bytes"] / beta + k["ppe_tree"] * aar * lg
    return dict(comp=comp, ppe=ppe, comm=comm, ppe_comm=ppe_comm, total=comp + ppe + comm + ppe_comm)


def costs_3d(out, args, idle=None):
    """The 3D costs of tools/bench3d.sh's runs in OUT and the two 3D partitions, as main() sets them up
    (the 2-rank share factor and c_ghost): (costs, rows 1.05 M, rows 8.7 M).  idle: scheme -> particle-
    steps/s on 1 and 2 ranks of an idle machine, to which the loaded runs' costs are scaled."""
    rows1 = [r for r in csv.DictReader(open(f"{out}/partition_spheric_test2.csv")) if r.get("case") == "spheric_test2" and r.get("ranks")]
    rows9 = [r for r in csv.DictReader(open(f"{out}/partition_spheric_test2_9M.csv")) if r.get("case") == "spheric_test2" and r.get("ranks")]
    N = int(rows1[0]["particles"])
    n_meas = json.load(open(f"{out}/{COST_RUNS[3]['isph'][0]}/summary.json"))["particles"]
    c = load_costs(out, 3, 2 * float(rows1[0]["ppe_rows_mean"]) * n_meas / N)
    c["c_ghost"] = args["c_ghost"]
    for s, (ps1, ps2) in (idle or {}).items():
        # runs made while other jobs loaded the machine: every per-unit cost scaled so that the 1-rank
        # time per step is the idle machine's (particle-steps/s ps1 on 1 rank, ps2 on 2), the split
        # between the phases (-log_view) kept as measured
        f = (c[s]["particles"] / ps1) / c[s]["t_step"]
        for k in [k for k in c[s] if k.startswith("c_")]: c[s][k] *= f
        c[s]["loaded_by"] = 1 / f
        c[s]["t_step"], c[s]["t_step2"] = c[s]["particles"] / ps1, c[s]["particles"] / ps2
    for s in ("wcsph", "isph"):
        c[s]["halo2"] = float(rows1[0]["halo_max"]) * (c[s]["particles"] / N) ** (2 / 3)
        m2 = model(rows1[0], c, s, args["alpha"], args["alpha_ar"], args["beta"], "as is", 0, args["o"])
        c[s]["share"] = max(1.0, c[s]["t_step2"] / m2["total"])
        c[s]["eff2"] = c[s]["t_step"] / (2 * c[s]["t_step2"])
    return c, rows1, rows9


def one_rank(row):
    """The partition's first row (2 ranks) as the whole problem on one rank."""
    one = dict(row)
    for key in ("work", "cost", "ppe_rows", "solid"):
        one[f"{key}_max"] = str(float(row[f"{key}_mean"]) * 2)
    one.update(ranks="1", ppe_rows_mean=str(float(row["ppe_rows_mean"]) * 2), halo_max="0", nbr_ranks_max="0")
    return one


def main():
    out = sys.argv[1]
    # c_ghost: 3D WCSPH Taylor-Green cube on 1 rank, periodic images as ghosts, 25 and 50 across
    # (ghosts 1.3 and 0.56 per owned particle): 8.32 and 8.27 us per particle-step, so <= 80 ns a ghost
    args = dict(alpha=2e-6, o=0.5e-6, alpha_ar=1.5e-6, beta=5e9, nsub=8, c_ghost=80e-9)
    for k in range(2, len(sys.argv) - 1, 2):
        args[sys.argv[k].lstrip("-")] = float(sys.argv[k + 1])
    a, aar, beta = args["alpha"], args["alpha_ar"], args["beta"]
    sc = open(f"{out}/solid_cost.txt").read().strip() if os.path.exists(f"{out}/solid_cost.txt") else "?"
    tables, series, costs = [], {}, {}
    for case, schemes, dim in (("dam_break", ("wcsph", "isph"), 2), ("elastic_gate", ("wcsph",), 2), ("elastic_gate_solidw", ("wcsph",), 2),
                               ("spheric_test2", ("wcsph", "isph"), 3), ("spheric_test2_9M", ("wcsph", "isph"), 3)):
        path = f"{out}/partition_{case}.csv"
        if not os.path.exists(path): continue
        name = case.replace("_solidw", "").replace("_9M", "")
        rows = [r for r in csv.DictReader(open(path)) if r.get("case") == name and r.get("ranks")]  # METIS may print into stdout
        if not rows: continue
        N = int(rows[0]["particles"])
        if dim not in costs:
            try:  # 3D: the PPE rows of the measured run are the partition's, scaled to its size
                rows_measured = None
                if dim == 3:  # the costs were measured at the size of partition_spheric_test2.csv
                    if case != "spheric_test2": raise OSError(f"{out}/partition_spheric_test2.csv first")
                    n_meas = json.load(open(f"{out}/{COST_RUNS[3]['isph'][0]}/summary.json"))["particles"]
                    rows_measured = 2 * float(rows[0]["ppe_rows_mean"]) * n_meas / N
                costs[dim] = load_costs(out, dim, rows_measured)
            except (OSError, KeyError) as e:
                print(f"{case}: no cost runs for {dim}D in {out} ({e}): skipped", file=sys.stderr)
                costs[dim] = None
        if costs[dim] is None: continue
        c = costs[dim]
        one = dict(rows[0]); one.update(ranks="1", work_max=str(float(rows[0]["work_mean"]) * 2), cost_max=str(float(rows[0]["cost_mean"]) * 2), ppe_rows_max=str(float(rows[0]["ppe_rows_mean"]) * 2),
                                        ppe_rows_mean=str(float(rows[0]["ppe_rows_mean"]) * 2), solid_max=str(float(rows[0]["solid_mean"]) * 2), halo_max="0", nbr_ranks_max="0")
        # the 2-rank halo of the measured run scales the ghost bytes: halo ~ N^((D-1)/D) at 2 ranks
        for s in schemes:
            c[s]["halo2"] = float(rows[0]["halo_max"]) * (c[s]["particles"] / N) ** ((dim - 1) / dim)
        for s in schemes:
            nsub = args["nsub"] if case.startswith("elastic_gate") else 0
            if dim == 3 and "share" not in c[s]:
                # the 2-rank run's time beyond the model is the two ranks sharing one memory system
                # (not the ghosts: c_ghost is measured apart); every multi-rank compute pays it
                c["c_ghost"] = args["c_ghost"]
                m2 = model(rows[0], c, s, a, aar, beta, "as is", nsub, args["o"])
                c[s]["share"] = max(1.0, c[s]["t_step2"] / m2["total"])
                c[s]["eff2"] = c[s]["t_step"] / (2 * c[s]["t_step2"])
            m1 = model(one, c, s, a, aar, beta, "as is", nsub)
            t1 = m1["total"]
            for variant in ("as is", "MPI_Alltoallv"):
                pts = [(1, t1, 1.0, 0, 0, 1.0)]
                for r in rows:
                    m = model(r, c, s, a, aar, beta, variant, nsub, args["o"])
                    P = int(r["ranks"])
                    ppe_eff = m1["ppe"] / (P * (m["ppe"] + m.get("ppe_lat", 0))) if m1["ppe"] > 0 else 1.0
                    pts.append((P, m["total"], t1 / (P * m["total"]), m["comm"] / m["total"], m.get("ppe_lat", 0) / m["total"], ppe_eff))
                series[(case, s, variant)] = (N, pts)
        tables.append((case, N, rows, dim))
    md = []
    md.append(f"Scaling model (tools/scaling_model.py): METIS partitions of the real cell graphs (bin/partition_model, initial state) "
              f"and the per-particle costs measured on this machine (2D: tools/bench.sh, ~400k particles; 3D: tools/bench3d.sh, SPHERIC Test 2 at 1.05 M particles; 1 rank, message counts from 2 ranks). "
              f"Assumed network: point-to-point latency alpha = {a * 1e6:.1f} us + {args['o'] * 1e6:.1f} us per further neighbour of an exchange, allreduce {aar * 1e6:.1f} us per log2(P) stage, "
              f"{beta / 1e9:.0f} GB/s per rank; elastic gate: {args['nsub']:.0f} solid sub-steps per fluid step, a solid particle costing {sc} work units per fluid step "
              f"(4 + 8 c_solid / c_work, c_solid from the oscillating plate on 2 ranks, an upper bound: its 1040 particles carry the per-step overheads).\n")
    for dim, c in costs.items():
        if c: md.append(measured_costs(c, dim))
    for case, N, rows, dim in tables:
        title = {"elastic_gate": "elastic_gate (solid particles balanced as METIS's second constraint, as the code does by default)",
                 "elastic_gate_solidw": f"elastic_gate, solid and clamp particles weighted {sc} (their cost with the sub-steps) in the partition instead of 4"}.get(case, case)
        md.append(f"\n**{title}**, {N} particles, {rows[0]['cells']} cells, solid particles on the busiest rank at 2 / 64 ranks: "
                  f"{rows[0]['solid_max']} / {rows[min(5, len(rows) - 1)]['solid_max']}\n" if case.startswith("elastic") else f"\n**{title}**, {N} particles, {rows[0]['cells']} cells\n")
        hdr = "| ranks | particles/rank | work imbalance | cost imbalance (solid sub-steps counted) | PPE-row imbalance | halo/owned (max) | neighbour ranks max | cut edges |"
        sep = "|---|---|---|---|---|---|---|---|"
        keys = [k for k in series if k[0] == case]
        for k in keys:
            hdr += f" {k[1].upper()} {'' if k[2] == 'as is' else '(MPI_Alltoallv) '}ms/step (eff.) |"
            sep += "---|"
        md.append(hdr); md.append(sep)
        for i, r in enumerate(rows):
            line = (f"| {r['ranks']} | {N / int(r['ranks']):.0f} | {float(r['work_imbalance']):.3f} | {float(r['cost_max']) / float(r['cost_mean']):.3f} | {float(r['ppe_imbalance']):.3f} | "
                    f"{float(r['halo_max']) / float(r['owned_max']):.2f} | {r['nbr_ranks_max']} | {r['cut_edges']} |")
            for k in keys:
                P, t, e, _, _, _ = series[k][1][i + 1]
                line += f" {t * 1e3:.3g} ({100 * e:.0f} %) |"
            md.append(line)
    # where it stops scaling
    md.append("")
    for k, (N, pts) in series.items():
        last = max((p for p in pts if p[2] >= 0.5), key=lambda p: p[0])
        md.append(f"- {k[0]} {k[1].upper()} ({k[2]}): efficiency >= 50 % up to {last[0]} ranks ({N / last[0]:.0f} particles per rank); "
                  f"at 1024 ranks {100 * pts[-1][2]:.0f} %, communication {100 * pts[-1][3]:.0f} % of the step"
                  + (f", PPE latency {100 * pts[-1][4]:.0f} %" if k[1] == "isph" else ""))
        if k[1] == "isph" and k[2] == "as is":
            near = min(pts[1:], key=lambda p: abs(N / p[0] - 16300))  # Guo et al.: 100M particles on 6144 partitions
            md.append(f"  - at {N / near[0]:.0f} particles per rank ({near[0]} ranks; Guo et al. 2018 ran ~16k per partition): "
                      f"overall {100 * near[2]:.0f} %, PPE alone {100 * near[5]:.0f} % (Guo et al.: > 43 % overall, PPE > 90 %)")
    open(f"{out}/scaling_model.md", "w").write("\n".join(md) + "\n")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(1, 2, figsize=(11, 5.6))
        colors = {("dam_break", "wcsph"): "C0", ("dam_break", "isph"): "C1", ("elastic_gate", "wcsph"): "C2", ("elastic_gate_solidw", "wcsph"): "C3",
                  ("spheric_test2", "wcsph"): "C4", ("spheric_test2", "isph"): "C5", ("spheric_test2_9M", "wcsph"): "C6", ("spheric_test2_9M", "isph"): "C7"}
        for k, (N, pts) in series.items():
            P = [p[0] for p in pts]; t = [p[1] * 1e3 for p in pts]; e = [100 * p[2] for p in pts]
            ls = "-" if k[2] == "as is" else "--"
            name = k[0].replace("spheric_test2_9M", "3D SPHERIC Test 2 (8.7 M)").replace("spheric_test2", "3D SPHERIC Test 2 (1.05 M)").replace("elastic_gate_solidw", "elastic gate (solids weighted by their cost)").replace("elastic_gate", "elastic gate (solids a second constraint, as now)").replace("_", " ")
            lab = f"{name} {k[1].upper()}{'' if k[2] == 'as is' else ', all-to-all exchanges (before)'}"
            ax[0].loglog(P, t, ls, marker="o", ms=3, color=colors[(k[0], k[1])], label=lab)
            if k[2] == "as is": ax[0].loglog(P, [t[0] / p for p in P], ":", color=colors[(k[0], k[1])], lw=0.8)
            ax[1].semilogx(P, e, ls, marker="o", ms=3, color=colors[(k[0], k[1])], label=lab)
        ax[0].set_xlabel("ranks"); ax[0].set_ylabel("modelled time per step (ms)"); ax[0].set_title("time per step (dotted: ideal)")
        ax[1].axhline(43, color="grey", lw=0.8); ax[1].text(1.2, 45, "Guo et al. 2018: 43 % overall at 6144 partitions", fontsize=7, color="grey")
        ax[1].axhline(90, color="grey", lw=0.8, ls="--"); ax[1].text(1.2, 92, "Guo et al. 2018: PPE > 90 %", fontsize=7, color="grey")
        ax[1].set_xlabel("ranks"); ax[1].set_ylabel("parallel efficiency (%)"); ax[1].set_ylim(0, 105); ax[1].set_title("strong scaling at ~1M particles (3D also 8.7M)")
        h, l = ax[1].get_legend_handles_labels()
        fig.legend(h, l, fontsize=7, loc="lower center", ncol=2)
        for x in ax: x.grid(True, which="both", alpha=0.3)
        fig.suptitle(f"sphfsi scaling model: METIS partitions of the real cell graphs + costs measured on this machine "
                     f"(alpha {a * 1e6:.0f} us, allreduce {aar * 1e6:.1f} us/stage)", fontsize=8)
        fig.tight_layout(rect=(0, 0.17, 1, 1))
        fig.savefig(f"{out}/scaling_model.png", dpi=110)
    except ImportError:
        print("matplotlib missing: no PNG", file=sys.stderr)
    print("\n".join(md))


if __name__ == "__main__":
    main()
