"""Opens the built documentation in headless Chromium and checks what a reader sees: every page
loads without a console error, an uncaught exception or a failed request; its images load; the
search finds `stream_to`; every tutorial shows a figure; maths is typeset by the MathJax the
site carries (no CDN).

Usage: python scripts/check-docs-browser.py [build/docs/html]

Chromium is driven through its DevTools protocol over a pipe (--remote-debugging-pipe: JSON
messages ended by a NUL byte on file descriptors 3 and 4), so the check needs the Python
standard library and Debian's chromium package only: no WebDriver, no browser download. The
site is served over HTTP from a local thread, as a web server would. Without Chromium the check
is skipped with a message (exit 0)."""

from __future__ import annotations

import fcntl
import functools
import json
import os
import select
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from http.server import SimpleHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any

BROWSERS = ("chromium", "chromium-browser", "google-chrome")
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--remote-debugging-pipe"]
SEARCHED = "stream_to"
PAGE_TIMEOUT = 30.0  # seconds for a page's load event
SETTLE = 0.3  # seconds after the load event for late requests and errors
MATH_TIMEOUT = 15.0  # seconds for MathJax to typeset a page
SEARCH_TIMEOUT = 30.0  # seconds for the search page to list what it found

IMAGES_NOT_LOADED = """Array.from(document.images)
    .filter(image => !image.complete || image.naturalWidth === 0)
    .map(image => image.src)"""
FIGURES = "Array.from(document.images).filter(image => image.naturalWidth > 0).length"
HAS_MATH = "document.querySelectorAll('.math').length"
TYPESET = "document.querySelectorAll('.MathJax_CHTML, .MathJax, mjx-container').length"
MATHJAX_SOURCES = """Array.from(document.scripts).map(script => script.src)
    .filter(source => /mathjax/i.test(source))"""
SEARCH_RESULTS = "document.querySelectorAll('#search-results li, ul.search li').length"


class Browser:
    """One headless Chromium and the page target the check drives."""

    def __init__(self, executable: str) -> None:
        # a helper process may still write the profile as the browser exits
        self._profile = tempfile.TemporaryDirectory(prefix="docs-browser-",
                                                    ignore_cleanup_errors=True)
        to_browser_read, self._to_browser = os.pipe()
        self._from_browser, from_browser_write = os.pipe()
        # the child's ends above 9, so that moving them to 3 and 4 closes neither
        to_browser_read, from_browser_write = (_above_nine(to_browser_read),
                                               _above_nine(from_browser_write))

        # the protocol's fixed descriptor numbers, set by the shell that then runs Chromium
        redirect = (f'exec "$0" "$@" 3<&{to_browser_read} 4>&{from_browser_write} '
                    f"{to_browser_read}<&- {from_browser_write}>&-")
        self._process = subprocess.Popen(
            ["bash", "-c", redirect, executable, *FLAGS,
             f"--user-data-dir={self._profile.name}", "about:blank"],
            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
            pass_fds=(to_browser_read, from_browser_write))
        os.close(to_browser_read)
        os.close(from_browser_write)
        self._buffer = b""
        self._next_id = 0
        self.events: list[dict[str, Any]] = []
        target = self.call("Target.createTarget", url="about:blank")["targetId"]
        self._session = self.call("Target.attachToTarget", targetId=target,
                                  flatten=True)["sessionId"]
        for domain in ("Page", "Runtime", "Log", "Network"):
            self.call(f"{domain}.enable", session=True)

    def close(self) -> None:
        try:  # asked to close, Chromium ends its helper processes before it exits
            self.call("Browser.close", timeout=10)
        except (OSError, RuntimeError, TimeoutError):
            self._process.terminate()
        try:
            self._process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self._process.kill()
            self._process.wait()
        os.close(self._to_browser)
        os.close(self._from_browser)
        self._profile.cleanup()

    def _receive(self, deadline: float) -> dict[str, Any] | None:
        """The next message, or None when the deadline passes first."""
        while b"\0" not in self._buffer:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                return None
            ready, _, _ = select.select([self._from_browser], [], [], remaining)
            if ready:
                chunk = os.read(self._from_browser, 1 << 20)
                if not chunk:
                    raise RuntimeError("Chromium closed the DevTools pipe")
                self._buffer += chunk
        message, self._buffer = self._buffer.split(b"\0", 1)
        return json.loads(message)

    def call(self, method: str, session: bool = False, timeout: float = PAGE_TIMEOUT,
             **params: Any) -> dict[str, Any]:
        """Send a command and wait for its answer; events that arrive meanwhile are kept."""
        self._next_id += 1
        request: dict[str, Any] = {"id": self._next_id, "method": method, "params": params}
        if session:
            request["sessionId"] = self._session
        os.write(self._to_browser, json.dumps(request).encode() + b"\0")
        deadline = time.monotonic() + timeout
        while (message := self._receive(deadline)) is not None:
            if message.get("id") == self._next_id:
                if "error" in message:
                    raise RuntimeError(f"{method}: {message['error']}")
                return message.get("result", {})
            self.events.append(message)
        raise TimeoutError(f"{method}: no answer in {timeout} s")

    def wait_for(self, method: str | None, timeout: float) -> bool:
        """Collect events until one named `method` arrives (True) or the timeout passes
        (None: collect them for the whole timeout)."""
        deadline = time.monotonic() + timeout
        while (message := self._receive(deadline)) is not None:
            self.events.append(message)
            if message.get("method") == method:
                return True
        return False

    def evaluate(self, expression: str) -> Any:
        result = self.call("Runtime.evaluate", session=True, expression=expression,
                           returnByValue=True)
        return result.get("result", {}).get("value")

    def poll(self, expression: str, timeout: float) -> Any:
        """`expression`'s value once it is truthy, or its last value when the timeout passes."""
        deadline = time.monotonic() + timeout
        while not (value := self.evaluate(expression)) and time.monotonic() < deadline:
            self.wait_for(None, 0.2)
        return value

    def open(self, url: str) -> list[str]:
        """Load `url`; the console errors, exceptions and failed requests while it loads."""
        self.events.clear()
        self.call("Page.navigate", session=True, url=url)
        if not self.wait_for("Page.loadEventFired", PAGE_TIMEOUT):
            return [f"no load event in {PAGE_TIMEOUT} s"]
        self.wait_for(None, SETTLE)
        return [problem for event in self.events if (problem := _problem(event))]


