#!/usr/bin/python3
"""polysim view in headless Chromium (issue 17): what the page draws is what the log says.

    /usr/bin/python3 tests/sim/view_test.py build/sim/polysim scenes

For the drop and the 5-box stack, the page is loaded at two times (#t=...). Checked: no
JavaScript error; the canvas is not blank; the state the page exposes (#test-state) holds
the log's poses at those times; the bodies' pixels move between the two screenshots by
the on-screen displacement of the logged positions; at rest the drawn contact is the
box's bottom square. A log cut short mid-line is shown to its last whole step with a
warning; a log of another scene gets one message and no page. The side-by-side page of `polysim compare --log-dir` shows both engines' logs.
Needs chromium and python3-matplotlib (to read the screenshots); exits 77 (skipped)
without chromium.
"""

import html
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

import matplotlib.image
import numpy as np

POLYSIM, SCENES = sys.argv[1], sys.argv[2]
CHROMIUM = ["chromium", "--headless=new", "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
            "--window-size=900,700", "--hide-scrollbars", "--virtual-time-budget=8000"]
VIEW_SIZE = "420x360"  # px: fixed, so that the screenshot and the DOM dump (whose windows differ) lay out alike
FAILURES = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        FAILURES.append(what)


def polysim(*args, ok=True):
    run = subprocess.run([POLYSIM, *args], capture_output=True, text=True)
    if ok and run.returncode != 0:
        sys.exit(f"polysim {' '.join(args)} failed: {run.stderr}")
    return run


def page_state(page, t, contacts=True, click=None):
    url = f"file://{page}#t={t}&contacts={int(contacts)}&size={VIEW_SIZE}" + (f"&click={click[0]},{click[1]}" if click else "")
    dom = subprocess.run(CHROMIUM + ["--dump-dom", url], capture_output=True, text=True, check=True).stdout
    found = re.search(r'<pre id="test-state"[^>]*>(.*?)</pre>', dom, re.S)
    if not found or not found.group(1):
        sys.exit(f"{url}: the page wrote no test state (it did not run)")
    return json.loads(html.unescape(found.group(1)))


def screenshot(page, t, png, contacts=False):
    url = f"file://{page}#t={t}&contacts={int(contacts)}&size={VIEW_SIZE}"
    subprocess.run(CHROMIUM + [f"--screenshot={png}", url], capture_output=True, check=True)
    return matplotlib.image.imread(png)[:, :, :3]


def coloured(image, canvas):
    """Pixels of the dynamic bodies: saturated colours (the ground is grey, the sky dark)
    inside the view's canvas (left, top, width, height; the plot below has colours too)."""
    spread = image.max(axis=2) - image.min(axis=2)
    mask = (spread > 0.3) & (image.max(axis=2) > 0.45)
    left, top, width, height = (int(round(v)) for v in canvas)
    inside = np.zeros_like(mask)
    inside[top:top + height, left:left + width] = True
    return mask & inside


def cyan(image):  # the contacts' colour, #35e0ff
    r, g, b = image[:, :, 0], image[:, :, 1], image[:, :, 2]
    return (r < 0.45) & (g > 0.7) & (b > 0.85)


def log_lines(path):
    with open(path) as f:
        return [json.loads(line) for line in f]


def line_at(lines, t):
    return max((l for l in lines if l["t"] <= t + 1e-9), key=lambda l: l["t"])


def poses_match(state_run, line):
    logged = {b["name"]: b["position"] for b in line["bodies"]}
    return all(np.allclose(b["position"], logged[b["name"]], rtol=1e-6, atol=1e-6) for b in state_run["bodies"])


def rotation(q):
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def box_corners(size):
    return [np.array([sx, sy, sz]) * np.array(size) / 2 for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]


def logged_body(line, name):
    return next(b for b in line["bodies"] if b["name"] == name)


def bottom_square(line, name):
    body = logged_body(line, name)
    return [rotation(body["orientation"]) @ c + np.array(body["position"]) for c in box_corners([1, 1, 1]) if c[2] < 0]


