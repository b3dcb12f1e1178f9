#!/usr/bin/env python3
"""The Python side of the peer comparison (not part of the test suite).

Subcommands:
  gen     write the windowed data file both sides read, and the Gaussian width β
  run     time the Python peers on that file, print one JSON object per method
  report  read both sides' JSON lines, print medians, ratios, OLS pick agreement

Peers (each timed from in-memory arrays to fitted weights, as `rbf fit` times its
`fit_seconds`; data loading is not timed on either side):
  cgs     the numpy OLS a careful engineer writes (the reference peer): Chen, Cowan &
          Grant (1991) by classical Gram-Schmidt with ONE matrix-vector product per
          pick. The kernel matrix P is never modified; running per-candidate sums keep
          the remaining energy ‖p‖² − Σ(qᵢᵀp)² and the projection pᵀr of every
          candidate: per pick, c = q_kᵀP (one gemv), energy −= c², pᵀr −= g_k c. The
          winner is orthogonalised explicitly (CGS2) against the basis. Bias forced
          first, weights by numpy lstsq, as below. Its Gaussian matrix comes from one
          matrix product (numpy's fastest route, `gaussian`): ‖a‖² + ‖c‖² − 2·A·Cᵀ
          with `A @ C.T` (OpenBLAS dgemm, threaded), clipped at 0, then `np.exp`;
  cgs_cdist  the same OLS with the Gaussian matrix from scipy's `cdist` (one thread,
          one distance at a time: `gaussian_cdist`), the reference before issue 37;
  ols     a straightforward numpy implementation of Chen, Cowan & Grant (1991): the
          Gaussian kernel matrix of all training vectors as candidates, the bias forced
          first, then per pick the error-reduction ratio of every candidate from its
          deflated column and the candidates deflated against the new column (the
          classic per-pick deflation, modified Gram-Schmidt order), then the output
          weights by numpy lstsq on [1 | picked columns];
  kmeans  scikit-learn KMeans (k-means++, n_init=1, the same K) + numpy lstsq;
  rbfi    scipy RBFInterpolator, Gaussian kernel exp(-(eps r)^2) with eps = 1/β (the
          library's exp(-r²/β²)), degree 0 (a constant, the library's bias), the same
          smoothing as the library's ridge; fit and predict;
  matvec  one plain matrix-vector product vᵀP over the N×N kernel matrix (numpy gemv):
          the memory-bandwidth bound of an OLS pick.
"""

import argparse
import csv
import json
import os
import statistics
import sys
import time

import numpy as np
from scipy.interpolate import RBFInterpolator
from scipy.spatial.distance import cdist, pdist
from sklearn.cluster import KMeans
from threadpoolctl import threadpool_info, threadpool_limits

DIM = 50
# The relative difference up to which two validation RMSEs of the same picks are equal:
# both sides solve the same least-squares problem (ours by QR, numpy's lstsq by SVD) in
# f64, on a design matrix whose condition number is below 1e4 here.
RMSE_EQUAL = 1e-9


# ---------------------------------------------------------------- data

def windowed(n, seed):
    """Windows of a resonant low-pass filtered white-noise signal and a nonlinear
    target: the recipe of crates/rbf/benches/centre_selection.rs (its own random numbers)."""
    rng = np.random.default_rng(seed)
    burn = 200
    length = n + DIM + burn
    u = rng.standard_normal(length)
    s = np.zeros(length)
    for k in range(2, length):
        s[k] = 1.6 * s[k - 1] - 0.8 * s[k - 2] + u[k]
    s = s[burn:]
    s = s / np.sqrt(np.mean(s * s))
    t = np.arange(n) + DIM - 1
    x = np.stack([s[t - j] for j in range(DIM)], axis=1)
    e = rng.standard_normal(n)
    y = np.sin(1.5 * s[t]) * np.exp(-s[t - 10] ** 2 / 2) + 0.3 * s[t - 3] * s[t - 7] + 0.05 * e
    return x, y