def _above_nine(descriptor: int) -> int:
    """A copy of `descriptor` numbered 10 or more; the original is closed."""
    copy = fcntl.fcntl(descriptor, fcntl.F_DUPFD, 10)
    os.close(descriptor)
    return copy


def _problem(event: dict[str, Any]) -> str | None:
    """What a DevTools event reports that a reader would see as broken, if anything."""
    params = event.get("params", {})
    method = event.get("method")
    if method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert"):
        return "console: " + " ".join(str(arg.get("value", arg.get("description", "")))
                                      for arg in params.get("args", []))
    if method == "Runtime.exceptionThrown":
        details = params.get("exceptionDetails", {})
        return "exception: " + details.get("exception", {}).get("description",
                                                                details.get("text", ""))
    if method == "Log.entryAdded" and params.get("entry", {}).get("level") == "error":
        entry = params["entry"]
        if entry.get("url", "").endswith("/favicon.ico"):
            return None  # the browser's own request, which a site without an icon answers 404
        return f"log: {entry.get('text')} {entry.get('url', '')}".rstrip()
    if method == "Network.loadingFailed" and not params.get("canceled"):
        return f"request failed: {params.get('errorText')}"
    return None


def serve(site: Path) -> ThreadingHTTPServer:
    class QuietHandler(SimpleHTTPRequestHandler):
        def log_message(self, format: str, *args: Any) -> None:
            pass

    server = ThreadingHTTPServer(("127.0.0.1", 0),
                                 functools.partial(QuietHandler, directory=str(site)))
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server


def check_site(site: Path, browser: Browser, base: str) -> list[str]:
    """Every problem found, as "page: problem" lines."""
    failures: list[str] = []
    pages = sorted(path.relative_to(site).as_posix() for path in site.rglob("*.html")
                   if "_static" not in path.parts and "_sources" not in path.parts)
    for page in pages:
        failures += [f"{page}: {problem}" for problem in browser.open(f"{base}/{page}")]
        failures += [f"{page}: image not loaded: {source}"
                     for source in browser.evaluate(IMAGES_NOT_LOADED) or []]
        if page.startswith("tutorials/") and page != "tutorials/index.html" \
                and not browser.evaluate(FIGURES):
            failures.append(f"{page}: a tutorial without a figure")
        if browser.evaluate(HAS_MATH):
            failures += _check_math(page, browser, base)
    browser.open(f"{base}/search.html?q={SEARCHED}")
    if not browser.poll(SEARCH_RESULTS, SEARCH_TIMEOUT):
        failures.append(f"search.html: searching {SEARCHED!r} finds nothing")
    print(f"{len(pages)} pages opened in Chromium; searched {SEARCHED!r}")
    return failures


def _check_math(page: str, browser: Browser, base: str) -> list[str]:
    failures = [f"{page}: MathJax comes from another site: {source}"
                for source in browser.evaluate(MATHJAX_SOURCES) or []
                if not source.startswith(base)]
    if not browser.poll(TYPESET, MATH_TIMEOUT):
        failures.append(f"{page}: its maths is not typeset")
    return failures


def main() -> int:
    site = Path(sys.argv[1] if len(sys.argv) > 1 else "build/docs/html").resolve()
    if not (site / "index.html").is_file():
        print(f"no built documentation in {site}: build it first (sphinx -b html)",
              file=sys.stderr)
        return 1
    executable = next((found for name in BROWSERS if (found := shutil.which(name))), None)
    if executable is None:
        print("skipped: no Chromium to open the documentation in (apt install chromium)")
        return 0
    server = serve(site)
    browser = Browser(executable)
    try:
        failures = check_site(site, browser, f"http://127.0.0.1:{server.server_port}")
    finally:
        browser.close()
        server.shutdown()
    for failure in failures:
        print(failure, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
