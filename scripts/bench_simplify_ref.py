#!/usr/bin/env python3
"""Homology-preserving edge contraction side by side: the reference Stellar tree's `stellar_suite -q contractT`
(UMDGeoVis/Stellar_tree, built by ../shared/peers/stellar_ref_build.sh) against `starplex simplify --mode homology`.

    bench_simplify_ref.py --ref PATH/stellar_suite --starplex PATH/starplex [--reps 3] [--threads 1,2] INPUT[:KV] ...

INPUT is a .tri or .ts file (both programs read them); KV defaults to 100 (.tri) and 400 (.ts), as in
../shared/peers/bench_stellar_ref.py. Both run to the end (no target): every edge that passes the link condition is
contracted. One process at a time, alternating which program goes first. Times are each program's own timer:
the reference's "[TIME] Edge contraction simplification" (its tree build and final compaction not counted) and
starplex's `time_s` (building its working structure and blocks, the rounds, and writing the result back into a
complex; reading and writing files not counted). Peak RSS is each process's (wait4). Prints a markdown table of
medians: contractions, time, microseconds per contraction, and ratio = reference / starplex.
"""
import argparse, os, re, shutil, statistics, subprocess, sys, tempfile, json

DEFAULT_KV = {"tri": 100, "ts": 400}


def run_rss(cmd, cwd, env):
    """Runs cmd; returns (stdout, stderr, rc, peak RSS in MiB)."""
    with tempfile.TemporaryFile() as fo, tempfile.TemporaryFile() as fe:
        pid = os.fork()
        if pid == 0:
            os.chdir(cwd)
            os.dup2(fo.fileno(), 1)
            os.dup2(fe.fileno(), 2)
            os.execvpe(cmd[0], cmd, env)
        _, status, ru = os.wait4(pid, 0)
        fo.seek(0)
        fe.seek(0)
        rc = os.waitstatus_to_exitcode(status)
        return fo.read().decode(errors="replace"), fe.read().decode(errors="replace"), rc, ru.ru_maxrss / 1024


def grab_last(pat, text):
    m = re.findall(pat, text)
    return float(m[-1]) if m else None


def ref_once(args, path, kv, work):
    env = dict(os.environ, OMP_NUM_THREADS="1", LC_ALL="C")
    out, err, rc, rss = run_rss([args.ref, "-i", os.path.basename(path), "-v", str(kv), "-q", "contractT"], work, env)
    text = out + err
    if rc != 0:
        sys.exit(f"reference failed ({rc}) on {path}:\n{text[-2000:]}")
    return {"time_s": grab_last(r"\[TIME\] Edge contraction simplification:\s*([0-9.eE+-]+)", text),
            "n_contractions": grab_last(r"\[STATS\] contracted edges\s*([0-9]+)", text),
            "vertices_after": grab_last(r"Vertices:\s*([0-9]+)", text),
            "tops_after": grab_last(r"Top-cells:\s*([0-9]+)", text),
            "peak_mib": rss}


def sp_once(args, path, threads, work):
    env = dict(os.environ, RAYON_NUM_THREADS=str(threads), LC_ALL="C")
    outp = os.path.join(work, "out.spb")
    out, err, rc, rss = run_rss([args.starplex, "simplify", path, outp, "--mode", "homology", "--threads",
                                 str(threads), "--json", "--quiet"], work, env)
    if rc != 0:
        sys.exit(f"starplex failed ({rc}) on {path}:\n{err[-2000:]}")
    d = json.loads(out)
    return {"time_s": d["time_s"], "n_contractions": d["n_contractions"], "rounds": d.get("rounds"),
            "vertices_after": d["after"]["n_vertices"], "tops_after": d["after"]["n_cells"], "peak_mib": rss}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ref", required=True)
    ap.add_argument("--starplex", required=True)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--threads", default="1,2", help="starplex thread counts, comma-separated (the reference runs on one)")
    ap.add_argument("inputs", nargs="+")
    args = ap.parse_args()
    args.threads = [int(t) for t in args.threads.split(",")]
    rows = []
    for spec in args.inputs:
        path, _, kv = spec.partition(":")
        path = os.path.abspath(path)
        ext = path.rsplit(".", 1)[-1]
        kv = int(kv) if kv else DEFAULT_KV.get(ext, 100)
        work = tempfile.mkdtemp(prefix="simpref_")
        os.symlink(path, os.path.join(work, os.path.basename(path)))
        res = {"ref": []}
        for t in args.threads:
            res[f"sp{t}"] = []
        for r in range(args.reps):
            order = ["ref"] + [f"sp{t}" for t in args.threads]
            if r % 2:
                order.reverse()
            for who in order:
                d = ref_once(args, path, kv, work) if who == "ref" else sp_once(args, path, int(who[2:]), work)
                print(f"  {os.path.basename(path)} rep {r + 1} {who:4} {json.dumps(d)}", file=sys.stderr)
                res[who].append(d)
        shutil.rmtree(work, ignore_errors=True)
        med = {w: {k: statistics.median([x[k] for x in v if x.get(k) is not None] or [float("nan")])
                   for k in ("time_s", "n_contractions", "vertices_after", "tops_after", "peak_mib")} for w, v in res.items()}
        rows.append((os.path.basename(path), kv, med))
    print("\n| input | program | contractions | left: vertices / tops | time s | µs per contraction | ratio ref/sp per contraction | peak RSS MiB |")
    print("|---|---|---:|---|---:|---:|---:|---:|")
    for name, kv, med in rows:
        ref = med["ref"]
        ref_us = 1e6 * ref["time_s"] / ref["n_contractions"]
        for w, m in med.items():
            us = 1e6 * m["time_s"] / m["n_contractions"]
            label = "reference (1 thread)" if w == "ref" else f"starplex ({w[2:]} thread{'s' if w != 'sp1' else ''})"
            ratio = "" if w == "ref" else f"**{ref_us / us:.1f}×**"
            print(f"| {name} (kV {kv}) | {label} | {m['n_contractions']:,.0f} | {m['vertices_after']:,.0f} / {m['tops_after']:,.0f} "
                  f"| {m['time_s']:.3f} | {us:.2f} | {ratio} | {m['peak_mib']:.0f} |")


if __name__ == "__main__":
    main()
