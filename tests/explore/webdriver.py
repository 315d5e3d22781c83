"""Headless Chromium through chromedriver's WebDriver protocol (W3C, plain HTTP + JSON),
and `pelage explore` as a child process: what the explorer's page test and the docs'
screenshot script drive. Standard library only; every wait is bounded."""
import base64
import json
import os
import shutil
import signal
import socket
import subprocess
import time
import urllib.error
import urllib.request


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _call(method, url, body=None, timeout=120):
    data = json.dumps(body).encode() if body is not None else None
    req = urllib.request.Request(url, data=data, method=method,
                                 headers={"Content-Type": "application/json"})
    try:
        with urllib.request.urlopen(req, timeout=timeout) as r:
            return json.loads(r.read() or b"null")
    except urllib.error.HTTPError as e:
        raise RuntimeError(f"{method} {url}: {e.code} {e.read()[:500]!r}") from None


def browser_available():
    return bool(shutil.which("chromedriver")) and os.path.exists("/usr/bin/chromium")


class Browser:
    """One headless Chromium window of width x height CSS pixels, WebGL by SwiftShader."""

    def __init__(self, width=1400, height=900):
        self.port = free_port()
        self.driver = subprocess.Popen(["chromedriver", f"--port={self.port}"],
                                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.base = f"http://127.0.0.1:{self.port}"
        self.session = None
        try:
            deadline = time.time() + 20
            while True:
                try:
                    if _call("GET", self.base + "/status", timeout=2)["value"]["ready"]:
                        break
                except (OSError, RuntimeError):
                    pass
                if time.time() > deadline:
                    raise RuntimeError("chromedriver did not start within 20 s")
                time.sleep(0.2)
            args = ["--headless=new", "--no-sandbox", "--disable-gpu", "--use-gl=swiftshader",
                    "--enable-unsafe-swiftshader", f"--window-size={width},{height}",
                    "--disable-dev-shm-usage"]
            caps = {"capabilities": {"alwaysMatch": {
                "browserName": "chrome",
                "goog:chromeOptions": {"binary": "/usr/bin/chromium", "args": args}}}}
            self.session = _call("POST", self.base + "/session", caps)["value"]["sessionId"]
            _call("POST", self._s("/timeouts"), {"script": 60000, "pageLoad": 60000})
        except BaseException:
            self.close()
            raise

    def _s(self, path):
        return f"{self.base}/session/{self.session}{path}"

    def get(self, url):
        _call("POST", self._s("/url"), {"url": url})

    def js(self, script, *args):
        """Runs `script` (a function body) in the page and returns its value."""
        return _call("POST", self._s("/execute/sync"),
                     {"script": script, "args": list(args)})["value"]

    def js_async(self, script, *args):
        """Runs `script`, which calls its last argument with the result, in the page."""
        return _call("POST", self._s("/execute/async"),
                     {"script": script, "args": list(args)})["value"]

    def wait(self, script, timeout, what):
        """Waits until `script` returns a truthy value; returns it."""
        deadline = time.time() + timeout
        while time.time() < deadline:
            v = self.js(script)
            if v:
                return v
            time.sleep(0.1)
        raise RuntimeError(f"timed out after {timeout} s waiting for {what}")

    def screenshot(self, path):
        png = _call("GET", self._s("/screenshot"))["value"]
        with open(path, "wb") as f:
            f.write(base64.b64decode(png))

    def close(self):
        if self.session:
            try:
                _call("DELETE", self._s(""), timeout=20)
            except (OSError, RuntimeError):
                pass
            self.session = None
        self.driver.terminate()
        try:
            self.driver.wait(10)
        except subprocess.TimeoutExpired:
            self.driver.kill()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


class Explorer:
    """`pelage explore` on a free loopback port; stopped with Ctrl-C (SIGINT)."""

    def __init__(self, pelage, args):
        self.port = free_port()
        self.proc = subprocess.Popen([pelage, "explore", *args, "--port", str(self.port)],
                                     stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        line = self.proc.stdout.readline()
        if "open http://" not in line:
            err = self.proc.stderr.read() if self.proc.poll() is not None else ""
            self.stop()
            raise RuntimeError(f"pelage explore did not start: {line!r} {err!r}")
        self.url = f"http://127.0.0.1:{self.port}/"

    def stop(self):
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
            try:
                self.proc.wait(20)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        return self.proc.returncode

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.stop()
