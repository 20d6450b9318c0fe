#!/usr/bin/env python3
"""ReportHtmlInChromium: the report.html of a real spire-tune run, opened in
headless Chromium (Debian's `chromium`, which scripts/install-deps.sh
installs).

Usage: report_html_chromium.py SPIRE_TUNE
Run from the repository root (CTest does). Exits 0 when every check holds,
1 with the reasons otherwise; a missing `chromium` is a failure, not a skip.
The run and the screenshots are kept in the temporary directory it names
when a check fails, or always with REPORT_HTML_KEEP=1 in the environment.

spire-tune tunes examples/scenes/terrain.json (shader Terrain, albedo x
lighting: 12 variants, one job, 64-texel bakes, 3 pairs of frames each) into
a temporary directory, then:

1. report.html parses as XML (the page closes every element and writes only
   the five predefined entities), names no http:// or https:// address and no
   script, and every href and src is a relative path to a file of the run.
2. Chromium's DOM (--dump-dom) has one <circle> per plotted variant of
   variants.csv (status ok, finite RMSE, no NaN or Inf pixels) and one
   front point per row of pareto.csv.
3. The page logs nothing to the console. With --enable-logging=stderr
   Chromium writes every console message of a page, uncaught exceptions
   included ("Uncaught ReferenceError: ..."), to stderr as
     [...:INFO:CONSOLE:LINE] "MESSAGE", source: URL (LINE)
   whatever its level. The page has no script, so any such line whose
   source is the page fails the test. A canary page with a deliberate error
   is loaded first: if its error is not seen, this Chromium reports in
   another way and the test fails rather than passing blind.
4. The screenshot is not blank: many colours, and the front's red or
   orange (#d2281e, #e08a00: its line, circles and error bars) present.
5. Hovering shows the image: a copy of the page that shows only the plot,
   with one front point's panel forced visible (the :hover rule as a plain
   rule), has the variant's image in the panel (many colours there, against
   a few for the same panel without it).
"""

import csv
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
import zlib

CHROMIUM_TIMEOUT_S = 120
TUNE_TIMEOUT_S = 240
# The front's colours (engine-demo/tune/report_html.cpp): red, and orange for
# points within the noise; on a busy machine every front point may be orange.
FRONT_COLOURS = {(0xD2, 0x28, 0x1E), (0xE0, 0x8A, 0x00)}
# CSS pixels of the plot-only copy: the body's margin and the hover panel's
# box inside the SVG (engine-demo/tune/report_html.cpp).
MARGIN = 24
PANEL = (700, 20, 970, 500)

failures = []


def fail(message):
    failures.append(message)
    print(f"FAIL: {message}", file=sys.stderr)


def chromium_binary():
    for name in ("chromium", "chromium-browser"):
        path = shutil.which(name)
        if path:
            return path
    return None


def run_chromium(chromium, profile, url, extra, capture_stdout=False):
    """Runs headless Chromium on `url`; returns (stdout, stderr)."""
    args = [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
            "--disable-background-networking", "--disable-component-update", "--disable-sync",
            "--force-device-scale-factor=1", f"--user-data-dir={profile}", "--enable-logging=stderr", "--v=0"]
    result = subprocess.run(args + extra + [url], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            timeout=CHROMIUM_TIMEOUT_S, text=True, errors="replace")
    if result.returncode != 0:
        fail(f"chromium exited with {result.returncode} on {url}:\n{result.stderr[-4000:]}")
    return result.stdout, result.stderr


def console_lines(stderr, url):
    """The console messages Chromium logged for the page at `url`."""
    return [line for line in stderr.splitlines() if ":CONSOLE" in line and f"source: {url}" in line]


