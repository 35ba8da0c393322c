#!/usr/bin/env python3
"""Serves the site `scripts/web` builds as a static host serves it: a file with a precompressed
copy beside it (`web_bg.wasm.br`, `web_bg.wasm.gz`) goes out as that copy with `Content-Encoding`
when the request's `Accept-Encoding` takes it (brotli first, then gzip, else the file itself),
with the original's `Content-Type` (`application/wasm` for the module, which the browser needs to
compile it while it downloads) and `Vary: Accept-Encoding`.

It serves only regular files whose real path (every link followed) lies inside the folder; `/`
is its index.html, and no folder is listed. A malformed path (not UTF-8, a NUL or other control
character, a `.` or `..` name, plain or percent-encoded) gets 400, anything else 404.

usage: web-serve.py DIRECTORY PORT    (binds 127.0.0.1; `scripts/web --serve` runs it)
"""
import functools
import http.server
import os
import stat
import sys
import urllib.parse

TYPES = {
    ".html": "text/html; charset=utf-8",
    ".js": "text/javascript; charset=utf-8",
    ".wasm": "application/wasm",
    ".css": "text/css; charset=utf-8",
    ".json": "application/json",
    ".png": "image/png",
}

# The encodings offered, best first, with the suffix of their precompressed copies.
ENCODINGS = (("br", ".br"), ("gzip", ".gz"))


def accepted(header):
    """The content codings an `Accept-Encoding` header takes (those with a q-value above 0)."""
    taken = set()
    for part in (header or "").split(","):
        fields = [f.strip() for f in part.split(";")]
        name = fields[0].lower()
        if not name:
            continue
        q = 1.0
        for f in fields[1:]:
            if f.lower().startswith("q="):
                try:
                    q = float(f[2:])
                except ValueError:
                    q = 0.0
        if q > 0:
            taken.add(name)
    if "*" in taken:
        taken.update(name for name, _ in ENCODINGS)
    return taken


def inside(root, path):
    """`path`'s real path when it names a regular file inside the real folder `root`, else None.

    The real path follows every link, so a link inside the folder that leads out of it, and a
    folder, a pipe or a device, are not served."""
    real = os.path.realpath(path)
    if os.path.commonpath([root, real]) != root or real == root:
        return None
    try:
        return real if stat.S_ISREG(os.stat(real).st_mode) else None
    except OSError:
        return None


class Malformed(ValueError):
    """A request path that names no file: not absolute, not UTF-8, a NUL, or `.`/`..`."""


def segments(target):
    """The file names a request's target walks, decoded; `[]` for `/`. Raises Malformed."""
    path = target.split("?", 1)[0].split("#", 1)[0]
    if not path.startswith("/"):
        raise Malformed("the path does not start with /")
    try:
        decoded = urllib.parse.unquote(path, errors="strict")
    except UnicodeDecodeError:
        raise Malformed("the path is not UTF-8") from None
    if any(ord(c) < 0x20 or c == "\x7f" for c in decoded):
        raise Malformed("the path holds a control character")
    names = decoded.split("/")[1:]
    if any(name in (".", "..") for name in names):
        raise Malformed("the path holds . or ..")
    return names


class Handler(http.server.SimpleHTTPRequestHandler):
    extensions_map = {**http.server.SimpleHTTPRequestHandler.extensions_map, **TYPES}

    encoding = None

    def send_head(self):
        """Opens the regular file inside the folder the request names (`/` names index.html), or
        answers 400 for a malformed path and 404 for anything else: no listing, no redirect."""
        self.encoding = None
        try:
            names = segments(self.path)
        except Malformed as e:
            self.send_error(400, "Bad request path", str(e))
            return None
        root = os.path.realpath(self.directory)
        if names == [""]:
            names = ["index.html"]
        path = inside(root, os.path.join(root, *names)) if all(names) else None
        if path is None:
            self.send_error(404, "File not found")
            return None
        # A copy older than its original is stale (a site half rebuilt): the original goes out.
        # Whole seconds: gzip and brotli give a copy its original's time, brotli without the
        # fraction.
        copies = {name: inside(root, path + suffix) for name, suffix in ENCODINGS}
        chosen, encoding = path, None
        taken = accepted(self.headers.get("Accept-Encoding"))
        for name, _ in ENCODINGS:
            copy = copies[name]
            if name in taken and copy and int(os.path.getmtime(copy)) >= int(os.path.getmtime(path)):
                chosen, encoding = copy, name
                break
        try:
            f = open(chosen, "rb")
        except OSError:
            self.send_error(404, "File not found")
            return None
        try:
            size = os.fstat(f.fileno()).st_size
            self.encoding = encoding  # for the log line send_response writes
            self.send_response(200)
            self.send_header("Content-Type", self.guess_type(path))
            if encoding:
                self.send_header("Content-Encoding", encoding)
            if any(copies.values()):
                self.send_header("Vary", "Accept-Encoding")
            self.send_header("Content-Length", str(size))
            self.send_header("Last-Modified", self.date_time_string(int(os.path.getmtime(path))))
            self.send_header("Cache-Control", "no-cache")
            self.end_headers()
            return f
        except Exception:
            f.close()
            raise

    def list_directory(self, path):
        """No folder is listed."""
        self.send_error(404, "File not found")
        return None

    def log_request(self, code="-", size="-"):
        sent = f" ({self.encoding})" if self.encoding else ""
        self.log_message('"%s" %s%s', self.requestline, code, sent)


class Server(http.server.ThreadingHTTPServer):
    def handle_error(self, request, client_address):
        """One line for a request that failed (a client gone mid-reply), not a traceback."""
        error = sys.exc_info()[1]
        if not isinstance(error, (BrokenPipeError, ConnectionResetError)):
            print(f"web-serve: a request from {client_address[0]} failed: {error!r}", file=sys.stderr, flush=True)


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: web-serve.py DIRECTORY PORT")
    directory, port = sys.argv[1], sys.argv[2]
    if not os.path.isfile(os.path.join(directory, "index.html")):
        sys.exit(f"web-serve: no index.html in {directory}: build the site with scripts/web")
    if not port.isdigit() or not 1 <= int(port) <= 65535:
        sys.exit(f"web-serve: the port is a number from 1 to 65535, not '{port}'")
    handler = functools.partial(Handler, directory=directory)
    try:
        server = Server(("127.0.0.1", int(port)), handler)
    except OSError as e:
        sys.exit(f"web-serve: cannot listen on 127.0.0.1:{port}: {e.strerror}")
    print(f"web: serving http://127.0.0.1:{port}/ (Ctrl-C stops)", file=sys.stderr, flush=True)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass


if __name__ == "__main__":
    main()
