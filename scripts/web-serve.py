#!/usr/bin/env python3
"""Serves the site `scripts/web` builds as a static host serves it: a file with a precompressed
copy beside it (`web_bg.wasm.br`, `web_bg.wasm.gz`) goes out as that copy with `Content-Encoding`
when the request's `Accept-Encoding` takes it (brotli first, then gzip, else the file itself),
with the original's `Content-Type` (`application/wasm` for the module, which the browser needs to
compile it while it downloads) and `Vary: Accept-Encoding`.

usage: web-serve.py DIRECTORY PORT    (binds 127.0.0.1; `scripts/web --serve` runs it)
"""
import functools
import http.server
import os
import sys

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


class Handler(http.server.SimpleHTTPRequestHandler):
    extensions_map = {**http.server.SimpleHTTPRequestHandler.extensions_map, **TYPES}

    encoding = None

    def send_head(self):
        self.encoding = None
        path = self.translate_path(self.path)
        if os.path.isdir(path):
            index = os.path.join(path, "index.html")
            if not self.path.split("?", 1)[0].endswith("/") or not os.path.isfile(index):
                return super().send_head()  # the redirect to "dir/", or the listing
            path = index
        if not os.path.isfile(path):
            return super().send_head()  # 404
        # A copy older than its original is stale (a site half rebuilt): the original goes out.
        # Whole seconds: gzip and brotli give a copy its original's time, brotli without the
        # fraction.
        chosen, encoding = path, None
        taken = accepted(self.headers.get("Accept-Encoding"))
        for name, suffix in ENCODINGS:
            copy = path + suffix
            if name in taken and os.path.isfile(copy) and int(os.path.getmtime(copy)) >= int(os.path.getmtime(path)):
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
            if any(os.path.isfile(path + suffix) for _, suffix in ENCODINGS):
                self.send_header("Vary", "Accept-Encoding")
            self.send_header("Content-Length", str(size))
            self.send_header("Last-Modified", self.date_time_string(int(os.path.getmtime(path))))
            self.send_header("Cache-Control", "no-cache")
            self.end_headers()
            return f
        except Exception:
            f.close()
            raise

    def log_request(self, code="-", size="-"):
        sent = f" ({self.encoding})" if self.encoding else ""
        self.log_message('"%s" %s%s', self.requestline, code, sent)


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
        server = http.server.ThreadingHTTPServer(("127.0.0.1", int(port)), handler)
    except OSError as e:
        sys.exit(f"web-serve: cannot listen on 127.0.0.1:{port}: {e.strerror}")
    print(f"web: serving http://127.0.0.1:{port}/ (Ctrl-C stops)", file=sys.stderr, flush=True)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass


if __name__ == "__main__":
    main()
