#!/usr/bin/env python3
"""The page of `coons view` in a real browser: headless Chromium driven through the DevTools
protocol over --remote-debugging-pipe (standard library only).

    view_browser_check.py COONS BOUNDARY WORKDIR [--keep-screenshots DIR | --expect-error]
                          [--expect-parameters alpha,weight] [--expect-view fixed|turned]

Writes WORKDIR/page.html with `coons view`, opens it at #alpha=-0.2013 (between the precomputed
values) and checks: no console error, no exception and no data-error attribute; data-ready="1";
data-alpha is -0.2013 and the net shown is that of `coons solve --alpha -0.2013` (1e-9) on the
file's outer ring (the problem of the α slider: ribbons, rings and free left out) when the
page solves the α family itself (coonsView.exact), else the nearest precomputed value; the screenshot of the 3D view is not blank (many colours, a part neither white nor
one colour); moving the slider through window.coonsView.setAlpha changes data-alpha, the drawn net
(data-net-hash) and the picture; moving it back gives the first net again; every other slider
(setValue: the C1 weight) changes its data attribute and the drawn net, and a weight between the
frames shows the net of `coons solve --mask c1-family --weight w` of the whole file (1e-9); every
slider the page solves itself (a triangle's c, a B-spline boundary's α, the weight) gives, solved
and sampled by the page at each frame's value, that frame's net and samples to 1e-4 of the largest
coordinate and its normals to 1e-3 (coonsView.selfCheck); the only request the page
makes is the page itself (nothing fetched). Exit 77 (skipped) when
chromium is not installed or coons was built without three.js. With --expect-error a failing
script is added to the page and the check must see its error (the check's own test). With
--expect-parameters the page's sliders (coonsView.parameters()) must be exactly those, in order
(so that a page that lost its C1 weight slider fails instead of checking no other slider). With
--expect-view the page's camera (data-view: "fixed", the usual direction, or "turned" about the
vertical to face a surface it would see edge on) must be that one."""
import base64
import json
import os
import select
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import zlib

