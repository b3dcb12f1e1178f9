"""Where the demo's time goes: runs a command on a pseudo-terminal (the
progress display shows only on one) and prints how long each of the demo's
progress messages stood, until the next one or the end.

    python3 scripts/demo-steps.py target/release/dtg-vib demo --out D
"""
import os, pty, sys, time, re

argv = sys.argv[1:]
t0 = time.time()
pid, fd = pty.fork()
if pid == 0:
    os.execvp(argv[0], argv)
seen = []; buf = b''
while True:
    try:
        data = os.read(fd, 4096)
    except OSError:
        break
    if not data: break
    buf += data
    for m in re.findall(rb'(simulating the vibration test|fitting the baseline model|writing the baseline report|diagnosing the baseline|refitting with the suggested effects|diagnosing the refit|writing the final report)', buf):
        key = m.decode()
        if not any(k == key for k, _ in seen):
            seen.append((key, time.time() - t0))
    buf = buf[-200:]
os.waitpid(pid, 0)
end = time.time() - t0
for i, (k, t) in enumerate(seen):
    nxt = seen[i + 1][1] if i + 1 < len(seen) else end
    print(f"{k:45s} {nxt - t:6.2f} s")
print(f"{'total':45s} {end:6.2f} s")
