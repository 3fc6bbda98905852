"""What both studio browser tests need: Debian's Chromium under chromedriver (skipping with a
message when either is missing), a `cropsight studio` started with its URL read from its output
and stopped with Ctrl-C, and screenshots small enough for the docs."""
import os
import signal
import subprocess

import pytest

CLI = os.environ.get("CROPSIGHT_CLI", "build/bin/cropsight")
CHROMIUM, CHROMEDRIVER = "/usr/bin/chromium", "/usr/bin/chromedriver"

webdriver = pytest.importorskip("selenium.webdriver", reason="python3-selenium is not installed")
Image = pytest.importorskip("PIL.Image", reason="python3-pil is not installed")
from selenium.webdriver.chrome.service import Service  # noqa: E402


def chromium():
    """A headless Chromium at a fixed window size and scale (the click positions depend on both)."""
    for exe in (CHROMIUM, CHROMEDRIVER):
        if not os.access(exe, os.X_OK):
            pytest.skip(f"{exe} not found (apt-get install chromium chromium-driver)")
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1500,900",
                "--force-device-scale-factor=1"):
        options.add_argument(arg)
    return webdriver.Chrome(service=Service(executable_path=CHROMEDRIVER), options=options)


def start_studio(*args):
    """`cropsight studio ARGS` and the URL (with its token) it printed."""
    proc = subprocess.Popen([CLI, "studio", *map(str, args)], stdout=subprocess.PIPE, text=True)
    for _ in range(5):
        line = proc.stdout.readline()
        if line.startswith("open "):
            return proc, line.split()[1]
    proc.kill()
    pytest.fail("the studio printed no URL")


def stop_studio(proc):
    """Ctrl-C, as a user stops it: the studio must end cleanly."""
    if proc.poll() is None:
        proc.send_signal(signal.SIGINT)
        proc.wait(timeout=20)


def screenshot(driver, path):
    """The page as a 128-colour PNG (a third of the size of Chromium's), for docs/studio.md."""
    driver.save_screenshot(str(path))
    Image.open(path).convert("RGB").quantize(colors=128).save(path, optimize=True)
