# SPDX-License-Identifier: LGPL-2.1-or-later
"""colortrack-studio's HTTP side: the standard library's threading server, the token, the body limits and
JSON, and the routes to the studio's requests (studio_pipeline.Studio)."""
import json
import secrets
import sys
import threading
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from urllib.parse import parse_qs, urlsplit

from studio_pipeline import BadRequest

MAX_BODY = 64 * 1024
MAX_STREAMS = 8          # MJPEG clients at once (each holds a thread)
MAX_CLIENTS = 32         # connections served at once; more are answered 503 (threads are not unbounded)
LOOPBACK_NAMES = ("127.0.0.1", "localhost", "[::1]")
REQUEST_TIMEOUT = 10     # seconds a client may take to send its request (slow clients are cut off)


class Handler(BaseHTTPRequestHandler):
    server_version = "colortrack-studio"
    protocol_version = "HTTP/1.1"
    timeout = REQUEST_TIMEOUT
    studio = None     # set by serve()
    token = None      # required when not listening on loopback
    page = b""
    streams = threading.BoundedSemaphore(MAX_STREAMS)

    def log_message(self, fmt_, *args):
        if self.server.verbose:
            super().log_message(fmt_, *args)

    def refusal(self):
        """Why this request may not be served, or None. With a token (off loopback), the token. On loopback,
        where no token is asked for: the Host must be a loopback name, so that a web page whose name was made
        to point at 127.0.0.1 (DNS rebinding) is refused, and an Origin must be that Host (another site's
        page)."""
        if self.token is not None:
            given = self.headers.get("X-Studio-Token") or parse_qs(urlsplit(self.path).query).get("token", [""])[0]
            if secrets.compare_digest(given.encode(), self.token.encode()):
                return None
            return "a token is needed: X-Studio-Token header or ?token="
        host = self.headers.get("Host", "")
        name = host.rsplit(":", 1)[0] if not host.endswith("]") else host
        if name not in LOOPBACK_NAMES:
            return f"Host {host[:80]!r} is not this studio's loopback address"
        origin = self.headers.get("Origin")
        if origin is not None and urlsplit(origin).netloc != host:
            return f"requests from {origin[:80]!r} are not served"
        return None

    def reply(self, status, body, content_type="application/json"):
        data = body if isinstance(body, bytes) else (json.dumps(body) + "\n").encode()
        self.send_response(status)
        self.send_header("Content-Type", content_type)
        self.send_header("Content-Length", str(len(data)))
        self.send_header("Cache-Control", "no-store")
        self.send_header("X-Frame-Options", "DENY")  # no other site frames the page under a user's clicks
        self.send_header("X-Content-Type-Options", "nosniff")
        self.end_headers()
        if self.command != "HEAD":
            self.wfile.write(data)

    def error(self, status, message):
        self.close_connection = True
        self.reply(status, {"error": message, "status": int(status)})

    def do_GET(self):
        if (why := self.refusal()) is not None:
            return self.error(HTTPStatus.FORBIDDEN, why)
        path = urlsplit(self.path).path
        if path in ("/", "/index.html"):
            return self.reply(HTTPStatus.OK, self.page, "text/html; charset=utf-8")
        if path == "/state":
            return self.reply(HTTPStatus.OK, self.studio.snapshot())
        if path in ("/video.mjpg", "/mask.mjpg"):
            return self.stream(path[1:-5])
        return self.error(HTTPStatus.NOT_FOUND, f"no such page: {path[:100]}")

    def stream(self, name):
        if name == "mask" and self.studio.maskct is None:
            return self.error(HTTPStatus.NOT_FOUND, "no mask: the studio runs mode=template")
        if not self.streams.acquire(blocking=False):
            return self.error(HTTPStatus.SERVICE_UNAVAILABLE, f"at most {MAX_STREAMS} video streams at once")
        try:
            self.close_connection = True
            self.send_response(HTTPStatus.OK)
            self.send_header("Content-Type", "multipart/x-mixed-replace; boundary=frame")
            self.send_header("Cache-Control", "no-store")
            self.end_headers()
            seq = 0
            while self.studio.running:
                seq, data, captured = self.studio.wait_frame(name, seq)
                if not data:
                    continue
                self.wfile.write(b"--frame\r\nContent-Type: image/jpeg\r\n" +
                                 f"Content-Length: {len(data)}\r\nX-Frame: {seq}\r\nX-Capture-Ns: {captured}\r\n\r\n".encode()
                                 + data + b"\r\n")
                self.wfile.flush()
        except (BrokenPipeError, ConnectionResetError, TimeoutError, OSError):
            pass
        finally:
            self.streams.release()

    def refuse_method(self):
        self.error(HTTPStatus.METHOD_NOT_ALLOWED, f"{self.command} is not served: GET or POST")

    do_PUT = do_DELETE = do_PATCH = do_OPTIONS = do_HEAD = refuse_method

    def do_POST(self):
        if (why := self.refusal()) is not None:
            return self.error(HTTPStatus.FORBIDDEN, why)
        # JSON only: another site's page can send a form or text/plain without asking, never JSON.
        if self.headers.get_content_type() != "application/json":
            return self.error(HTTPStatus.UNSUPPORTED_MEDIA_TYPE, "send the body as Content-Type: application/json")
        path = urlsplit(self.path).path
        actions = {"/select": self.studio.select, "/settings": self.studio.apply_settings,
                   "/stop": self.studio.stop, "/save": self.studio.save}
        if path not in actions:
            return self.error(HTTPStatus.NOT_FOUND, f"no such action: {path[:100]}")
        try:
            body = self.read_json()
            self.reply(HTTPStatus.OK, actions[path](body))
        except BadRequest as e:
            self.error(e.status, str(e))
        except Exception as e:  # noqa: BLE001 -- a bug of ours is a 500, never a dead server
            print(f"internal error on {path}: {e!r}", file=sys.stderr, flush=True)
            self.error(HTTPStatus.INTERNAL_SERVER_ERROR, "internal error")

    def read_json(self):
        if self.headers.get("Transfer-Encoding"):
            raise BadRequest(HTTPStatus.LENGTH_REQUIRED, "send the body with a Content-Length, not chunked")
        try:
            length = int(self.headers.get("Content-Length", "0"))
        except ValueError:
            raise BadRequest(HTTPStatus.BAD_REQUEST, "Content-Length is not a number") from None
        if length < 0:
            raise BadRequest(HTTPStatus.BAD_REQUEST, "negative Content-Length")
        if length > MAX_BODY:
            raise BadRequest(HTTPStatus.REQUEST_ENTITY_TOO_LARGE, f"body over {MAX_BODY} bytes")
        try:
            raw = self.rfile.read(length) if length else b"{}"
        except (TimeoutError, OSError):
            raise BadRequest(HTTPStatus.REQUEST_TIMEOUT, "the body did not arrive in time") from None
        if len(raw) != length:
            raise BadRequest(HTTPStatus.BAD_REQUEST, "body shorter than its Content-Length")
        try:
            body = json.loads(raw.decode("utf-8"), parse_constant=not_json)
        except (UnicodeDecodeError, ValueError, RecursionError) as e:
            raise BadRequest(HTTPStatus.BAD_REQUEST, f"the body is not JSON: {str(e)[:100]}") from None
        if not isinstance(body, dict):
            raise BadRequest(HTTPStatus.BAD_REQUEST, "the body must be a JSON object")
        return body


