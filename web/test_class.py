#!/usr/bin/env python3
"""The live class in headless Chromium (issue 50): the class server (`armlab class serve`, which
serves the web build too) with one teacher page (the teacher link, ``?token=T``) and two student
pages (the student link with a nickname, ``?code=C&name=N``), each its own Chromium driven
through chromedriver (web/test_page.py's Driver). Checks, from the pages:

1. the three pages join: the teacher's page counts two students;
2. the teacher drags the IK target's gizmo (a scripted mouse drag, as web/test_page.py does):
   both students' ``status().q`` equal the teacher's within 1 s (polled), to 1e-9 rad;
3. the teacher asks "Which posture is this?" (the page hook that applies the Class window
   button's action), one student answers a choice (the hook that applies the question window
   button's action): the teacher's page shows one answer of two, counted on that choice;
4. a third student opens the students' link without a nickname: the page asks for one, the
   nickname typed key by key (a whole sentence, no shortcut firing: q, tab and solutions stay,
   then Enter) joins, and the server's data file holds it exactly;
5. the server is stopped and started again on the same port and data file: every page
   reconnects by itself, the students as the same students (the teacher still counts three, no
   new rows in the data file), and they follow the teacher's arm again;
6. no console errors, no panic.

Usage: web/test_class.py DIST_DIR. Builds ``target/debug/armlab`` with cargo if it is missing.
Fails (never skips) when Chromium or chromedriver is missing.
"""

import json
import os
import shutil
import sqlite3
import subprocess
import sys
import tempfile
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_page import Driver, drag_from, fail, free_port, status, wait_for  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ARMLAB = os.path.join(ROOT, "target", "debug", "armlab")
FOLLOW_WITHIN_S = 1.0


