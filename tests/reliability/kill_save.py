#!/usr/bin/env python3
"""SIGKILL in the middle of saving a large scene, 50 times: the file is
always the old or the new scene, whole (never cut, never empty), and the
temporary files a killed save leaves are removed by the next save.

Usage: kill_save.py PATH/TO/isolux_save_loop
"""
import glob, json, os, random, signal, subprocess, sys, tempfile, time

loop = sys.argv[1]
d = tempfile.mkdtemp(prefix="isolux_kill_")
path = os.path.join(d, "level.json")
subprocess.run([loop, path, "once"], check=True)
random.seed(7)
bad, kills = [], 0
for i in range(50):
    p = subprocess.Popen([loop, path], stdout=subprocess.PIPE)
    p.stdout.readline()  # it has saved once: the next saves are under way
    time.sleep(random.uniform(0.0, 0.25))
    os.kill(p.pid, signal.SIGKILL)
    p.wait()
    kills += 1
    try:
        n = len(json.load(open(path))["lights"])
    except Exception as e:  # noqa: BLE001 - any failure to read is the bug we look for
        bad.append(f"kill {i}: {e}")
        continue
    if n not in (4000, 6000):
        bad.append(f"kill {i}: {n} lights")
left = glob.glob(os.path.join(d, ".level.tmp*"))
# A temp file of a writer that no longer runs, as a kill mid-write leaves
# one, and one of a writer still running (this script): the next save
# removes the first and leaves the second.
dead = next(pid for pid in range(4000000, 3000000, -1) if not os.path.exists(f"/proc/{pid}"))
open(os.path.join(d, f".level.tmp{dead}_3.json"), "w").write('{"cut')
live = os.path.join(d, f".level.tmp{os.getpid()}_0.json")
open(live, "w").write("{")
subprocess.run([loop, path, "once"], check=True)
if not os.path.exists(live):
    bad.append("a running writer's temp file was removed")
os.remove(live)
after = glob.glob(os.path.join(d, ".level.tmp*"))
print(f"kill_save: {kills} kills, {len(bad)} damaged files, {len(left)} temp files left by kills, {len(after)} after one more save")
for b in bad:
    print("FAIL", b)
if after:
    print("FAIL stale temp files remain:", after)
for f in glob.glob(os.path.join(d, "*")) + glob.glob(os.path.join(d, ".*")):
    os.remove(f)
os.rmdir(d)
sys.exit(1 if bad or after else 0)
