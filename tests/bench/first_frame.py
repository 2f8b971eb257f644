#!/usr/bin/env python3
"""Time from `stratad serve` start to the first frame of `strata stream` (docs/BENCHMARKS.md, "Live
viewer and first frames"), with Mesa's shader cache in a given folder (an empty one: a cold machine).

    tests/bench/first_frame.py --build build/release --cache /tmp/mesa-cold [--method restir-gather]
        [--size 256] [--frames 400] [--serve-arg=--no-progressive-start ...]

Prints the seconds to the first frame, to the first frame of the method asked for (with a progressive
start, the frame after its first-frame pipelines compiled), to its first frame with history (where the
progressive start held its history passes: the frame after theirs compiled), stratad's CPU seconds up
to then, the load average, and stratad's log. Stops both processes once that frame is in (or the
stream ends).
"""
import argparse
import json
import os
import pathlib
import resource
import signal
import subprocess
import sys
import tempfile
import time


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default="build/release")
    ap.add_argument("--cache", required=True, help="MESA_SHADER_CACHE_DIR (created if missing)")
    ap.add_argument("--scene", default="carousel")
    ap.add_argument("--method", default="restir-gather")
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--frames", type=int, default=400)
    ap.add_argument("--serve-arg", action="append", default=[])
    a = ap.parse_args()

    build = pathlib.Path(a.build)
    work = pathlib.Path(tempfile.mkdtemp(prefix="first_frame_"))
    out = work / "out"
    env = dict(os.environ, MESA_SHADER_CACHE_DIR=str(pathlib.Path(a.cache).resolve()))
    pathlib.Path(a.cache).mkdir(parents=True, exist_ok=True)
    load = os.getloadavg()
    t0 = time.monotonic()
    log = open(work / "stratad.log", "w+")
    serve = subprocess.Popen([str(build / "server/stratad"), "serve", "--listen", "127.0.0.1:0", "--port-file",
                              str(work / "port")] + a.serve_arg, stdout=log, stderr=subprocess.STDOUT, env=env)
    while not (work / "port").exists():
        if serve.poll() is not None:
            sys.exit("stratad exited:\n" + (work / "stratad.log").read_text())
        time.sleep(0.01)
    port = (work / "port").read_text().strip()
    t_listen = time.monotonic() - t0
    stream = subprocess.Popen([str(build / "client/strata"), "stream", "--server", "127.0.0.1:" + port, "--scene", a.scene,
                               "--method", a.method, "--width", str(a.size), "--height", str(a.size), "--frames",
                               str(a.frames), "--encodings", "exr,png", "--out", str(out), "--timeout", "900"],
                              stdout=open(work / "stream.log", "w"), stderr=subprocess.STDOUT, env=env)
    t_first = t_method = t_history = None
    def frames_seen():
        return len(list(out.glob("frame_*.png"))) if out.exists() else 0
    while stream.poll() is None:
        n = frames_seen()
        if n and t_first is None:
            t_first = time.monotonic() - t0
        text = (work / "stratad.log").read_text()
        progressive = "compile in the background" in text
        if t_first is not None and t_method is None and (not progressive or " renders from frame " in text):
            if not progressive:
                t_method = t_first
            else:
                switch = int(text.split(" renders from frame ")[1].split()[0])
                if n > switch:
                    t_method = time.monotonic() - t0
        if t_method is not None and t_history is None:
            if "its history passes held" not in text:
                t_history = t_method
            elif " reuse history from frame " in text:
                if n > int(text.split(" reuse history from frame ")[1].split()[0]):
                    t_history = time.monotonic() - t0
        if t_history is not None:
            break
        time.sleep(0.02)
    cpu = None
    try:
        with open(f"/proc/{serve.pid}/stat") as f:
            fields = f.read().rsplit(")", 1)[1].split()
            cpu = (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except OSError:
        pass
    stream.send_signal(signal.SIGTERM)
    stream.wait()
    serve.send_signal(signal.SIGTERM)
    try:
        serve.wait(timeout=300)
    except subprocess.TimeoutExpired:
        serve.kill()
        serve.wait()
    result = {"listen_s": round(t_listen, 2), "first_frame_s": t_first and round(t_first, 2),
              "method_first_frame_s": t_method and round(t_method, 2),
              "method_history_frame_s": t_history and round(t_history, 2), "stratad_cpu_s_then": cpu,
              "frames": frames_seen(), "loadavg_before": load, "loadavg_after": os.getloadavg()}
    print((work / "stratad.log").read_text())
    print((work / "stream.log").read_text()[-3000:])
    print(json.dumps(result))


if __name__ == "__main__":
    main()