def not_json(constant):
    """Python's json reads NaN and Infinity, which JSON has not."""
    raise ValueError(f"{constant} is not JSON")


class Server(ThreadingHTTPServer):
    daemon_threads = True
    verbose = False
    request_queue_size = 64  # connections waiting to be accepted (the default 5 drops a burst of clients)
    clients = threading.BoundedSemaphore(MAX_CLIENTS)

    def process_request(self, request, client_address):
        """A thread per connection, at most MAX_CLIENTS of them: one more is answered 503 and closed."""
        if not self.clients.acquire(blocking=False):
            try:
                request.sendall(b"HTTP/1.1 503 Service Unavailable\r\nContent-Length: 0\r\nConnection: close\r\n\r\n")
            except OSError:
                pass
            self.shutdown_request(request)
            return
        super().process_request(request, client_address)

    def process_request_thread(self, request, client_address):
        try:
            super().process_request_thread(request, client_address)
        finally:
            self.clients.release()

    def handle_error(self, request, client_address):
        """A client that went away or stalled: one line, no traceback (a bug of ours is still printed)."""
        error = sys.exc_info()[1]
        if isinstance(error, (ConnectionError, TimeoutError)):
            if self.verbose:
                print(f"client {client_address[0]}: {error!r}", file=sys.stderr, flush=True)
            return
        super().handle_error(request, client_address)


def is_loopback(address):
    """Listening here needs no token. (IPv4 only: the server is.)"""
    return address == "localhost" or address.startswith("127.")

