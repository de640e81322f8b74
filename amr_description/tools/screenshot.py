# Copyright 2026 The amr_description Authors
# Licensed under the Apache License, Version 2.0
"""
``screenshot``: a PNG of a viewer page (or any page) from headless chromium.

``chromium --headless --screenshot`` gives a blank picture of the viewer: the page draws its
3-D view with WebGL after its websocket has delivered the scene, long after the ``load`` event
chromium waits for. This opens the page in Debian's chromium through playwright (the browser
the browser tests use, software WebGL), waits until the page shows a text (``Fixed Frame``, the
viewer's displays panel, by default), closes its notifications, waits until the 3-D canvas holds
more than one colour (it has drawn) and then ``--delay`` seconds more (the scene's latest
messages are drawn), and writes the picture::

    ros2 run amr_description screenshot http://127.0.0.1:8080/ -o viewer.png

Exit codes: 0 written; 1 the page did not open, did not show the text or did not draw within
``--timeout`` (one line saying which; the last picture is written anyway when there is one).
"""

import argparse
import contextlib
import shutil
import sys
import tempfile
import time

CHROMIUM = shutil.which('chromium') or '/usr/bin/chromium'
"""Debian's chromium (scripts/setup installs it); playwright's own download is not used."""
FLAGS = ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
         '--disable-background-networking', '--disable-component-update', '--disable-sync',
         '--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader']
"""chromium flags: software WebGL (SwiftShader), nothing fetched from the network."""


@contextlib.contextmanager
def browser_page(url, viewport, timeout_ms, on_request=None):
    """
    Open ``url`` in headless chromium with a fresh profile; yield the playwright page.

    :param url: the page's address.
    :param viewport: ``{'width': px, 'height': px}``.
    :param timeout_ms: default timeout of the page's operations (ms).
    :param on_request: optional callable given each URL the page requests (websockets too).
    :raises playwright.sync_api.Error: the browser or the page could not be opened.
    """
    from playwright.sync_api import sync_playwright
    profile = tempfile.mkdtemp(prefix='amr_chromium_')
    try:
        with sync_playwright() as playwright:
            context = playwright.chromium.launch_persistent_context(
                profile, executable_path=CHROMIUM, headless=True, args=FLAGS,
                viewport=viewport)
            try:
                page = context.pages[0] if context.pages else context.new_page()
                if on_request is not None:
                    context.on('request', lambda request: on_request(request.url))
                    page.on('websocket', lambda ws: on_request(ws.url))
                page.set_default_timeout(timeout_ms)
                page.goto(url, wait_until='load', timeout=timeout_ms)
                yield page
            finally:
                context.close()
    finally:
        shutil.rmtree(profile, ignore_errors=True)


def close_notifications(page):
    """Close the page's notifications (viser's 'Software WebGL rendering detected' toast)."""
    buttons = page.locator('.mantine-Notification-closeButton')
    for index in range(buttons.count()):
        try:
            buttons.nth(index).click(timeout=10000)
        except Exception:  # noqa: B902 - cosmetic: a notification may close itself
            pass


def _drawn(png):
    """Return True when a PNG holds more than one colour (a blank WebGL canvas is one)."""
    from io import BytesIO

    import numpy as np
    from PIL import Image
    pixels = np.asarray(Image.open(BytesIO(png)).convert('RGB')).reshape(-1, 3)
    return bool((pixels != pixels[0]).any())


def drawn_screenshot(page, text, delay, deadline):
    """
    Wait for ``text``, then for the page's 3-D canvas to have drawn; return a screenshot.

    :param page: a playwright page.
    :param text: text the page must show first ('' for none).
    :param delay: seconds to wait once the canvas has drawn (the scene's messages arrive).
    :param deadline: ``time.monotonic()`` value at which to give up.
    :returns: ``(png bytes or None, problem str or '')``.
    """
    while text and text not in page.inner_text('body'):
        if time.monotonic() > deadline:
            return None, f'the page never showed {text!r}'
        page.wait_for_timeout(250)
    close_notifications(page)
    canvas = page.locator('canvas')
    while canvas.count() and not _drawn(canvas.first.screenshot()):
        if time.monotonic() > deadline:
            return page.screenshot(), 'the 3-D view never drew'
        page.wait_for_timeout(250)
    page.wait_for_timeout(int(delay * 1000))
    return page.screenshot(), ''


def main(argv=None):
    """Run the command line (see the module docstring); return the exit code."""
    parser = argparse.ArgumentParser(
        prog='screenshot', description='Write a PNG of a viewer page once it has drawn.')
    parser.add_argument('url', nargs='?', default='http://127.0.0.1:8080/',
                        help='the page (default: the viewer at http://127.0.0.1:8080/)')
    parser.add_argument('-o', '--output', default='viewer.png', help='PNG file to write')
    parser.add_argument('--size', default='1280x800', help='viewport WIDTHxHEIGHT in pixels')
    parser.add_argument('--wait-for', default='Fixed Frame',
                        help="text the page shows before the picture ('' for none)")
    parser.add_argument('--delay', type=float, default=3.0,
                        help='seconds to wait after the 3-D view has drawn (default: 3)')
    parser.add_argument('--timeout', type=float, default=120.0,
                        help='seconds to wait in all (software WebGL on 2 cores is slow)')
    args = parser.parse_args(argv)
    try:
        width, height = (int(v) for v in args.size.lower().split('x'))
        if width <= 0 or height <= 0:
            raise ValueError
    except ValueError:
        print(f'screenshot: --size {args.size!r}: expected WIDTHxHEIGHT, e.g. 1280x800',
              file=sys.stderr)
        return 1
    deadline = time.monotonic() + args.timeout
    try:
        from playwright.sync_api import Error
    except ImportError:
        print('screenshot: playwright is not installed (run scripts/setup)', file=sys.stderr)
        return 1
    try:
        with browser_page(args.url, {'width': width, 'height': height},
                          int(args.timeout * 1000)) as page:
            png, problem = drawn_screenshot(page, args.wait_for, args.delay, deadline)
    except Error as exc:
        print(f'screenshot: {args.url}: {str(exc).splitlines()[0]}', file=sys.stderr)
        return 1
    if png is not None:
        with open(args.output, 'wb') as stream:
            stream.write(png)
    if problem:
        print(f'screenshot: {args.url}: {problem} within {args.timeout:g} s'
              + (f'; wrote the last picture to {args.output}' if png else ''), file=sys.stderr)
        return 1
    print(f'screenshot: wrote {args.output} ({width}x{height})')
    return 0


if __name__ == '__main__':
    sys.exit(main())
