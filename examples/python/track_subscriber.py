#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""A consumer of trackpublish's documents: subscribes to an MQTT broker, drops repeats, one line per document.

    track_subscriber.py --host broker.local                      # every camera (colortrack/#), until Ctrl-C
    track_subscriber.py --host broker.local --topic colortrack/cam1 --brief
    track_subscriber.py --host broker.local --count 300          # collect 300 documents, then exit

Subscribes at QoS 1 with a persistent session (a fixed client id, clean session off, `--clean` turns it off):
documents published while this consumer is away, or while the broker restarts (with `persistence true` in
mosquitto.conf), are kept by the broker and delivered when it comes back. QoS 1 may deliver a document twice;
repeats are dropped by (source, run, frame). A camera pipeline that restarts (systemd's Restart=always) counts
frames from 0 again under a new `run` id, so its documents are never taken for repeats. Documents without a
run (older trackpublish) fall back on a guess: a frame far below the newest one seen from that source
(`--restart-gap`, default 1000) starts a new run.

Prints each document as it arrived (one JSON line), or with `--brief` a short line
`cam1 frame 12: 1 object(s) #1 144,104 40x40 tracking 0.98`. Status lines go to stderr.
`--subscribe-only` connects, subscribes and exits: the broker then keeps documents for this client id until it
comes back.

Works with Eclipse Paho's Python client 1.6 (Debian 12's python3-paho-mqtt) and 2.x (Debian 13's), whose
Client() and callback signatures differ. Exit code 0, or 1 when `--timeout` passes before `--count` documents.
"""
import argparse
import json
import socket
import sys
import threading

import paho.mqtt.client as mqtt


class Deduper:
    """Tells new documents from repeats by (source, run) and frame; without a run id a frame far below the newest
    one starts a new run."""

    def __init__(self, restart_gap=1000, window=4096):
        self.restart_gap = restart_gap
        self.window = window  # frames kept per source: repeats are recent ones (at most a queue's worth)
        self.sources = {}  # source -> [newest frame, set of frames seen]

    def is_new(self, source, frame):
        state = self.sources.get(source)
        if state is None and isinstance(source, tuple):
            # A new run of a camera: keep its previous run (late repeats of it are still caught), forget older.
            runs = [k for k in self.sources if isinstance(k, tuple) and k[0] == source[0]]
            for old in runs[:-1]:
                del self.sources[old]
        if state is None or frame + self.restart_gap < state[0]:
            state = self.sources[source] = [frame, set()]  # first document, or the pipeline restarted
        if frame in state[1]:
            return False
        state[1].add(frame)
        state[0] = max(state[0], frame)
        if len(state[1]) > 2 * self.window:
            state[1] = {f for f in state[1] if f > state[0] - self.window}
        return True


def make_client(client_id, clean_session):
    """A Paho client for 1.6 and 2.x: 2.x wants the callback API version first (VERSION2 is used; the callbacks
    below take *args, so both signatures fit)."""
    if hasattr(mqtt, "CallbackAPIVersion"):
        return mqtt.Client(mqtt.CallbackAPIVersion.VERSION2, client_id=client_id, clean_session=clean_session)
    return mqtt.Client(client_id=client_id, clean_session=clean_session)


def code_of(reason):
    """An int from 1.6's int result codes and 2.x's ReasonCode objects."""
    return getattr(reason, "value", reason)


def brief(doc):
    objects = doc.get("objects") or []
    parts = [f"{doc.get('source')} frame {doc.get('frame')}: {len(objects)} object(s)"]
    for o in objects:
        score = o.get("score")
        parts.append(f"#{o.get('id')} {o.get('x')},{o.get('y')} {o.get('w')}x{o.get('h')} {o.get('state', '')}"
                     + (f" {score:.2f}" if isinstance(score, (int, float)) else ""))
    return " ".join(parts)


def connect_with_news(client, host, port):
    """Connects in the background, retried until a broker answers. A mistyped host would otherwise look like a
    hang: says where it connects, whether the name resolves, and when attempts fail."""
    failures = [0]

    def on_connect_fail(client, userdata, *rest):
        failures[0] += 1
        if failures[0] in (1, 10) or failures[0] % 100 == 0:  # said, without flooding a long wait
            print(f"cannot connect to {host}:{port} (attempt {failures[0]}): no broker answers there; retrying",
                  file=sys.stderr, flush=True)

    client.on_connect_fail = on_connect_fail  # paho-mqtt >= 1.6; an older one only stays silent
    client.reconnect_delay_set(1, 30)
    print(f"connecting to {host}:{port} (retried until a broker answers; Ctrl-C to stop)", file=sys.stderr,
          flush=True)
    try:
        socket.getaddrinfo(host, port)
    except OSError as e:
        print(f"warning: the host {host} does not resolve ({e}); retrying anyway", file=sys.stderr, flush=True)
    client.connect_async(host, port, keepalive=30)
    client.loop_start()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--host", default="localhost", help="broker host (default: localhost)")
    parser.add_argument("--port", type=int, default=1883, help="broker port (default: 1883)")
    parser.add_argument("--topic", default="colortrack/#", help="topic filter (default: colortrack/#)")
    parser.add_argument("--qos", type=int, default=1, choices=(0, 1, 2), help="subscription QoS (default: 1)")
    parser.add_argument("--client-id", default=f"colortrack-sub-{socket.gethostname()}",
                        help="client id: the broker keeps this id's session (default: colortrack-sub-HOSTNAME)")
    parser.add_argument("--clean", action="store_true", help="clean session: nothing kept while away")
    parser.add_argument("--username", help="broker user name")
    parser.add_argument("--password", help="broker password")
    parser.add_argument("--count", type=int, default=0, help="exit after this many new documents (0: never)")
    parser.add_argument("--timeout", type=float, help="give up (exit code 1) after this many seconds")
    parser.add_argument("--subscribe-only", action="store_true",
                        help="subscribe and exit (the broker keeps documents for this client id)")
    parser.add_argument("--brief", action="store_true", help="a short line per document instead of its JSON")
    parser.add_argument("--restart-gap", type=int, default=1000,
                        help="a frame this far below a source's newest starts a new run (default: 1000)")
    args = parser.parse_args()

    dedupe = Deduper(args.restart_gap)
    done = threading.Event()
    received = [0]  # new documents
    lock = threading.Lock()

    def on_connect(client, userdata, flags, reason, *properties):
        if code_of(reason) != 0:
            print(f"connection refused: {reason}", file=sys.stderr, flush=True)
            return
        present = flags.get("session present") if isinstance(flags, dict) else flags.session_present
        print(f"connected to {args.host}:{args.port} as {args.client_id} (session present: {bool(present)})",
              file=sys.stderr, flush=True)
        client.subscribe(args.topic, qos=args.qos)  # again on every connect: harmless when the session is kept

    def on_subscribe(client, userdata, mid, granted, *properties):
        if any(code_of(g) >= 128 for g in granted):
            print(f"subscription to {args.topic} refused", file=sys.stderr, flush=True)
            done.set()
            return
        print(f"subscribed to {args.topic} at QoS {code_of(granted[0])}", file=sys.stderr, flush=True)
        if args.subscribe_only:
            done.set()

    def on_message(client, userdata, message):
        try:
            doc = json.loads(message.payload)
            source, frame = (doc["source"], doc.get("run")), int(doc["frame"])
        except (ValueError, KeyError, TypeError):
            print(f"not a trackpublish document on {message.topic}: {message.payload[:80]!r}", file=sys.stderr,
                  flush=True)
            return
        with lock:
            if done.is_set() or not dedupe.is_new(source, frame):
                return
            print(brief(doc) if args.brief else message.payload.decode(), flush=True)
            received[0] += 1
            if args.count and received[0] >= args.count:
                done.set()

    client = make_client(args.client_id, clean_session=args.clean)
    client.on_connect = on_connect
    client.on_subscribe = on_subscribe
    client.on_message = on_message
    if args.username:
        client.username_pw_set(args.username, args.password)
    connect_with_news(client, args.host, args.port)
    try:
        finished = done.wait(args.timeout)
    except KeyboardInterrupt:
        finished = True
    client.disconnect()
    client.loop_stop()
    if not finished:
        print(f"timed out after {args.timeout} s with {received[0]} of {args.count} documents", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
