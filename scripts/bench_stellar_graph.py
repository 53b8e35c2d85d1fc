#!/usr/bin/env python3
"""Stellar trees by coordinates and by connectivity on the same complexes: chi, mu, leaves and
build time from `starplex stellar FILE --json [--decomposition graph] [--kv K]`, one process
per run, CPU seconds from /usr/bin/time.

usage: bench_stellar_graph.py --starplex BIN FILE [FILE ...] [--kv K] [--bench]
"""
import argparse
import json
import subprocess
import sys


def run(cmd):
    p = subprocess.run(["/usr/bin/time", "-f", "%e %U %S %M"] + cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("failed: %s\n%s" % (" ".join(cmd), p.stderr[-2000:]))
    wall, user, sys_, rss = p.stderr.strip().splitlines()[-1].split()
    return json.loads(p.stdout), float(wall), float(user) + float(sys_), int(rss) / 1024


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("files", nargs="+")
    ap.add_argument("--starplex", required=True)
    ap.add_argument("--kv", type=int)
    ap.add_argument("--bench", action="store_true")
    a = ap.parse_args()
    print("| complex | decomposition | k_V | leaves | chi | mu | build s | build CPU s | VT all s | process CPU s | peak MB |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for f in a.files:
        chis = {}
        for d in ("spatial", "graph"):
            cmd = [a.starplex, "--quiet", "stellar", f, "--json", "--decomposition", d]
            if a.kv is not None:
                cmd += ["--kv", str(a.kv)]
            if a.bench:
                cmd += ["--bench"]
            j, wall, cpu, rss = run(cmd)
            t = j["timings"]
            chis[d] = j["chi"]
            print("| %s | %s | %d | %d | %.3f | %.3f | %.3f | %s | %s | %.2f | %.0f |" % (
                f.split("/")[-1], d, j["kv"], j["n_leaves"], j["chi"], j["mu"], t["build_s"],
                "%.3f" % t["build_cpu_s"] if t.get("build_cpu_s") is not None else "",
                "%.3f" % t["vt_all_s"] if "vt_all_s" in t else "", cpu, rss), flush=True)
        print("| %s | graph chi / spatial chi | | | %.2f | | | | | | |" % (
            f.split("/")[-1], chis["graph"] / chis["spatial"]), flush=True)


if __name__ == "__main__":
    main()
