#!/usr/bin/env python3
"""vsil serve's page in headless Chromium (Debian's chromium, chromium-driver, python3-selenium).

Loads the page; drags 40 px: the frame changes and the command line follows, and that command
run through `vsil render` gives the bytes the page shows. Then a `semantic` server whose rule
base focuses around the cursor's pixel: two clicks, and the focus region follows them. Bad
parameters get 400 and the server renders on; rapid changes coalesce (median latency printed).

Usage: browser_test.py VSIL_BINARY [--screenshot PNG]
Exit 77 (ctest: skipped) when Chromium, chromedriver or Selenium is absent, naming which — unless
VSIL_REQUIRE_BROWSER=1 (CI), where that fails instead.
"""
import base64
import concurrent.futures
import io
import os
import shlex
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request

SKIP = 77


def missing_browser():
    for program in ("chromium", "chromedriver"):
        if not shutil.which(program):
            return f"{program} is not installed (Debian: chromium, chromium-driver)"
    try:
        import selenium  # noqa: F401
    except ImportError:
        return "python3-selenium is not installed"
    return None


def wait_for(what, predicate, seconds=90):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(0.1)
    raise AssertionError(f"timed out after {seconds} s waiting for {what}")


class Server:
    """`vsil serve` on a free loopback port (--port 0: it prints the one it took)."""

    def __init__(self, binary, *arguments):
        self.process = subprocess.Popen(
            [binary, "serve", *arguments, "--port", "0"],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        line = self.process.stdout.readline()  # "vsil serve: http://127.0.0.1:PORT/"
        if not line.startswith("vsil serve: http://127.0.0.1:"):
            self.process.kill()
            raise AssertionError("vsil serve did not start: " + line + self.process.stderr.read())
        self.url = line.split(": ", 1)[1].strip()

    def get(self, path):
        """(status, body bytes, headers)"""
        try:
            with urllib.request.urlopen(self.url + path, timeout=120) as answer:
                return answer.status, answer.read(), answer.headers
        except urllib.error.HTTPError as error:
            return error.code, error.read(), error.headers

    def stop(self):
        self.process.terminate()
        try:
            self.process.wait(timeout=20)
        except subprocess.TimeoutExpired:
            self.process.kill()


def chrome():
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    options = webdriver.ChromeOptions()
    options.binary_location = shutil.which("chromium")
    for argument in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                     "--window-size=900,800", "--hide-scrollbars"):
        options.add_argument(argument)
    return webdriver.Chrome(service=Service(shutil.which("chromedriver")), options=options)


def shown_png(driver):
    """The bytes of the PNG the page shows (fetched back from its blob: URL)."""
    data = driver.execute_async_script("""
        const done = arguments[arguments.length - 1];
        fetch(document.getElementById('frame').src).then(r => r.arrayBuffer()).then(b => {
          let s = ''; for (const x of new Uint8Array(b)) s += String.fromCharCode(x);
          done(btoa(s));
        });""")
    return base64.b64decode(data)


def settled(driver):
    """Waits until the page shows its latest view; returns its command line."""
    frame = driver.find_element("id", "frame")
    wait_for("the page's frame", lambda: frame.get_attribute("data-busy") == "0")
    return frame.get_attribute("data-command")


def render_command(binary, command, out):
    """Runs the page's command line with this build's binary, writing `out`."""
    words = shlex.split(command)
    assert words[:2] == ["vsil", "render"], command
    assert words[-2] == "--out", command
    words = [binary] + words[1:-1] + [out]
    subprocess.run(words, check=True, capture_output=True, timeout=120)
    with open(out, "rb") as file:
        return file.read()


def region_change(a_png, b_png, centre, radius):
    """Mean absolute difference of the two images in a square around `centre`."""
    from PIL import Image, ImageChops
    a = Image.open(io.BytesIO(a_png)).convert("RGB")
    b = Image.open(io.BytesIO(b_png)).convert("RGB")
    x, y = centre
    box = (max(0, x - radius), max(0, y - radius), x + radius, y + radius)
    diff = ImageChops.difference(a.crop(box), b.crop(box)).convert("L")
    pixels = list(diff.getdata())
    return sum(pixels) / max(1, len(pixels))