def cmd_gen(a):
    x, y = windowed(a.train + a.val, a.seed)
    roles = np.array(["train"] * a.train + ["val"] * a.val)
    with open(a.out, "w") as f:
        f.write(",".join([f"x{j}" for j in range(DIM)] + ["y", "split"]) + "\n")
        for i in range(len(y)):
            f.write(",".join(repr(float(v)) for v in x[i]) + f",{float(y[i])!r},{roles[i]}\n")
    # β = the median pairwise distance of (up to 2000 of) the training windows: both
    # sides get this fixed width, so only the algorithms differ.
    m = min(a.train, 2000)
    beta = float(np.median(pdist(x[:m])))
    print(json.dumps({"file": a.out, "n_train": a.train, "n_val": a.val, "dim": DIM, "beta": beta}))


def load(path):
    with open(path) as f:
        header = next(csv.reader(f))
    xcols = [i for i, h in enumerate(header) if h.startswith("x")]
    ycol = header.index("y")
    scol = header.index("split")
    num = np.loadtxt(path, delimiter=",", skiprows=1, usecols=xcols + [ycol])
    roles = np.loadtxt(path, delimiter=",", skiprows=1, usecols=[scol], dtype=str)
    train = np.flatnonzero(roles == "train")
    val = np.flatnonzero(roles == "val")
    x, y = num[:, :-1], num[:, -1]
    return x[train], y[train], x[val], y[val], train


# ---------------------------------------------------------------- peers

def gaussian(a, c, beta):
    """exp(−‖a_i − c_j‖²/β²) by numpy's fastest route: the squared distances
    ‖a‖² + ‖c‖² − 2·A·Cᵀ from one matrix product (`A @ C.T`, OpenBLAS dgemm), clipped
    at 0, then `np.exp`, every step in place on the one n × m array."""
    aa = np.einsum("ij,ij->i", a, a)
    cc = np.einsum("ij,ij->i", c, c)
    r2 = a @ c.T
    r2 *= -2.0
    r2 += aa[:, None]
    r2 += cc[None, :]
    np.maximum(r2, 0.0, out=r2)
    r2 *= -1.0 / beta**2
    return np.exp(r2, out=r2)


def gaussian_cdist(a, c, beta):
    """The same matrix from scipy's `cdist` (one thread, one distance at a time)."""
    return np.exp(-cdist(a, c, "sqeuclidean") / beta**2)


def take_best(alive, wd, ww, floor, dd, picks, errs):
    """Appends the live candidate of largest ERR = (wᵀd)²/(wᵀw·dᵀd) among those with
    energy wᵀw above `floor`, marks it taken; False when none is left."""
    ok = alive & (ww > floor)
    err = np.where(ok, wd**2 / np.where(ok, ww, 1.0) / dd, -1.0)
    j = int(np.argmax(err))
    if err[j] <= 0:
        return False
    picks.append(j)
    errs.append(float(err[j]))
    alive[j] = False
    return True


def ols_chen(p, d, k, collinear=1e-12):
    """Chen's OLS with the bias forced: returns picks (column indices) and their ERRs."""
    n, m = p.shape
    dd = d @ d
    w = p.copy()
    norms = np.einsum("ij,ij->j", p, p)
    # forced bias column
    ones = np.ones(n)
    w -= np.outer(ones, (ones @ w) / n)
    r = d - d.mean()
    picks, errs = [], []
    alive = np.ones(m, dtype=bool)
    for _ in range(k):
        ww = np.einsum("ij,ij->j", w, w)
        wd = r @ w  # = wᵀd: the deflated columns are orthogonal to the span already fitted
        if not take_best(alive, wd, ww, norms * collinear, dd, picks, errs):
            break
        j = picks[-1]
        q = w[:, j].copy()
        qq = q @ q
        r -= q * ((q @ r) / qq)
        w -= np.outer(q, (q @ w) / qq)
    return picks, errs


def ols_cgs(p, d, k, collinear=1e-12):
    """Chen's OLS by classical Gram-Schmidt, one gemv q_kᵀP per pick (bias forced)."""
    n, m = p.shape
    dd = d @ d
    norms = np.einsum("ij,ij->j", p, p)
    q = np.ones(n) / np.sqrt(n)
    c = q @ p                     # the one product of this step
    energy = norms - c * c
    g = q @ d
    r = d - g * q
    pr = p.T @ d - g * c          # pᵀr: one more product, once
    basis = [q]
    picks, errs = [], []
    alive = norms > 0
    for _ in range(k):
        if not take_best(alive, pr, energy, norms * collinear, dd, picks, errs):
            break
        j = picks[-1]
        qs = np.column_stack(basis)
        w = p[:, j].copy()
        for _ in range(2):        # CGS2: the winner, explicitly
            w -= qs @ (qs.T @ w)
        q = w / np.linalg.norm(w)
        basis.append(q)
        g = q @ r
        r -= g * q
        c = q @ p                 # the one gemv of the pick
        energy -= c * c
        pr -= g * c
    return picks, errs


