# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0

"""
Helpers of the browser tests: Debian's chromium driven headless by playwright, pixels, ports.

playwright's own browser download cannot work on these machines; it drives the
``chromium`` Debian package (installed by scripts/setup) through ``executable_path``, with a
fresh profile per test and software WebGL (SwiftShader), as the package's ``screenshot`` tool
(amr_description/tools/screenshot.py, whose launch this shares). Every request the page makes is
recorded, to check that nothing leaves the machine.
"""

import contextlib
import os
import socket
import time

from amr_description.tools.screenshot import browser_page
from amr_description.tools.screenshot import CHROMIUM
from amr_description.tools.screenshot import close_notifications
import numpy as np

VIEWPORT = {'width': 800, 'height': 520}
TIMEOUT_MS = 240000  # software WebGL on a loaded 2-core machine: a frame can take a minute


def free_port():
    """Return a TCP port on 127.0.0.1 that is free right now."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.bind(('127.0.0.1', 0))
        return sock.getsockname()[1]


def port_open(port, host='127.0.0.1'):
    """Return True when something accepts TCP connections on ``host:port``."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as sock:
        sock.settimeout(1.0)
        return sock.connect_ex((host, port)) == 0


class Page:
    """An open page plus every URL it requested (``requests``, also websockets)."""

    def __init__(self, page, requests):
        self.page = page
        self.requests = requests

    def pixels(self, path=None):
        """Return a screenshot as an (H, W, 3) uint8 array (saved to ``path`` when given)."""
        from io import BytesIO

        from PIL import Image
        png = self.page.screenshot(path=path, timeout=TIMEOUT_MS)
        return np.asarray(Image.open(BytesIO(png)).convert('RGB'))

    def image_pixels(self, path=None):
        """
        Return the largest visible ``<img>`` of the page as an (H, W, 3) uint8 array, or None.

        Scrolled into view first, so the panel's layout above it does not matter (a camera
        panel's picture).
        """
        from io import BytesIO

        from PIL import Image
        images = self.page.locator('img')
        best, area = None, 0
        for index in range(images.count()):
            box = images.nth(index).bounding_box()
            if box is not None and box['width'] * box['height'] > area:
                best, area = images.nth(index), box['width'] * box['height']
        if best is None:
            return None
        best.scroll_into_view_if_needed(timeout=TIMEOUT_MS)
        png = best.screenshot(path=path, timeout=TIMEOUT_MS)
        return np.asarray(Image.open(BytesIO(png)).convert('RGB'))

    def all_image_pixels(self):
        """Return every visible ``<img>`` of the page as (H, W, 3) uint8 arrays (a list)."""
        from io import BytesIO

        from PIL import Image
        images = self.page.locator('img')
        found = []
        for index in range(images.count()):
            image = images.nth(index)
            if image.bounding_box() is None:
                continue
            image.scroll_into_view_if_needed(timeout=TIMEOUT_MS)
            png = image.screenshot(timeout=TIMEOUT_MS)
            found.append(np.asarray(Image.open(BytesIO(png)).convert('RGB')))
        return found

    def close_notifications(self):
        """Close the page's notifications (e.g. 'Software WebGL rendering detected')."""
        close_notifications(self.page)

    def wait_for_text(self, text, timeout=60.0):
        """Wait until ``text`` is in the page's visible text; return True when seen."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if text in self.page.inner_text('body'):
                return True
            self.page.wait_for_timeout(250)
        return False


@contextlib.contextmanager
def open_page(url):
    """
    Open ``url`` in headless chromium (fresh profile, software WebGL); yield a :class:`Page`.

    :param url: the page to open.
    """
    requests = []
    with browser_page(url, VIEWPORT, TIMEOUT_MS, requests.append) as page:
        yield Page(page, requests)


def colour_mask(image, rgb, tolerance):
    """
    Return the (H, W) boolean mask of pixels near a colour's hue.

    Shading changes brightness, so a pixel matches when its colour, scaled to the brightness
    of ``rgb``, is within ``tolerance`` (0..255 per channel) of ``rgb``.
    """
    image = image.astype(float)
    target = np.asarray(rgb, dtype=float)
    brightness = image.max(axis=2, keepdims=True)
    scaled = image / np.maximum(brightness, 1.0) * target.max()
    return (np.abs(scaled - target).max(axis=2) <= tolerance) & (brightness[..., 0] > 40)


def centroid(mask):
    """Return the (x, y) pixel centroid of a mask, or None when it is empty."""
    ys, xs = np.nonzero(mask)
    if len(xs) == 0:
        return None
    return float(xs.mean()), float(ys.mean())


def local_only(urls, port):
    """Return the URLs that go anywhere but this machine's ``port`` (or data:/blob:)."""
    allowed = (f'http://127.0.0.1:{port}', f'ws://127.0.0.1:{port}')
    return [u for u in urls
            if not u.startswith(allowed) and not u.startswith(('data:', 'blob:'))]


def ensure_chromium():
    """Return True when Debian's chromium is installed (scripts/setup installs it)."""
    return os.path.exists(CHROMIUM)