def main():
    binary = sys.argv[1]
    screenshot = sys.argv[sys.argv.index("--screenshot") + 1] if "--screenshot" in sys.argv else None
    reason = missing_browser()
    if reason:
        if os.environ.get("VSIL_REQUIRE_BROWSER") == "1":
            print(f"FAIL: VSIL_REQUIRE_BROWSER=1 but {reason}")
            return 1
        print(f"SKIP: {reason}")
        return SKIP
    from selenium.webdriver import ActionChains
    from selenium.webdriver.support.ui import Select

    scratch = tempfile.mkdtemp(prefix="vsil-serve-browser-")
    # The example rule base with its focus around the cursor's pixel (image_distance) instead of
    # the 3D cursor: a click then moves the focus region. The file is the server's own flag.
    rules = os.path.join(scratch, "focus.rules")
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "src", "core",
                           "rules", "example.rules")) as example, open(rules, "w") as out:
        text = example.read()
        assert "attribute focus from cursor_distance" in text
        out.write(text.replace("attribute focus from cursor_distance",
                               "attribute focus from image_distance"))
    server = Server(binary, "gen:spheres:96", "--size", "320x320")
    focus_server = None
    driver = None
    try:
        driver = chrome()
        driver.set_script_timeout(60)
        driver.get(server.url)
        frame = wait_for("the page", lambda: (driver.find_elements("id", "frame") or [None])[0])
        wait_for("the first frame", lambda: frame.get_attribute("data-frames") not in (None, "0"))
        first_command = settled(driver)
        first = shown_png(driver)

        # Drag 40 px: a new view, its command line, and that command's bytes are the page's.
        ActionChains(driver).move_to_element(frame).click_and_hold().move_by_offset(40, 0) \
            .release().perform()
        wait_for("the dragged view", lambda: frame.get_attribute("data-command") != first_command)
        dragged_command = settled(driver)
        dragged = shown_png(driver)
        assert dragged != first, "the frame did not change with the drag"
        assert "--view 10,20" in dragged_command, dragged_command  # 30 - 40 * 0.5
        assert driver.find_element("id", "command").get_attribute("value") == dragged_command
        assert render_command(binary, dragged_command, os.path.join(scratch, "drag.png")) == dragged, \
            "vsil render of the page's command line gave other bytes than the page shows"
        # What the element shows on screen is that PNG, pixel for pixel (no border, no scaling).
        from PIL import Image, ImageChops
        on_screen = Image.open(io.BytesIO(frame.screenshot_as_png)).convert("RGB")
        served = Image.open(io.BytesIO(dragged)).convert("RGB")
        assert on_screen.size == served.size, (on_screen.size, served.size)
        assert ImageChops.difference(on_screen, served).getbbox() is None, \
            "the page shows other pixels than its PNG"
        print("drag: frame changed; the screen shows the PNG; its command line reproduces it:",
              dragged_command)

        # A fill chosen for the silhouette is cleared when the technique changes to one that
        # draws no lines (the CLI refuses the line flags there): the page shows the MIP frame.
        Select(driver.find_element("id", "option-fill")).select_by_value("flat")
        wait_for("the filled frame", lambda: "--fill flat" in (frame.get_attribute("data-command") or ""))
        settled(driver)
        Select(driver.find_element("id", "technique")).select_by_value("mip")
        wait_for("the MIP frame", lambda: "--technique mip" in (frame.get_attribute("data-command") or ""))
        mip_command = settled(driver)
        assert "--fill" not in mip_command, mip_command
        assert not driver.find_elements("id", "option-fill"), "a fill control beside a MIP"
        error = driver.find_element("id", "error").text
        assert error == "", error
        print("technique change: the fill went with the silhouette:", mip_command)

        # semantic: a click sets --cursor-pixel; the focus region follows the click.
        focus_server = Server(binary, "gen:spheres:96", "--size", "320x320", "--technique",
                              "semantic", "--rules", rules)
        driver.get(focus_server.url)
        frame = wait_for("the page", lambda: (driver.find_elements("id", "frame") or [None])[0])
        wait_for("the semantic frame", lambda: frame.get_attribute("data-frames") not in (None, "0"))
        settled(driver)
        shown = []
        for offset in ((-40, 0), (40, 0)):  # from the image's centre: on the object
            before = frame.get_attribute("data-command")
            ActionChains(driver).move_to_element_with_offset(frame, *offset).click().perform()
            wait_for("the clicked view", lambda: frame.get_attribute("data-command") != before)
            command = settled(driver)
            words = shlex.split(command)
            assert "--cursor-pixel" in words, command
            pixel = tuple(int(v) for v in words[words.index("--cursor-pixel") + 1].split(","))
            shown.append((pixel, shown_png(driver)))
        (pixel_a, a), (pixel_b, b) = shown
        assert abs(pixel_a[0] - 120) <= 3 and abs(pixel_b[0] - 200) <= 3, (pixel_a, pixel_b)
        near_a = region_change(a, b, pixel_a, 20)
        near_b = region_change(a, b, pixel_b, 20)
        far = region_change(a, b, (20, 20), 15)
        print(f"semantic: clicks at {pixel_a} and {pixel_b}; mean change near them "
              f"{near_a:.1f} and {near_b:.1f} grey levels, in a corner {far:.1f}")
        assert near_a > 10 and near_b > 10 and far < 1, "the focus region did not follow the click"
        if screenshot:  # for the README: 256 colours keep it small
            from PIL import Image
            shot = Image.open(io.BytesIO(driver.get_screenshot_as_png())).convert("RGB")
            shot.quantize(256).save(screenshot, optimize=True)

        # Bad parameters: 400 with one line, and the server renders on; rapid changes coalesce.
        status, body, _ = server.get("frame?width_near=-3")  # the silhouette server
        assert status == 400 and body.decode().count("\n") == 1 and b"--width-near" in body, body
        latencies = []

        def change(i):
            start = time.monotonic()
            status, _, _ = server.get(f"frame?view={i},20")
            latencies.append(time.monotonic() - start)
            return status

        with concurrent.futures.ThreadPoolExecutor(4) as pool:
            statuses = list(pool.map(change, range(24)))
        assert set(statuses) <= {200, 409}, statuses
        status, body, _ = server.get("frame?view=5,5")
        assert status == 200 and body.startswith(b"\x89PNG"), (status, body[:80])
        print(f"24 rapid changes: {statuses.count(200)} rendered, {statuses.count(409)} superseded, "
              f"median latency {statistics.median(latencies) * 1000:.0f} ms; the server answers")
        return 0
    finally:
        if driver:
            driver.quit()
        server.stop()
        if focus_server:
            focus_server.stop()
        shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