def fit_ols(xt, yt, beta, k, select=ols_chen, kernel=gaussian):
    phi = kernel(xt, xt, beta)
    picks, errs = select(phi, yt, k)
    a = np.column_stack([np.ones(len(yt)), phi[:, picks]])
    coef = np.linalg.lstsq(a, yt, rcond=None)[0]
    return xt[picks], coef, picks, errs


def fit_kmeans(xt, yt, beta, k, seed):
    km = KMeans(n_clusters=k, init="k-means++", n_init=1, random_state=seed).fit(xt)
    c = km.cluster_centers_
    a = np.column_stack([np.ones(len(yt)), gaussian(xt, c, beta)])
    coef = np.linalg.lstsq(a, yt, rcond=None)[0]
    return c, coef, int(km.n_iter_)


def predict(x, c, coef, beta):
    return coef[0] + gaussian(x, c, beta) @ coef[1:]


def scores(y, yhat):
    mse = float(np.mean((y - yhat) ** 2))
    return {"val_rmse": mse**0.5, "val_nmse": mse / float(np.var(y))}


def timed(f):
    t = time.perf_counter()
    out = f()
    return out, time.perf_counter() - t


def thread_pools():
    """The native thread pools loaded (numpy's and scipy's OpenBLAS, scikit-learn's
    OpenMP), as `threadpoolctl` reports them: library, version, kernel architecture,
    the package that ships it, and the threads it runs with."""
    out = []
    for p in threadpool_info():
        pkg = os.path.basename(os.path.dirname(p["filepath"])).removesuffix(".libs")
        arch = f" {p['architecture']}" if p.get("architecture") else ""
        version = f" {p['version']}" if p.get("version") else ""
        out.append(f"{pkg}: {p['internal_api']}{version}{arch}, "
                   f"{p['num_threads']} thread{'s' if p['num_threads'] != 1 else ''}")
    return out


def cmd_run(a):
    if a.threads:
        # run.sh sets OPENBLAS_NUM_THREADS and OMP_NUM_THREADS too; this holds the pools
        # to the count under test whatever the environment, and `blas` says what ran.
        threadpool_limits(limits=a.threads)
    xt, yt, xv, yv, train_rows = load(a.data)
    methods = a.methods.split(",")
    base = {"side": "python", "n_train": len(yt), "n_val": len(yv), "threads": a.threads,
            "blas": thread_pools()}
    for _ in range(a.reps):
        for name, select, kernel in (("cgs", ols_cgs, gaussian),
                                     ("cgs_cdist", ols_cgs, gaussian_cdist),
                                     ("ols", ols_chen, gaussian)):
            if name not in methods:
                continue
            (c, coef, picks, errs), secs = timed(
                lambda: fit_ols(xt, yt, a.beta, a.k, select, kernel))
            rec = dict(base, method=name, fit_seconds=secs, n_centers=len(picks),
                       picks=[int(train_rows[j]) for j in picks], errs=errs,
                       **scores(yv, predict(xv, c, coef, a.beta)))
            print(json.dumps(rec), flush=True)
        if "kmeans" in methods:
            (c, coef, iters), secs = timed(lambda: fit_kmeans(xt, yt, a.beta, a.k, a.seed))
            rec = dict(base, method="kmeans", fit_seconds=secs, n_centers=a.k, iterations=iters,
                       **scores(yv, predict(xv, c, coef, a.beta)))
            print(json.dumps(rec), flush=True)
        if "rbfi" in methods:
            interp, fit_s = timed(lambda: RBFInterpolator(
                xt, yt, kernel="gaussian", epsilon=1.0 / a.beta, smoothing=a.smoothing, degree=0))
            yhat, pred_s = timed(lambda: interp(xv))
            rec = dict(base, method="all", fit_seconds=fit_s, predict_seconds=pred_s,
                       n_centers=len(yt), **scores(yv, yhat))
            print(json.dumps(rec), flush=True)
        if "matvec" in methods:
            phi = gaussian(xt, xt, a.beta)
            v = np.sin(np.arange(len(yt)))
            ts = []
            for _ in range(30):
                _, s = timed(lambda: v @ phi)
                ts.append(s)
            print(json.dumps(dict(base, method="matvec", seconds=statistics.median(ts))), flush=True)