SKIP = 77
# the options of `coons solve` that give the net of a value of the other sliders (the value follows)
SOLVE_OPTIONS = {"weight": ["--mask", "c1-family", "--weight"]}
TARGET = -0.2013  # the α the page is opened at: between the precomputed values


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def decode_png(data):
    """(width, height, rows of RGB(A) bytes) of an 8-bit RGB or RGBA PNG."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        fail("the screenshot is not a PNG")
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            if depth != 8 or colour not in (2, 6):
                fail("unexpected PNG format (depth %d, colour type %d)" % (depth, colour))
            bpp = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = width * bpp
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b = previous[x]
            c = previous[x - bpp] if x >= bpp else 0
            if kind == 1:
                line[x] = (line[x] + a) & 255
            elif kind == 2:
                line[x] = (line[x] + b) & 255
            elif kind == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        previous = line
    return width, height, bpp, rows


def pixel_stats(png):
    width, height, bpp, rows = decode_png(png)
    colours, non_white = set(), 0
    for row in rows:
        for x in range(0, width * bpp, bpp):
            rgb = row[x:x + 3]
            colours.add(rgb)
            if rgb != b"\xff\xff\xff":
                non_white += 1
    return len(colours), non_white / float(width * height), rows


class Browser:
    def __init__(self, chromium, profile):
        to_child_r, self.to_child = os.pipe()
        self.from_child, from_child_w = os.pipe()

        def setup_fds():  # the pipe ends become the child's fds 3 (commands) and 4 (answers)
            a, b = os.dup(to_child_r), os.dup(from_child_w)
            os.dup2(a, 3)
            os.dup2(b, 4)

        args = [chromium, "--headless=new", "--no-sandbox", "--disable-gpu", "--use-angle=swiftshader",
                "--enable-unsafe-swiftshader", "--remote-debugging-pipe", "--user-data-dir=" + profile,
                "--window-size=1200,800", "--no-first-run", "--no-default-browser-check", "about:blank"]
        self.process = subprocess.Popen(args, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                        stderr=subprocess.DEVNULL, preexec_fn=setup_fds, pass_fds=(3, 4))
        os.close(to_child_r)
        os.close(from_child_w)
        self.buffer, self.next_id, self.events = b"", 0, []

    def send(self, method, params=None, session=None, timeout=60):
        self.next_id += 1
        message = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            message["sessionId"] = session
        os.write(self.to_child, json.dumps(message).encode() + b"\0")
        deadline = time.time() + timeout
        while True:
            for reply in self.read(deadline):
                if reply.get("id") == self.next_id:
                    if "error" in reply:
                        fail("%s: %s" % (method, reply["error"]))
                    return reply.get("result", {})
                self.events.append(reply)

    def read(self, deadline):
        while b"\0" not in self.buffer:
            left = deadline - time.time()
            if left <= 0 or not select.select([self.from_child], [], [], left)[0]:
                fail("chromium did not answer in time")
            chunk = os.read(self.from_child, 1 << 20)
            if not chunk:
                fail("chromium closed the pipe")
            self.buffer += chunk
        messages = []
        while b"\0" in self.buffer:
            text, self.buffer = self.buffer.split(b"\0", 1)
            messages.append(json.loads(text))
        return messages

    def close(self):
        try:
            os.write(self.to_child, json.dumps({"id": 0, "method": "Browser.close"}).encode() + b"\0")
            self.process.wait(timeout=10)
        except Exception:  # noqa: BLE001 - a browser that does not close is killed
            self.process.kill()
            self.process.wait()


def main():
    if len(sys.argv) < 4:
        print(__doc__)
        return 2
    coons, boundary, work = sys.argv[1], sys.argv[2], sys.argv[3]
    options = sys.argv[4:]
    keep = options[options.index("--keep-screenshots") + 1] if "--keep-screenshots" in options else None
    expect_error = "--expect-error" in options
    expected_parameters = (options[options.index("--expect-parameters") + 1].split(",")
                           if "--expect-parameters" in options else None)
    expected_view = options[options.index("--expect-view") + 1] if "--expect-view" in options else None
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    if not chromium:
        print("skipped: chromium not found (apt-get install chromium)")
        return SKIP
    os.makedirs(work, exist_ok=True)
    page = os.path.join(work, "page.html")
    made = subprocess.run([coons, "view", boundary, "--out", page, "--force", "--alphas", "51"],
                          capture_output=True, text=True)
    if made.returncode != 0:
        if "libjs-three" in made.stderr:
            print("skipped: coons was built without three.js (apt-get install libjs-three): " + made.stderr.strip())
            return SKIP
        fail("coons view exited %d: %s" % (made.returncode, made.stderr))
    if expect_error:
        with open(page, encoding="utf-8") as f:
            text = f.read()
        with open(page, "w", encoding="utf-8") as f:
            f.write(text.replace("</body>", "<script>coonsViewNoSuchFunction();</script>\n</body>"))

    profile = tempfile.mkdtemp(prefix="coons-view-chromium-")
    browser = Browser(chromium, profile)
    try:
        targets = browser.send("Target.getTargets")["targetInfos"]
        target = next(t for t in targets if t["type"] == "page")
        session = browser.send("Target.attachToTarget", {"targetId": target["targetId"], "flatten": True})["sessionId"]
        for domain in ("Runtime.enable", "Log.enable", "Page.enable", "Network.enable"):
            browser.send(domain, session=session)
        browser.send("Page.navigate", {"url": "file://" + os.path.abspath(page) + "#alpha=%r" % TARGET}, session=session)

        def evaluate(expression):
            result = browser.send("Runtime.evaluate", {"expression": expression, "returnByValue": True},
                                  session=session)
            if "exceptionDetails" in result:
                fail("%s threw: %s" % (expression, result["exceptionDetails"]))
            return result["result"].get("value")

        def check_shown_net(solved, parameter, value):
            """The net the page shows is `solved` (a report's "net": rows of points, or a triangle's
            list of points) to 1e-9 of its largest coordinate."""
            reference = [x for point in solved for x in point] if not isinstance(solved[0][0], list) else \
                [x for row in solved for point in row for x in point]
            shown_net = evaluate("window.coonsView.net()")
            scale = max(abs(x) for x in reference)
            worst = max(abs(a - b) for a, b in zip(shown_net, reference))
            print("exact %s=%r: net of the page vs coons solve: max difference %.3g (scale %.3g)" %
                  (parameter, value, worst, scale))
            if len(shown_net) != len(reference) or worst > 1e-9 * scale:
                fail("the page's net at %s=%r differs from coons solve by %g" % (parameter, value, worst))

        def body(attribute):
            return evaluate("document.body ? document.body.getAttribute('%s') : null" % attribute)

        def page_errors():
            errors = [body("data-error")] if body("data-error") else []
            for event in browser.events:
                method, params = event.get("method"), event.get("params", {})
                if method == "Runtime.exceptionThrown":
                    errors.append(json.dumps(params.get("exceptionDetails", {}))[:300])
                elif method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert"):
                    errors.append(json.dumps(params.get("args", []))[:300])
                elif method == "Log.entryAdded" and params.get("entry", {}).get("level") == "error":
                    errors.append(params["entry"].get("text", "")[:300])
            return errors

        deadline = time.time() + 90
        while body("data-ready") != "1":
            if time.time() > deadline:
                fail("data-ready never became 1 (data-error: %s)" % body("data-error"))
            time.sleep(0.2)

        def screenshot(name):
            rect = evaluate("(function(){var r=document.getElementById('surface').getBoundingClientRect();"
                            "return [r.left, r.top, r.width, r.height];})()")
            shot = browser.send("Page.captureScreenshot", {"format": "png", "clip": {
                "x": rect[0], "y": rect[1], "width": rect[2], "height": rect[3], "scale": 1}}, session=session)
            png = base64.b64decode(shot["data"])
            with open(os.path.join(work, name), "wb") as f:
                f.write(png)
            if keep:
                os.makedirs(keep, exist_ok=True)
                with open(os.path.join(keep, name), "wb") as f:
                    f.write(png)
            return png

        values = evaluate("window.coonsView.values('alpha')")
        exact = evaluate("window.coonsView.exact('alpha')")
        # a page that solves the α family itself shows α = TARGET exactly (the contract), and the
        # net of `coons solve --alpha TARGET`; the others the nearest precomputed value
        expected = TARGET if exact else min(values, key=lambda v: abs(v - TARGET))
        alpha = float(body("data-alpha"))
        if alpha != expected:
            fail("#alpha=%r opened at data-alpha=%r, not %r" % (TARGET, alpha, expected))
        if exact:
            if TARGET in values:
                fail("%r is a precomputed value: the check would not test the page's own solve" % TARGET)
            # the α slider solves the α family on the file's outer ring (alpha_view_slider of its
            # sides); `coons solve` takes every data ring (ribbons, rings, free): it is given the
            # file without them, the same one-ring problem the page solves
            with open(boundary, encoding="utf-8") as f:
                doc = json.load(f)
            outer = boundary
            if any(key in doc for key in ("ribbons", "rings", "free")):
                for key in ("ribbons", "rings", "free"):
                    doc.pop(key, None)
                outer = os.path.join(work, "outer-ring.json")
                with open(outer, "w", encoding="utf-8") as f:
                    json.dump(doc, f)
            report = json.loads(subprocess.run([coons, "solve", outer, "--alpha", repr(TARGET)], check=True,
                                               capture_output=True, text=True).stdout)
            if report.get("rings", 1) != 1:
                fail("coons solve of %s solved %r data rings, not the outer one" % (outer, report["rings"]))
            check_shown_net(report["net"], "alpha", TARGET)
            # a value within rounding of a precomputed one (0.1 beside the frame 0.09999999999999998)
            # is shown as itself, not as that frame
            near = [float(repr(round(v, 12))) for v in values]
            near = [(v, w) for v, w in zip(values, near) if w != v]
            if near:
                frame_value, asked = near[0]
                shown = evaluate("window.coonsView.setValue('alpha', %r)" % asked)
                print("near a frame: asked alpha=%r (frame %r), shown %r, data-alpha=%s" %
                      (asked, frame_value, shown, body("data-alpha")))
                if shown != asked or float(body("data-alpha")) != asked:
                    fail("alpha=%r, within rounding of the frame %r, showed %r" % (asked, frame_value, shown))
                evaluate("window.coonsView.setValue('alpha', %r)" % TARGET)
        first_hash = body("data-net-hash")
        png1 = screenshot("view-alpha-start.png")
        colours, coverage, rows1 = pixel_stats(png1)
        print("start: alpha=%r mu=%s net-hash=%s view=%s colours=%d non-white=%.3f" %
              (alpha, body("data-mu"), first_hash, body("data-view"), colours, coverage))
        if colours < 64 or coverage < 0.05:
            fail("the 3D view looks blank (%d colours, %.1f%% not white)" % (colours, 100 * coverage))
        view = (body("data-view") or "").split()
        if expected_view is not None and (not view or view[0] != expected_view):
            fail("the camera is %r, expected %r" % (body("data-view"), expected_view))

        mu = body("data-mu")
        if mu is not None and not float(mu) > 0:
            fail("data-mu=%r at alpha=%r is not a positive number" % (mu, alpha))
        # 0.1, or three quarters along the slider when it ends below (a B-spline boundary's U)
        moved = 0.1 if max(values) >= 0.1 else values[(3 * len(values)) // 4]
        shown = evaluate("window.coonsView.setAlpha(%r)" % moved)
        if moved > 0 and body("data-mu") is not None:
            fail("data-mu=%r at alpha=%r, which has no mu" % (body("data-mu"), moved))
        second_alpha, second_hash = float(body("data-alpha")), body("data-net-hash")
        png2 = screenshot("view-alpha-moved.png")
        _, _, rows2 = pixel_stats(png2)
        changed = sum(1 for a, b in zip(rows1, rows2) if a != b)
        print("moved: alpha=%r net-hash=%s rows changed=%d" % (second_alpha, second_hash, changed))
        if abs(second_alpha - moved) > 0.006 or shown != second_alpha:
            fail("setAlpha(%r) shows data-alpha=%r (returned %r)" % (moved, second_alpha, shown))
        if second_hash == first_hash:
            fail("the drawn net did not change when alpha moved (data-net-hash %s)" % first_hash)
        if changed == 0:
            fail("the picture did not change when alpha moved")
        evaluate("window.coonsView.setAlpha(%r)" % expected)
        if body("data-net-hash") != first_hash:
            fail("moving back to alpha=%r did not draw the first net again" % expected)
        # the other sliders (the C1 weight of a boundary with ribbons) move their nets too
        parameters = evaluate("window.coonsView.parameters()")
        print("sliders: %r" % parameters)
        if expected_parameters is not None and parameters != expected_parameters:
            fail("the page has the sliders %r, expected %r" % (parameters, expected_parameters))
        # where the page solves a family itself, its solve and sampling at every frame's value agree
        # with the frame coons wrote (5 significant digits of the offsets from the page's origin)
        for parameter in parameters:
            if not evaluate("window.coonsView.exact('%s')" % parameter):
                continue
            check = evaluate("window.coonsView.selfCheck('%s')" % parameter)
            print("%s: the page's own solve at %d frames: net %.3g, samples %.3g (of the largest coordinate), "
                  "normals %.3g" % (parameter, check["frames"], check["net"], check["points"], check["normals"]))
            if check["frames"] < 2 or not (check["net"] <= 1e-4 and check["points"] <= 1e-4 and
                                           check["normals"] <= 1e-3):
                fail("the page's own solve of %s differs from the frames: %r" % (parameter, check))
        for parameter in parameters[1:]:
            choices = evaluate("window.coonsView.values('%s')" % parameter)
            before = body("data-net-hash")
            for value in (choices[len(choices) // 3], choices[2 * len(choices) // 3]):
                shown = evaluate("window.coonsView.setValue('%s', %r)" % (parameter, value))
                now = body("data-net-hash")
                print("%s: %s=%r net-hash=%s" % (parameter, parameter, shown, now))
                if shown != value or float(body("data-" + parameter)) != value or body("data-shown") != parameter:
                    fail("setValue('%s', %r) shows %r" % (parameter, value, body("data-" + parameter)))
                if now == before:
                    fail("the drawn net did not change when %s moved to %r" % (parameter, value))
                before = now
            # a value between the frames: the page's net is that of `coons solve` of the whole file
            if parameter in SOLVE_OPTIONS and evaluate("window.coonsView.exact('%s')" % parameter):
                between = float("%.6f" % ((choices[1] + choices[2]) / 2))
                if between in choices:
                    fail("%r is a precomputed value: the check would not test the page's own solve" % between)
                shown = evaluate("window.coonsView.setValue('%s', %r)" % (parameter, between))
                if shown != between or float(body("data-" + parameter)) != between:
                    fail("setValue('%s', %r) shows %r" % (parameter, between, body("data-" + parameter)))
                report = json.loads(subprocess.run([coons, "solve", boundary] + SOLVE_OPTIONS[parameter] +
                                                   [repr(between)], check=True, capture_output=True,
                                                   text=True).stdout)
                check_shown_net(report["net"], parameter, between)

        if expect_error:
            time.sleep(0.5)
            errors = page_errors()
            if not any("coonsViewNoSuchFunction" in e for e in errors):
                fail("the error of the added script was not seen (errors: %r)" % errors)
            print("ok: the check sees a script error: " + errors[0][:120])
            return 0
        errors = page_errors()
        fetched = [e["params"]["request"]["url"] for e in browser.events
                   if e.get("method") == "Network.requestWillBeSent"]
        outside = [u for u in fetched if not u.startswith("file://") and not u.startswith("data:")]
        if outside or len(fetched) != 1:
            fail("the page fetched more than itself: %r" % fetched)
        print("requests: %r" % fetched)
        if errors:
            fail("errors in the page: " + " | ".join(errors))
        print("ok: no console errors, the page is drawn and the slider moves the net")
        return 0
    finally:
        browser.close()
        shutil.rmtree(profile, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