def projected_box(state, scene, line):
    """The screen box (left, top, right, bottom, px) of every dynamic box's corners at the
    logged poses, through the page's camera: for convex bodies, their silhouettes' box."""
    M = np.array(state["viewProjection"]).reshape(4, 4).T  # three.js stores matrices column-major
    left, top, width, height = state["runs"][0]["canvas"]
    points = []
    for body in scene["bodies"]:
        if body.get("static"):
            continue
        logged = logged_body(line, body["name"])
        for corner in box_corners(body["shape"]["size"]):
            x, y, z, w = M @ np.append(rotation(logged["orientation"]) @ corner + np.array(logged["position"]), 1.0)
            points.append((left + (x / w + 1) / 2 * width, top + (1 - y / w) / 2 * height))
    points = np.array(points)
    return np.array([*points.min(axis=0), *points.max(axis=0)])


def same_points(a, b, tol):
    return len(a) == len(b) and all(min(np.linalg.norm(np.array(p) - q) for q in b) < tol for p in a)


def moves_as_logged(page, log, scene_path, t0, t1, work, label):
    """Screenshots at t0 and t1: the bodies are drawn where their logged poses project."""
    lines = log_lines(log)
    with open(scene_path) as f:
        scene = json.load(f)
    states = [page_state(page, t, contacts=False) for t in (t0, t1)]
    images = [screenshot(page, t, os.path.join(work, f"{label}_{i}.png")) for i, t in enumerate((t0, t1))]
    for t, state, image in zip((t0, t1), states, images):
        check(state["errors"] == [], f"{label} t={t}: no JavaScript error ({state['errors']})")
        run = state["runs"][0]
        check(abs(run["time"] - line_at(lines, t)["t"]) < 1e-9, f"{label} t={t}: the page shows the logged step at or before t")
        check(poses_match(run, line_at(lines, t)), f"{label} t={t}: the page's poses are the log's")
        bodies = coloured(image, run["canvas"]).sum()
        check(bodies > 500 and image.std() > 0.05, f"{label} t={t}: the canvas is not blank ({bodies} body pixels)")
    # A convex body's silhouette spans the screen box of its corners: the drawn pixels
    # must fill the union of those boxes, edge for edge, at both times.
    for t, state, image in zip((t0, t1), states, images):
        expected = projected_box(state, scene, line_at(lines, t))
        ys, xs = np.nonzero(coloured(image, state["runs"][0]["canvas"]))
        drawn = np.array([xs.min(), ys.min(), xs.max() + 1, ys.max() + 1])
        check(np.abs(drawn - expected).max() <= 3,
              f"{label} t={t}: bodies drawn over {drawn} px, where the logged poses project to {expected.round(1)}")
    return states, images


