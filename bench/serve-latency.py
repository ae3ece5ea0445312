#!/usr/bin/env python3
"""How quickly `snell serve` shows a saved scene, and how fast its picture refines.

For each scene, a copy is written beside it (scenes/.bench-NAME.toml, so that its relative
paths still work) and previewed by `snell serve COPY --port 0 [--integrator ...]`. The script
follows the server's event stream (/events, as the page does) and, --saves times over, saves
the copy (a comment line added or taken away: the server reads and renders it again either
way) and measures:

  save -> picture   from the write to the status event of the new render's first frame
                    (the page asks for the frame then; its JPEG takes a few ms more), and
  refinement        frames a second over the rest of that render, and the time until it is
                    done (Whitted: one sample a pixel, then all; path: passes of about
                    0.15 s each until the scene's samples are reached, capped at --window s).

Usage:
    cargo build --release
    python3 bench/serve-latency.py                               # seed and bunny, Whitted and path
    python3 bench/serve-latency.py --scene scenes/seed.toml --saves 20 --size 512

Prints one line per scene and integrator: the median and worst save-to-picture time, and the
median frames a second of refinement. This is a manual benchmark; CI does not run it.
"""
import argparse
import http.client
import json
import os
import statistics
import subprocess
import sys
import threading
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class Events:
    """The server's status events, each with the time it arrived."""

    def __init__(self, port):
        self.statuses = []
        self.lock = threading.Lock()
        conn = http.client.HTTPConnection('127.0.0.1', port)
        conn.request('GET', '/events', headers={'Host': f'127.0.0.1:{port}'})
        self.resp = conn.getresponse()
        threading.Thread(target=self.read, daemon=True).start()

    def read(self):
        data = b''
        while True:
            chunk = self.resp.readline()
            if not chunk:
                return
            if chunk.startswith(b'data: '):
                data = chunk[6:]
            elif chunk == b'\n' and data:
                with self.lock:
                    self.statuses.append((time.perf_counter(), json.loads(data)))
                data = b''

    def since(self, t):
        with self.lock:
            return [(at, s) for at, s in self.statuses if at >= t]


def wait(events, t0, test, timeout=60.0):
    """The first status after t0 that passes `test`, with its time."""
    start = time.perf_counter()
    while True:
        for at, s in events.since(t0):
            if test(s):
                return at, s
        if time.perf_counter() - start > timeout:
            raise TimeoutError('no such status')
        time.sleep(0.001)


def run(snell, scene, integrator, saves, size, window):
    name = os.path.splitext(os.path.basename(scene))[0]
    copy = os.path.join(os.path.dirname(os.path.abspath(scene)), f'.bench-{name}.toml')
    with open(scene) as f:
        text = f.read()
    with open(copy, 'w') as f:
        f.write(text)
    args = [snell, 'serve', copy, '--port', '0', '--size', str(size)]
    if integrator:
        args += ['--integrator', integrator]
    server = subprocess.Popen(args, cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    try:
        line = server.stdout.readline()
        port = int(line.split('http://127.0.0.1:')[1].split('/')[0])
        events = Events(port)
        done = lambda s: s['frame'] and s['frame']['generation'] == s['generation'] and s['frame']['done']
        wait(events, 0.0, done)
        latencies, fps, finish = [], [], []
        for i in range(saves):
            time.sleep(0.2)
            last = events.since(0.0)[-1][1]['generation']
            t0 = time.perf_counter()
            with open(copy, 'w') as f:
                f.write(text if i % 2 else text + '\n# saved again\n')
            first_at, first = wait(events, t0, lambda s: s['generation'] > last and s['frame']
                                   and s['frame']['generation'] == s['generation'])
            g = first['generation']
            latencies.append(first_at - t0)
            try:
                end_at, _ = wait(events, first_at, lambda s: s['generation'] == g and s['frame']
                                 and s['frame']['done'], timeout=window)
            except TimeoutError:
                end_at = first_at + window
            frames = {s['frame']['id'] for at, s in events.since(first_at)
                      if at <= end_at and s['frame'] and s['frame']['generation'] == g}
            finish.append(end_at - t0)
            if end_at > first_at and len(frames) > 1:
                fps.append((len(frames) - 1) / (end_at - first_at))
        st = events.since(0.0)[-1][1]
        print(f"{os.path.relpath(scene, REPO)} {st['integrator']} {st['size'][0]}x{st['size'][1]} "
              f"{st['target_spp']} spp: save -> first picture median {statistics.median(latencies) * 1e3:.0f} ms "
              f"(worst {max(latencies) * 1e3:.0f} ms); refinement {statistics.median(fps) if fps else 0:.1f} frames/s, "
              f"all samples after {statistics.median(finish):.2f} s ({saves} saves)")
    finally:
        server.terminate()
        server.wait()
        os.remove(copy)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--snell', default=os.path.join(REPO, 'target', 'release', 'snell'))
    ap.add_argument('--scene', action='append', help='scene file (repeatable; default seed and bunny)')
    ap.add_argument('--integrator', action='append', help='whitted or path (repeatable; default both)')
    ap.add_argument('--saves', type=int, default=10)
    ap.add_argument('--size', type=int, default=512, help="the preview's longest side (its default)")
    ap.add_argument('--window', type=float, default=10.0, help='most seconds of refinement measured')
    a = ap.parse_args()
    scenes = a.scene or [os.path.join(REPO, 'scenes', 'seed.toml'), os.path.join(REPO, 'scenes', 'bunny.toml')]
    for scene in scenes:
        for integrator in a.integrator or ['whitted', 'path']:
            run(a.snell, scene, integrator, a.saves, a.size, a.window)


if __name__ == '__main__':
    sys.exit(main())
