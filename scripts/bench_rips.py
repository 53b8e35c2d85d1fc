#!/usr/bin/env python3
"""starplex rips against GUDHI RipsComplex + create_simplex_tree and networkx find_cliques on the
same points, in one run, each in a fresh process (peak RSS from /usr/bin/time -v).

usage: bench_rips.py --starplex BIN --peer ../shared/peers/bench_gudhi.py POINTS.xyz
                     (--eps E | --eps-nn F) --maxdim K [K ...] [--python VENV_PYTHON] [--no-gudhi]

Prints one JSON line per run and a markdown table of ratios (peer / starplex; above 1: starplex
is faster or smaller). starplex is timed on its build (graph + cliques, `timings.build_s` of
--json) and on its whole process; GUDHI on RipsComplex + create_simplex_tree; networkx on
find_cliques alone (its graph is built before the clock starts).
"""
import argparse
import json
import re
import subprocess
import sys


def timed(cmd):
    p = subprocess.run(["/usr/bin/time", "-v"] + cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("failed: %s\n%s" % (" ".join(cmd), p.stderr[-3000:]))
    rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", p.stderr).group(1)) / 1024
    wall = re.search(r"Elapsed \(wall clock\) time.*: (.*)", p.stderr).group(1).split(":")
    wall = sum(float(x) * 60 ** i for i, x in enumerate(reversed(wall)))
    cpu = sum(float(re.search(r"%s time \(seconds\): ([\d.]+)" % w, p.stderr).group(1))
              for w in ("User", "System"))
    timed.cpu = cpu
    return p.stdout, rss, wall


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("points")
    ap.add_argument("--starplex", required=True)
    ap.add_argument("--peer", required=True)
    ap.add_argument("--python", default="/work/data/.venv/bin/python")
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--eps", type=float)
    g.add_argument("--eps-nn", type=float)
    ap.add_argument("--maxdim", type=int, nargs="+", required=True)
    ap.add_argument("--no-gudhi", action="store_true")
    a = ap.parse_args()
    scale = ["--eps", repr(a.eps)] if a.eps else ["--eps-nn", repr(a.eps_nn)]
    rows = []
    for k in a.maxdim:
        out, rss, wall = timed([a.starplex, "--quiet", "rips", a.points] + scale +
                               ["--max-dim", str(k), "-o", "/tmp/bench_rips_out.spb", "--json"])
        sp = json.loads(out)
        sp.update(tool="starplex", max_dim=k, peak_rss_mb=rss, process_wall_s=wall,
                  process_cpu_s=timed.cpu)
        print(json.dumps(sp), flush=True)
        row = {"max_dim": k, "sp_build_s": sp["timings"]["build_s"], "sp_wall_s": wall, "sp_rss": rss,
               "sp_tops": sp["n_maximal_simplices"], "eps": sp["eps"], "sp_cpu": timed.cpu}
        if not a.no_gudhi:
            out, rss, wall = timed([a.python, a.peer, "rips", a.points, "--eps", repr(sp["eps"]),
                                    "--maxdim", str(k)])
            for line in out.splitlines():
                j = json.loads(line)
                if j.get("op") == "RipsComplex.create_simplex_tree":
                    j.update(process_peak_rss_mb=rss)
                    print(json.dumps(j), flush=True)
                    row.update(gudhi_s=j["wall_s"], gudhi_rss=rss, gudhi_simplices=j["num_simplices"],
                               gudhi_cpu=j["cpu_s"])
        rows.append(row)
    # networkx maximal cliques (no max_dim): once
    out, rss, wall = timed([a.python, a.peer, "rips", a.points, "--eps", repr(rows[0]["eps"]),
                            "--maxdim", "1", "--cliques"])
    nx = None
    for line in out.splitlines():
        j = json.loads(line)
        if j.get("peer") == "networkx":
            nx = j
            print(json.dumps(j), flush=True)
    full, rss_full, wall_full = timed([a.starplex, "--quiet", "rips", a.points] + scale +
                                      ["-o", "/tmp/bench_rips_out.spb", "--json"])
    full = json.loads(full)
    full_cpu = timed.cpu
    print(json.dumps(dict(full, tool="starplex", max_dim=None, peak_rss_mb=rss_full,
                          process_cpu_s=full_cpu)), flush=True)
    print()
    print("| max dim K | starplex build wall s | starplex process CPU s | starplex peak MB | GUDHI wall s | "
          "GUDHI CPU s | GUDHI peak MB | GUDHI simplices | starplex maximal simplices | wall ratio | "
          "CPU ratio | memory ratio |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        if "gudhi_s" in r:
            print("| %d | %.3f | %.2f | %.0f | %.2f | %.2f | %.0f | %d | %d | %.1fx | %.1fx | %.1fx |" % (
                r["max_dim"], r["sp_build_s"], r["sp_cpu"], r["sp_rss"], r["gudhi_s"], r["gudhi_cpu"],
                r["gudhi_rss"], r["gudhi_simplices"], r["sp_tops"], r["gudhi_s"] / r["sp_build_s"],
                r["gudhi_cpu"] / r["sp_cpu"], r["gudhi_rss"] / r["sp_rss"]))
    # the whole complex by its maximal simplices holds every K-skeleton: against GUDHI's K rows
    print()
    print("starplex without --max-dim (the whole complex, every dimension): build %.3f s wall, "
          "process %.2f s CPU, peak %.1f MB, %d maximal simplices" % (
              full["timings"]["build_s"], full_cpu, rss_full, full["n_maximal_simplices"]))
    print()
    print("| GUDHI max dim K | GUDHI wall s | GUDHI peak MB | wall ratio (GUDHI / starplex whole) | "
          "memory ratio |")
    print("|---|---|---|---|---|")
    for r in rows:
        if "gudhi_s" in r:
            print("| %d | %.2f | %.0f | %.1fx | %.1fx |" % (
                r["max_dim"], r["gudhi_s"], r["gudhi_rss"], r["gudhi_s"] / full["timings"]["build_s"],
                r["gudhi_rss"] / rss_full))
    if nx:
        t = full["timings"]
        print()
        print("networkx find_cliques (its graph built before its clock starts): %.3f s wall, %.3f s CPU, "
              "%d cliques; starplex clique enumeration (cliques_s, graph excluded likewise): %.4f s wall "
              "-> **%.1fx**; starplex graph + cliques + complex (build_s): %.4f s -> %.1fx; whole "
              "process %.3f s CPU -> %.1fx CPU" % (
                  nx["wall_s"], nx["cpu_s"], nx["maximal_cliques"], t["cliques_s"],
                  nx["wall_s"] / t["cliques_s"], t["build_s"], nx["wall_s"] / t["build_s"], full_cpu,
                  nx["cpu_s"] / full_cpu))

if __name__ == "__main__":
    main()