# ---------------------------------------------------------------- report

def normalise(r):
    """`rbf fit --json` objects become records like the Python side's; our records are
    labelled by the threads they ran on."""
    if r.get("command") == "fit":
        r = dict(r, side="rust", method=r["centers"])
        if r.get("ols"):
            r["picks"] = [p["row"] for p in r["ols"]["picks"]]
    if r.get("side") in ("rust", "python"):
        r["side"] = f"{r['side']}-{r.get('threads') or 0}t"
    return r


def agreement(ours, theirs):
    """Whether two sides' OLS picks (lists of data rows) agree: the same rows in the same
    order, and the same in every repetition of each side."""
    a_, b_ = ours[0]["picks"], theirs[0]["picks"]
    first_diff = next((i for i, (u, v) in enumerate(zip(a_, b_)) if u != v), None)
    shared = len(set(a_) & set(b_))
    same = ("identical, in the same order" if a_ == b_
            else f"first difference at pick {first_diff + 1}" if first_diff is not None
            else "one list is a prefix of the other")
    steady = all(r["picks"] == a_ for r in ours) and all(r["picks"] == b_ for r in theirs)
    return (f"{len(a_)} and {len(b_)} picks, {same}; {shared} of {min(len(a_), len(b_))} "
            f"centres shared; {'the same' if steady else 'NOT the same'} in every repetition")


