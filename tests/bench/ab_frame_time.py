#!/usr/bin/env python3
"""Median GPU ms per frame of every method on carousel and cornell for two stratad builds (A/B), in
interleaved rounds (before, after; then after, before; ...), frames 2.. of each run.
usage: ab_frame_time.py BEFORE_STRATAD AFTER_STRATAD OUT.json [rounds] [size] [frames]"""
import json, statistics, subprocess, sys, tempfile, os
before, after, out = sys.argv[1:4]
rounds = int(sys.argv[4]) if len(sys.argv) > 4 else 2
size = sys.argv[5] if len(sys.argv) > 5 else "256"
frames = int(sys.argv[6]) if len(sys.argv) > 6 else 8
methods = ["pt", "restir-gather", "restir-di", "restir-splat", "restir-splat-backup", "restir-multilayer"]
scenes = ["carousel", "cornell"]
res = {}
def run(binary, scene, method):
    with tempfile.TemporaryDirectory() as d:
        subprocess.run([binary, "render", "--scene", scene, "--method", method, "--width", size, "--height", size,
                        "--frames", str(frames), "--out", d], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        fr = json.load(open(os.path.join(d, "frames.json")))["frames"]
        return statistics.median(f["gpu_ms_total"] for f in fr[2:])
for r in range(rounds):
    for scene in scenes:
        for method in methods:
            order = [("before", before), ("after", after)] if r % 2 == 0 else [("after", after), ("before", before)]
            for name, b in order:
                ms = run(b, scene, method)
                res.setdefault(f"{scene}/{method}", {}).setdefault(name, []).append(ms)
                print(r, scene, method, name, round(ms, 1), flush=True)
summary = {k: {"before_ms": statistics.mean(v["before"]), "after_ms": statistics.mean(v["after"]),
               "ratio": statistics.mean(v["after"]) / statistics.mean(v["before"]), "rounds": v} for k, v in res.items()}
json.dump({"size": size, "frames": frames, "rounds": rounds, "results": summary}, open(out, "w"), indent=1)
for k, v in summary.items(): print(f"| {k} | {v['before_ms']:.1f} | {v['after_ms']:.1f} | {v['ratio']:.2f} |")