def main():
    if shutil.which("chromium") is None:
        print("chromium is not installed (apt-get install chromium): skipped")
        return 77
    work = tempfile.mkdtemp(prefix="polysim_view_test_")

    # The drop: falling at 0.3 s, at rest at 2.9 s.
    drop_log = os.path.join(work, "drop.jsonl")
    polysim("run", os.path.join(SCENES, "drop_box.json"), "--log", drop_log, "--log-contacts")
    started = time.time()
    made = json.loads(polysim("view", drop_log).stdout)
    page = made["page"]
    check(os.path.isfile(page) and made["bytes"] == os.path.getsize(page), f"view wrote {page} ({made['bytes']} bytes)")
    with open(page) as f:
        fetches = re.findall(r"<(?:script|link|img|iframe)[^>]*\b(?:src|href)=", f.read())
    check(not fetches, f"the page fetches nothing: three.js and the data are inlined ({fetches})")
    states, _ = moves_as_logged(page, drop_log, os.path.join(SCENES, "drop_box.json"), 0.3, 2.9, work, "drop")
    print(f"      (page written and checked in {time.time() - started:.1f} s)")
    check(np.linalg.norm(np.array(states[1]["runs"][0]["bodies"][0]["screen"]) - states[0]["runs"][0]["bodies"][0]["screen"]) > 20,
          "drop: the box moves on screen by more than 20 px")
    rest = page_state(page, 2.9)
    pairs = rest["runs"][0]["contacts"]
    square = bottom_square(line_at(log_lines(drop_log), 2.9), "box")
    check(len(pairs) == 1 and pairs[0]["b"] == "ground" and pairs[0]["contacts"][0]["type"] == "area"
          and same_points(pairs[0]["contacts"][0]["points"], square, 1e-6),
          "drop at rest: the contact drawn is the box's bottom square")
    check(rest["runs"][0]["drawnContactObjects"] >= 4, "drop at rest: area, outline, points and normal are drawn")
    box_at = rest["runs"][0]["bodies"][0]["screen"]
    clicked = page_state(page, 2.9, click=box_at)["info"]
    position = ", ".join(f"{x:.5f}" for x in line_at(log_lines(drop_log), 2.9)["bodies"][0]["position"])
    check(clicked.startswith("box (drop, t = 2.9000 s)") and f"position [{position}]" in clicked,
          f"a click on the box shows its name and logged pose: {clicked!r}")
    ground = page_state(page, 2.9, click=(rest["runs"][0]["canvas"][0] + 5, box_at[1] + 100))["info"]
    check(ground.startswith("ground (static)"), f"a click on the floor names the floor: {ground!r}")
    with_contacts = screenshot(page, 2.9, os.path.join(work, "drop_contacts.png"), contacts=True)
    check(cyan(with_contacts).sum() > 50, f"drop at rest: the contact shows on screen ({cyan(with_contacts).sum()} px)")

    # The 5-box stack stands: drawn where the log has it at 1 s and at 3 s.
    stack_log = os.path.join(work, "stack.jsonl")
    polysim("run", os.path.join(SCENES, "stack_5.json"), "--log", stack_log, "--duration", "3")
    stack_page = json.loads(polysim("view", stack_log, "--out", os.path.join(work, "stack.html")).stdout)["page"]
    moves_as_logged(stack_page, stack_log, os.path.join(SCENES, "stack_5.json"), 1.0, 3.0, work, "stack")

    # A box dropped tilted, landing on a corner: its silhouette checks the drawn orientation.
    tilted_log = os.path.join(work, "tilted.jsonl")
    polysim("run", os.path.join(SCENES, "tilted_drop.json"), "--log", tilted_log)
    tilted_page = json.loads(polysim("view", tilted_log, "--out", os.path.join(work, "tilted.html")).stdout)["page"]
    moves_as_logged(tilted_page, tilted_log, os.path.join(SCENES, "tilted_drop.json"), 0.2, 0.75, work, "tilted")

    # A log cut short mid-line (a run killed while writing): shown to its last whole step,
    # with a warning naming the line. A log of another scene: one message, no page.
    cut = os.path.join(work, "cut.jsonl")
    with open(drop_log) as f, open(cut, "w") as g:
        text = f.read()
        g.write(text[: len(text) // 2])
    whole_lines = text[: len(text) // 2].count("\n")
    shown = json.loads(polysim("view", cut, "--out", os.path.join(work, "cut.html")).stdout)
    check(len(shown.get("warnings", [])) == 1 and f"line {whole_lines + 1}: cut short" in shown["warnings"][0]
          and os.path.exists(os.path.join(work, "cut.html")), f"a log cut mid-line: {shown}")
    other = polysim("view", drop_log, "--scene", os.path.join(SCENES, "stack_5.json"), "--out", os.path.join(work, "x.html"), ok=False)
    check(other.returncode == 1 and "box" in other.stderr and "stack_5.json" in other.stderr
          and not os.path.exists(os.path.join(work, "x.html")), f"a log of another scene: {other.stderr.strip()}")

    # polysim and ODE side by side on one clock.
    both = os.path.join(work, "both")
    os.mkdir(both)
    polysim("compare", os.path.join(SCENES, "drop_box.json"), "--log-dir", both)
    side = json.loads(polysim("view", os.path.join(both, "polysim.jsonl"), os.path.join(both, "ode.jsonl")).stdout)["page"]
    state = page_state(side, 0.5)
    labels = [r["label"] for r in state["runs"]]
    check(state["errors"] == [] and labels == ["polysim", "ode"], f"compare --log-dir: both logs on one page ({labels})")
    check(all(poses_match(r, line_at(log_lines(os.path.join(both, r["label"] + ".jsonl")), 0.5)) for r in state["runs"]),
          "compare --log-dir: each view shows its own engine's poses at the same time")

    shutil.rmtree(work)
    print(f"{len(FAILURES)} failed" if FAILURES else "all passed")
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main())