def cmd_report(a):
    recs = [normalise(json.loads(line)) for path in a.files for line in open(path)
            if line.startswith("{")]
    ours = sorted({r["side"] for r in recs if r["side"].startswith("rust")}, reverse=True)
    theirs = sorted({r["side"] for r in recs if r["side"].startswith("python")}, reverse=True)
    # The Python side compared with ours: the one run with as many threads, else the only one.
    peer_side = [theirs[0] if theirs else "python-0t"]

    def peer_for(ours_side):
        same = "python-" + ours_side[5:]
        return same if same in theirs else (theirs[0] if theirs else "python-0t")

    def pick(side, method):
        if side == "python":
            side = peer_side[0]
        return [r for r in recs if r.get("side") == side and r.get("method") == method]

    def med(rs, key):
        vals = [r[key] for r in rs if r.get(key) is not None]
        return statistics.median(vals) if vals else float("nan")

    for r in recs:
        if r.get("method") == "all":
            r["fit+predict"] = r["fit_seconds"] + r["predict_seconds"]
    print("| measurement | threads: ours, peer | reps ours/peer | ours median (s) | peer median (s) "
          "| ours/peer | val NMSE ours | val NMSE peer |")
    print("|---|---|---|---|---|---|---|---|")
    for label, method, peer_method, key in [
        ("OLS K=100, fit (vs numpy CGS OLS, one gemv a pick, Gaussian by `A @ C.T`)", "ols", "cgs",
         "fit_seconds"),
        ("OLS K=100, fit (vs the same numpy CGS OLS, Gaussian by scipy `cdist`)", "ols", "cgs_cdist",
         "fit_seconds"),
        ("OLS K=100, fit (vs numpy OLS deflating every candidate)", "ols", "ols", "fit_seconds"),
        ("k-means K=100 + least squares, fit", "kmeans", "kmeans", "fit_seconds"),
        ("all points, fit", "all", "all", "fit_seconds"),
        ("all points, predict 2500", "all", "all", "predict_seconds"),
        ("all points, fit + predict", "all", "all", "fit+predict"),
    ]:
        for side in ours:
            peer_side[0] = peer_for(side)
            ps, rs = pick("python", peer_method), pick(side, method)
            if not (ps and rs):
                continue
            peer, o = med(ps, key), med(rs, key)
            pt = peer_side[0][7:-1]
            print(f"| {label} | {side[5:-1]}, {pt if pt != '0' else 'default'} | {len(rs)}/{len(ps)} "
                  f"| {o:.4f} | {peer:.4f} | {o / peer:.3f} "
                  f"| {med(rs, 'val_nmse'):.6f} | {med(ps, 'val_nmse'):.6f} |")

    print()
    for side in theirs:
        peer_side[0] = side
        blas = next((r["blas"] for r in recs if r.get("side") == side and r.get("blas")), None)
        if blas:
            print(f"Python thread pools ({side[7:-1]} threads asked): {'; '.join(blas)}")
        ref = pick("python", "cgs")
        for other in ("cgs_cdist", "ols"):
            po = pick("python", other)
            if ref and po:
                print(f"numpy OLS peers cgs and {other} pick the same ({side[7:-1]} threads): "
                      f"{ref[0]['picks'] == po[0]['picks']}")
    differ = []
    for side in ours:
        peer_side[0] = peer_for(side)
        ro = pick(side, "ols")
        for name in ("cgs", "cgs_cdist", "ols"):
            po = pick("python", name)
            if ro and po:
                print(f"OLS picks ({side[5:-1]} threads), ours against numpy {name}: "
                      f"{agreement(ro, po)}")
                e_o, e_p = med(ro, "val_rmse"), med(po, "val_rmse")
                print(f"OLS validation RMSE: ours {e_o:.9f}, numpy {name} {e_p:.9f}")
                if any(r["picks"] != po[0]["picks"] for r in ro + po):
                    differ.append(f"the OLS picks of ours ({side[5:-1]} threads) and numpy {name}")
                if not abs(e_o - e_p) <= RMSE_EQUAL * e_p:
                    differ.append(f"the OLS validation RMSE of ours ({side[5:-1]} threads) "
                                  f"and numpy {name} ({e_o!r} against {e_p!r})")
        if not ro:
            continue
        used = sorted({r.get("threads_used") for r in ro if r.get("threads_used")})
        if used:
            print(f"OLS passes ({side[5:-1]} threads asked): ran on {used} threads; "
                  f"last reason: {ro[-1].get('threads_reason')}")
        spp = med(ro, "seconds_per_pick")
        line = f"OLS core ({side[5:-1]} threads): {spp * 1e3:.2f} ms per pick"
        mv = pick(side, "matvec")
        if mv:
            b1, b2 = med(mv, "seconds"), med(mv, "seconds_2row")
            r32 = med(mv, "seconds_read_f32")
            line += (f"; one read of the f32 copy of the 2500×2500 candidates {r32 * 1e3:.2f} ms: "
                     f"a pick costs {spp / r32:.2f}× reading what it streams; "
                     f"one faer vᵀP over the f64 matrix {b1 * 1e3:.2f} ms "
                     f"({med(mv, 'gb_per_s'):.1f} GB/s), [q r]ᵀP {b2 * 1e3:.2f} ms")
        print(line)
    for side in theirs:
        peer_side[0] = side
        mp = pick("python", "matvec")
        if mp:
            print(f"numpy v @ P over the same matrix ({side[7:-1]} threads): "
                  f"{med(mp, 'seconds') * 1e3:.2f} ms")
        ko = pick("python", "kmeans")
        if ko:
            print(f"scikit-learn k-means iterations (median, {side[7:-1]} threads): "
                  f"{med(ko, 'iterations'):.0f}")
    if differ:
        print("DIFFERENT: " + "; ".join(differ), file=sys.stderr)
        return 4
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    g = sub.add_parser("gen")
    g.add_argument("--train", type=int, default=2500)
    g.add_argument("--val", type=int, default=2500)
    g.add_argument("--seed", type=int, default=2024)
    g.add_argument("--out", required=True)
    r = sub.add_parser("run")
    r.add_argument("--data", required=True)
    r.add_argument("--beta", type=float, required=True)
    r.add_argument("--k", type=int, default=100)
    r.add_argument("--seed", type=int, default=42)
    r.add_argument("--smoothing", type=float, default=1e-8)
    r.add_argument("--reps", type=int, default=1)
    r.add_argument("--methods", default="cgs,cgs_cdist,ols,kmeans,rbfi,matvec")
    r.add_argument("--threads", type=int, default=None,
                   help="the OpenBLAS/OpenMP threads this run was given (a label for the report)")
    p = sub.add_parser("report")
    p.add_argument("files", nargs="+")
    a = ap.parse_args()
    return {"gen": cmd_gen, "run": cmd_run, "report": cmd_report}[a.cmd](a)


if __name__ == "__main__":
    sys.exit(main())