def read_png(path):
    """(width, height, rows of (r, g, b) tuples) of an 8-bit RGB or RGBA PNG."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path} is not a PNG")
    pos, idat = 8, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    if depth != 8 or color not in (2, 6) or interlace != 0:
        raise ValueError(f"{path}: depth {depth}, colour type {color}, interlace {interlace} not read here")
    channels = 3 if color == 2 else 4
    stride = width * channels
    raw = zlib.decompress(idat)
    previous = bytearray(stride)
    rows = []
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        unfilter(kind, line, previous, channels)
        rows.append([tuple(line[x:x + 3]) for x in range(0, stride, channels)])
        previous = line
    return width, height, rows


def unfilter(kind, line, previous, bpp):
    if kind == 1:
        for i in range(bpp, len(line)):
            line[i] = (line[i] + line[i - bpp]) & 0xFF
    elif kind == 2:
        for i in range(len(line)):
            line[i] = (line[i] + previous[i]) & 0xFF
    elif kind == 3:
        for i in range(len(line)):
            left = line[i - bpp] if i >= bpp else 0
            line[i] = (line[i] + (left + previous[i]) // 2) & 0xFF
    elif kind == 4:
        for i in range(len(line)):
            a = line[i - bpp] if i >= bpp else 0
            b = previous[i]
            c = previous[i - bpp] if i >= bpp else 0
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            predictor = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
            line[i] = (line[i] + predictor) & 0xFF
    elif kind != 0:
        raise ValueError(f"PNG filter {kind}")


def colours(rows, box=None):
    x0, y0, x1, y1 = box if box else (0, 0, len(rows[0]), len(rows))
    return {pixel for row in rows[y0:y1] for pixel in row[x0:x1]}


def run_tune(spire_tune, out_dir):
    command = [spire_tune, "examples/scenes/terrain.json", "--shader", "Terrain", "--components", "albedo,lighting",
               "--jobs", "1", "--bake-size", "64", "--max-frames", "3", "-o", out_dir]
    env = dict(os.environ, ASAN_OPTIONS="detect_leaks=0")
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env,
                            timeout=TUNE_TIMEOUT_S)
    if result.returncode != 0:
        fail(f"spire-tune exited with {result.returncode}:\n{result.stderr[-4000:]}")
        return False
    return True


def plotted_and_front(out_dir):
    """The number of variants the plot shows, and of front points, from the CSVs."""
    with open(os.path.join(out_dir, "variants.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    plotted = [r for r in rows if r["status"] == "ok" and math.isfinite(float(r["rmse"])) and
               int(r["nan_pixels"]) + int(r["inf_pixels"]) == 0]
    with open(os.path.join(out_dir, "pareto.csv"), newline="") as f:
        front = list(csv.DictReader(f))
    return len(plotted), len(front)


def check_source(out_dir, text):
    """Check 1; returns the id of a front point with an image, for check 5."""
    try:
        root = ET.fromstring(text)
    except ET.ParseError as error:
        fail(f"report.html is not well-formed: {error}")
        return None
    for banned in ("http://", "https://", "<script"):
        if banned in text:
            fail(f"report.html contains {banned!r}")
    for element in root.iter():
        for attribute in ("href", "src"):
            target = element.get(attribute)
            if target is None or target.startswith("#"):
                continue
            if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("/"):
                fail(f"report.html refers to {target!r}, outside the output directory")
            elif not os.path.isfile(os.path.join(out_dir, target)):
                fail(f"report.html refers to {target!r}, which the run did not write")
    for group in root.iter("g"):
        if "front" in (group.get("class") or "").split() and any(True for _ in group.iter("image")):
            return group.get("id")
    fail("no front point of the plot has an image")
    return None


def check_canary(chromium, work):
    """Check 3's premise: a page's uncaught error reaches Chromium's log."""
    canary = os.path.join(work, "canary.html")
    with open(canary, "w") as f:
        f.write("<!DOCTYPE html><html><body><p>canary</p><script>noSuchFunction();</script></body></html>\n")
    url = "file://" + canary
    _, stderr = run_chromium(chromium, os.path.join(work, "profile-canary"), url, ["--dump-dom"])
    if not any("Uncaught ReferenceError" in line for line in console_lines(stderr, url)):
        fail("the canary page's uncaught error is not in Chromium's log: this Chromium does not report console "
             f"messages as 'INFO:CONSOLE ... source: URL'; the console check cannot work:\n{stderr[-4000:]}")