def start_server(dist, data, port):
    """`armlab class serve` on `port`; returns (process, teacher URL, students URL)."""
    if not os.path.isfile(ARMLAB):
        print("  building target/debug/armlab (cargo build)")
        subprocess.run(["cargo", "build", "--bin", "armlab"], cwd=ROOT, check=True)
    proc = subprocess.Popen(
        [ARMLAB, "class", "serve", "--port", str(port), "--web", dist, "--data", data],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    lines, deadline = {}, time.time() + 60

    def read():
        for line in proc.stdout:
            key, _, value = line.partition(": ")
            if key in ("teacher", "students") and key not in lines:
                lines[key] = value.strip()

    threading.Thread(target=read, daemon=True).start()
    while len(lines) < 2:
        if proc.poll() is not None:
            fail(f"armlab class serve exited ({proc.returncode}): {proc.stderr.read()[:2000]}")
        if time.time() > deadline:
            proc.kill()
            fail("armlab class serve printed no teacher: and students: lines in 60 s")
        time.sleep(0.05)
    return proc, lines["teacher"], lines["students"]


def class_status(d):
    st = status(d)
    return (st or {}).get("class") or {}


def drag_gizmo(d):
    """A mouse drag on the IK target's gizmo (web/test_page.py's drag, as its check_gizmo_drag)."""
    before = wait_for(d, "the teacher's gizmo", lambda s: s.get("gizmo"), 20)
    x, y = before["gizmo"]
    drag_from(d, x, y)
    return wait_for(d, "the teacher's arm to move after the drag",
                    lambda s: s["q"] != before["q"], 10)


def same_q(a, b):
    return len(a) == len(b) and all(abs(x - y) <= 1e-9 for x, y in zip(a, b))


def check_follow(teacher, students):
    moved = drag_gizmo(teacher)
    # The drag's last frames may still move the arm: the teacher's q once it is steady.
    time.sleep(0.2)
    q = status(teacher)["q"]
    t0 = time.time()
    pending = dict(enumerate(students))
    while pending:
        for i, d in list(pending.items()):
            if same_q(status(d)["q"], q):
                print(f"  student {i + 1} follows: {1000 * (time.time() - t0):.0f} ms")
                del pending[i]
        if time.time() - t0 > FOLLOW_WITHIN_S:
            fail(f"students {sorted(pending)} did not follow within {FOLLOW_WITHIN_S} s: teacher "
                 f"q {q}, theirs {[status(d)['q'] for d in pending.values()]}")
        time.sleep(0.02)
    print(f"  the teacher dragged the target: q {[round(v, 4) for v in moved['q']]}")


def check_poll(teacher, students):
    teacher.js("window.armlab.class_ask_poll()")
    qs = [wait_for(d, "the poll on a student's page",
                   lambda s: ((s.get("class") or {}).get("question") or {}).get("kind") == "poll",
                   10)["class"]["question"] for d in students]
    q = qs[0]
    if len(q["choices"]) < 2:
        fail(f"the poll has choices {q['choices']}")
    choice = len(q["choices"]) - 1
    students[0].js("window.armlab.class_answer(BigInt(arguments[0]), arguments[1])", q["id"],
                   json.dumps(choice))
    st = wait_for(teacher, "the teacher's count of the answer",
                  lambda s: (s.get("class") or {}).get("answered") == 1, 10)["class"]
    print(f"  poll {q['id']} ({len(q['choices'])} postures): answered {st['answered']} of "
          f"{st['joined']}, counts {st['counts']}")
    if st["joined"] != 2 or st["counts"][choice] != 1 or sum(st["counts"]) != 1:
        fail(f"the teacher's tally: {st}")
    wait_for(students[0], "the student's answer received",
             lambda s: (s.get("class") or {}).get("answered") == 1, 10)


def type_keys(d, text):
    """Types `text` key by key into whatever has the page's focus (egui's text field)."""
    actions = []
    for ch in text:
        actions += [{"type": "keyDown", "value": ch}, {"type": "keyUp", "value": ch}]
    d.s("/actions", {"actions": [{"type": "key", "id": "keyboard", "actions": actions}]})
    d.s("/actions", method="DELETE")


def student_names(data):
    with sqlite3.connect(data) as db:
        return [r[0] for r in db.execute("SELECT name FROM students ORDER BY number")]


NICKNAME = "Chen, who types whole sentences"


def check_nickname_prompt(d, students_url, teacher, data):
    d.s("/url", {"url": students_url})
    wait_for(d, "the nickname prompt", lambda s: (s.get("class") or {}).get("prompt"), 30)
    time.sleep(0.3)
    before = status(d)
    type_keys(d, NICKNAME)
    time.sleep(0.3)
    after = status(d)
    # letters of the sentence are shortcuts elsewhere (W, P, H, Space: the next solution)
    for key in ("q", "tab", "solutions"):
        if after[key] != before[key]:
            fail(f"typing the nickname fired a shortcut: {key} {before[key]} -> {after[key]}")
    type_keys(d, "\ue007")
    wait_for(teacher, "the teacher's page to see three students",
             lambda s: (s.get("class") or {}).get("joined") == 3, 20)
    names = student_names(data)
    if NICKNAME not in names:
        fail(f"the typed nickname is not in the data file: {names}")
    print(f"  a student typed the nickname {NICKNAME!r}: {names}")


def check_restart(dist, data, port, proc, teacher, students):
    before = student_names(data)
    proc.terminate()
    proc.wait(20)
    proc, _, _ = start_server(dist, data, port)
    wait_for(teacher, "the teacher's page to reconnect and count the same three students",
             lambda s: (s.get("class") or {}).get("connected")
             and (s.get("class") or {}).get("joined") == 3, 30)
    for d in students:
        wait_for(d, "a student to reconnect", lambda s: (s.get("class") or {}).get("connected"),
                 30)
    after = student_names(data)
    if after != before:
        fail(f"the students after the restart are not the same ones: {before} -> {after}")
    check_follow(teacher, students)
    print(f"  restarted on port {port}: the pages reconnected as the same students")
    return proc


def main():
    if len(sys.argv) != 2:
        fail("usage: web/test_class.py DIST_DIR")
    dist = os.path.abspath(sys.argv[1])
    for f in ("index.html", "armlab.js", "armlab_bg.wasm"):
        if not os.path.isfile(os.path.join(dist, f)):
            fail(f"{dist}/{f} is missing: run web/build.sh first")
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    chromedriver = shutil.which("chromedriver")
    if not chromium or not chromedriver:
        fail("headless Chromium and chromedriver are needed: apt-get install chromium chromium-driver")
    folder = tempfile.mkdtemp(prefix="armlab-class-web-")
    data, port = os.path.join(folder, "class.sqlite"), free_port()
    proc, teacher_url, students_url = start_server(dist, data, port)
    drivers = []
    try:
        print(f"  server: {teacher_url.split('?')[0]}")
        teacher = Driver(chromedriver, chromium)
        drivers.append(teacher)
        students = []
        for name in ("Ada", "Bo"):
            d = Driver(chromedriver, chromium)
            drivers.append(d)
            d.s("/url", {"url": f"{students_url}&name={name}"})
            students.append(d)
        teacher.s("/url", {"url": teacher_url})
        wait_for(teacher, "the teacher's page to see two students",
                 lambda s: (s.get("class") or {}).get("connected")
                 and (s.get("class") or {}).get("joined") == 2, 30)
        for d in students:
            wait_for(d, "a student following", lambda s: (s.get("class") or {}).get("following")
                     and (s.get("class") or {}).get("connected"), 30)
        print("  one teacher and two students joined")
        check_follow(teacher, students)
        check_poll(teacher, students)
        third = Driver(chromedriver, chromium)
        drivers.append(third)
        check_nickname_prompt(third, students_url, teacher, data)
        proc = check_restart(dist, data, port, proc, teacher, students + [third])
        for d in drivers:
            errors = d.js("return window.__errors || []")
            severe = [e for e in d.browser_log() if e.get("level") == "SEVERE"]
            if errors or severe:
                fail(f"console errors: {errors} {severe}")
    finally:
        for d in drivers:
            d.quit()
        proc.terminate()
        try:
            proc.wait(10)
        except subprocess.TimeoutExpired:
            proc.kill()
        shutil.rmtree(folder, ignore_errors=True)
    print("web class test passed")


if __name__ == "__main__":
    main()
