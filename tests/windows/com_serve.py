# tests/windows/run.sh: tmclrun.exe --serve COM7 under Wine, COM7 mapped (a dosdevices link) to the
# slave of a pseudo-terminal whose master this script holds as the host: one GAP request, its
# reply. Prints "ready: LINE" and "reply: HEX".
#   com_serve.py WINEPREFIX TMCLRUN_EXE PROGRAM
import os, pty, select, subprocess, sys, time, tty
prefix, exe, prog = sys.argv[1:4]
master, slave = pty.openpty()
tty.setraw(master)
tty.setraw(slave)
link = os.path.join(prefix, "dosdevices", "com7")
if os.path.lexists(link):
    os.remove(link)
os.symlink(os.ttyname(slave), link)
p = subprocess.Popen(["wine", exe, "--serve", "COM7", prog], stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
print("ready:", p.stdout.readline().decode().strip())
req = bytes([1, 6, 4, 0, 0, 0, 0, 0])
os.write(master, req + bytes([sum(req) & 0xFF]))
reply, deadline = b"", time.time() + 10
while len(reply) < 9 and time.time() < deadline:
    if select.select([master], [], [], 0.5)[0]:
        reply += os.read(master, 64)
print("reply:", reply.hex(" "))
p.kill()
p.wait()
os.remove(link)