def check_page(chromium, work, out_dir):
    """Checks 2, 3 and 4 on the page as the run wrote it."""
    url = "file://" + os.path.join(out_dir, "report.html")
    dom, stderr = run_chromium(chromium, os.path.join(work, "profile-dom"), url, ["--dump-dom"])
    plotted, front = plotted_and_front(out_dir)
    circles = len(re.findall(r"<circle\b", dom))
    front_points = len(re.findall(r'<g class="pt front', dom))
    if circles != plotted or front_points != front:
        fail(f"the rendered DOM has {circles} circles and {front_points} front points; variants.csv has "
             f"{plotted} plotted variants, pareto.csv {front} front points")
    shot = os.path.join(work, "report.png")
    _, shot_log = run_chromium(chromium, os.path.join(work, "profile-shot"), url,
                               [f"--screenshot={shot}", "--window-size=1200,900"])
    for line in console_lines(stderr + shot_log, url):
        fail(f"the page logged to the console: {line}")
    if not os.path.isfile(shot):
        fail("chromium wrote no screenshot")
        return
    _, _, rows = read_png(shot)
    found = colours(rows)
    print(f"screenshot {shot}: {len(found)} colours")
    if len(found) < 50 or not FRONT_COLOURS & found:
        fail(f"the screenshot looks blank: {len(found)} colours, the front's colours present: "
             f"{sorted(FRONT_COLOURS & found)}")


def hover_copy(out_dir, point, name):
    """A copy of report.html beside it that shows only the plot, with `point`'s
    panel shown as if hovered (none when `point` is None)."""
    with open(os.path.join(out_dir, "report.html")) as f:
        text = f.read()
    style = "body > :not(svg) { display: none; }"
    if point:
        style += f" #{point} .tip {{ display: inline; }}"
    path = os.path.join(out_dir, name)
    with open(path, "w") as f:
        f.write(text.replace("</head>", f"<style>{style}</style>\n</head>", 1))
    return path


def check_hover(chromium, work, out_dir, point):
    """Check 5: the panel of a hovered front point holds its image."""
    counts = {}
    for name, shown in (("plain", None), ("hovered", point)):
        page = hover_copy(out_dir, shown, f"report-{name}.html")
        shot = os.path.join(work, f"{name}.png")
        run_chromium(chromium, os.path.join(work, f"profile-{name}"), "file://" + page,
                     [f"--screenshot={shot}", "--window-size=1040,620"])
        if not os.path.isfile(shot):
            fail(f"chromium wrote no screenshot of the {name} plot")
            return
        _, _, rows = read_png(shot)
        box = (MARGIN + PANEL[0], MARGIN + PANEL[1], MARGIN + PANEL[2], MARGIN + PANEL[3])
        counts[name] = len(colours(rows, box))
    print(f"hover panel of {point}: {counts['hovered']} colours, {counts['plain']} without hover")
    if counts["hovered"] < 200 or counts["hovered"] < 4 * counts["plain"]:
        fail(f"the hover panel of {point} shows no image: {counts['hovered']} colours against {counts['plain']} "
             "without it")


def main(argv):
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    chromium = chromium_binary()
    if not chromium:
        print("FAIL: chromium is not installed; scripts/install-deps.sh installs Debian's chromium package "
              "(apt-get install chromium)", file=sys.stderr)
        return 1
    work = tempfile.mkdtemp(prefix="spire_report_html_")
    out_dir = os.path.join(work, "tune")
    if run_tune(os.path.abspath(argv[1]), out_dir):
        with open(os.path.join(out_dir, "report.html"), encoding="utf-8") as f:
            point = check_source(out_dir, f.read())
        check_canary(chromium, work)
        check_page(chromium, work, out_dir)
        if point:
            check_hover(chromium, work, out_dir, point)
    if failures:
        print(f"{len(failures)} check(s) failed; the run and screenshots are kept in {work}", file=sys.stderr)
        return 1
    if os.environ.get("REPORT_HTML_KEEP"):
        print(f"kept {work} (REPORT_HTML_KEEP)")
    else:
        shutil.rmtree(work, ignore_errors=True)
    print("report.html: well-formed, self-contained, rendered by Chromium without console messages")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
