#!/usr/bin/env python3
"""Hostile-user reliability campaign for colortrack, robotctl and trackpublish (issue 22).

Feeds several hundred bad or edge inputs to the three elements, each in its own process group with a hard
timeout and in a fresh empty working directory, and tallies per element: error, warning, silent-accept,
hang, crash, refusals that do not name the property, and files created where the input did not point.

  python3 tests/campaign/reliability-campaign.py --plugin-path build/gst [--out DIR] [--jobs 2]

Values set before start go through gst-launch-1.0 lines (what a user types). Values set while PLAYING, and
values no command line can carry (invalid UTF-8, newlines, > 100 kB), go through a worker mode of this same
script run by a Python that has PyGObject (this one, else /usr/bin/python3); without one they are skipped.
Standard library only (plus gi in the worker). Per-case results go to DIR/results.jsonl.
"""
import argparse
import json
import os
import re
import shutil
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import time
import zlib
from concurrent.futures import ThreadPoolExecutor

TIMEOUT = 15  # s per case: every element promises to start, run 8 frames and stop far within this
CAPS = 'video/x-raw,width=320,height=240,framerate=30/1'
SECRET = 'hunter2x'  # a password that must never appear in any message
FILE_PROPS = {'template-location', 'location', 'device', 'tls-ca-file', 'tls-cert-file', 'tls-key-file'}
MQTT_PROPS = {'address', 'topic', 'client-id', 'source', 'username', 'password', 'qos', 'max-queued',
              'drain-timeout', 'fail-on-connect', 'tls-ca-file', 'tls-cert-file', 'tls-key-file', 'tls-verify'}
URL_LIKE = re.compile(r'^[A-Za-z][A-Za-z0-9+.-]*:')  # "scheme:..." is an address, never a file name
UNDECODABLE = '<message text is not valid UTF-8>'
BAD = b'\xff\xfe'.decode('utf-8', 'surrogateescape')  # invalid UTF-8, carried in a str
# What a careful user expects: refused; accepted; 'either' = judge by hand; 'defer' = a valid start-time
# property changed while playing: a warning naming it, applied at the next start.
R, A, E, D = 'refuse', 'accept', 'either', 'defer'


# ---------------------------------------------------------------- fixtures

def png_bytes(w, h, alpha=False, with_data=True):
    """A PNG written by hand: a red square with a white bar, or all transparent with alpha."""
    px = b'\x00\x00\x00\x00' if alpha else None

    def row(y):
        colour = b'\xff\xff\xff' if h // 3 <= y < 2 * h // 3 else b'\xc8\x1e\x1e'
        return b'\x00' + (px or colour) * w

    def chunk(kind, data):
        return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data))

    ihdr = struct.pack('>IIBBBBB', w, h, 8, 6 if alpha else 2, 0, 0, 0)
    idat = chunk(b'IDAT', zlib.compress(b''.join(row(y) for y in range(h)), 1)) if with_data else b''
    return b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', ihdr) + idat + chunk(b'IEND', b'')


def make_master(fx):
    """Shared read-only fixtures; each case gets hard links to them (see populate)."""
    os.makedirs(fx)
    pngs = {'good.png': (32, 32), 'eight.png': (8, 8), 'one.png': (1, 1), 'seven.png': (7, 8),
            'frame.png': (320, 240), 'big.png': (400, 300), 'huge.png': (4096, 4096)}
    for name, (w, h) in pngs.items():
        write(os.path.join(fx, name), png_bytes(w, h))
    write(os.path.join(fx, 'transparent.png'), png_bytes(32, 32, alpha=True))
    write(os.path.join(fx, 'bomb.png'), png_bytes(100000, 100000, with_data=False))  # header only
    write(os.path.join(fx, 'trunc.png'), png_bytes(32, 32)[:60])
    write(os.path.join(fx, 'empty.png'), b'')
    write(os.path.join(fx, 'garbage.png'), bytes(range(256)) * 64)
    write(os.path.join(fx, 'ca.pem'), b'-----BEGIN CERTIFICATE-----\nnot base64 !!\n-----END CERTIFICATE-----\n')


def write(path, data):
    with open(path, 'wb') as f:
        f.write(data)


def populate(fx, master):
    """Per-case fixtures: FIFOs, links and folders made fresh so that no case sees another's state."""
    os.makedirs(os.path.join(fx, 'dir'))
    for name in os.listdir(master):
        os.link(os.path.join(master, name), os.path.join(fx, name))
    os.mkfifo(os.path.join(fx, 'fifo_in'))   # nobody will ever write: a template read must not wait
    os.mkfifo(os.path.join(fx, 'fifo_out'))  # nobody will ever read: an output open must not wait
    os.symlink('loop', os.path.join(fx, 'loop'))
    os.symlink('nodir/x', os.path.join(fx, 'dangling'))
    os.symlink('good.png', os.path.join(fx, 'good_link'))


def snapshot(root):
    out = set()
    for d, dirs, files in os.walk(root):
        out.update(os.path.join(d, n) for n in dirs + files)
    return out


# ---------------------------------------------------------------- cases

def case(el, prop, value, expect=R, mode='launch', extra=None, **kw):
    """One input. extra: other properties; kw: caps, nbuf, tracked (robotctl behind colortrack), blame."""
    needs_gi = value is not None and (value == '' or len(value) > 100000 or any(c < ' ' or '\udc80' <= c <= '\udcff'
                                                                  for c in value))
    if mode == 'launch' and needs_gi:
        mode = 'before-gi'  # gst-launch cannot carry these (prop= with nothing takes the next token)
    return dict(el=el, prop=prop, value=value, expect=expect, mode=mode, extra=extra or {}, **kw)


def many(el, prop, pairs, **kw):
    return [case(el, prop, v, x, **kw) for v, x in pairs]


def refuse_all(el, table, **kw):
    """table: {prop: [values]} all of which a careful user expects to be refused."""
    return [case(el, p, v, R, **kw) for p, vs in table.items() for v in vs]


def colortrack_cases():
    ct = 'colortrack'
    out = many(ct, 'template-location', [
        ('@FX@/missing.png', R), ('@FX@/dir', R), ('@FX@/empty.png', R), ('@FX@/garbage.png', R),
        ('@FX@/one.png', R), ('@FX@/seven.png', R), ('@FX@/huge.png', R), ('@FX@/big.png', R),
        ('@FX@/bomb.png', R), ('@FX@/trunc.png', R), ('@FX@/fifo_in', R), ('/dev/zero', R), ('/dev/null', R),
        ('@FX@/loop', R), ('@FX@/dangling', R), ('', E), ('@FX@/dir/', R), ('/' + 'a' * 5000, R),
        ('@FX@/transparent.png', R), ('@FX@/good.png\n', R), ('@FX@/' + BAD + '.png', R),
        ('@FX@/good.png', A), ('@FX@/eight.png', A), ('@FX@/frame.png', A), ('@FX@/good_link', A)])
    out += many(ct, 'init-box', [
        ('', E), ('abc', R), ('1,2,3', R), ('1,2,3,4,5', R), ('0,0,7,7', R), ('-10,-10,64,64', E),
        ('300,200,64,64', E), ('400,400,10,10', R), ('0,0,321,241', R), ('0,0,0,0', R), ('nan,0,10,10', R),
        ('inf,0,10,10', R), ('1e309,0,10,10', R), ('10,10,16.5,16.5', E), ('0x10,0,16,16', E),
        (' 10 , 10 , 16 , 16 ', E), ('10;10;16;16', R), (','.join(['2147483647'] * 4), R),
        ('-2147483648,0,16,16', R), ('99999999999999999999,0,16,16', R), (',' * 35000, R),
        ('10,10,16,16,', E), ('0,0,8,8', A), ('0,0,320,240', A), ('312,232,8,8', A)])
    out += many(ct, 'bins', [
        ('', R), ('0,16,8', R), ('257,16,8', R), ('16,16', R), ('16,16,8,8', R), ('-1,16,8', R),
        ('a,b,c', R), ('16.5,16,8', R), ('nan,16,8', R), ('99999999999999999999,16,8', R), (',,', R),
        ('16,,8', R), ('16,16,8,', R), ('1' * 70000, R), ('1,1,1', A), ('256,256,256', A), (' 16,16,8', E)])
    out += many(ct, 'channel-weights', [
        ('0,0,0', R), ('-0,0,1e-320', R), ('1,1,2', R), ('-1,1,1', R), ('nan,1,1', R), ('inf,1,1', R),
        ('1,1', R), ('', R), ('1e-320,1e-320,1e-320', R), ('0.0005,0,0', R), ('1,1,1,1', R), ('a,b,c', R),
        ('0,0,0.0009999', R), ('0.001,0,0', A), ('1,1,1', A), ('0,0,1', A)])
    thr = {'mode': 'threshold'}
    for p in ('hsv-lower', 'hsv-upper'):
        out += many(ct, p, [(v, R) for v in ('', '361,0,0', '-1,0,0', '0,1.5,0', '0,0,-0.1', 'nan,0,0',
                                             'inf,0.5,0.5', '0,0', 'a,b,c', '0,0,0,0')], extra=thr)
    out += [case(ct, 'hsv-lower', '0,0,0', A, extra=thr), case(ct, 'hsv-upper', '360,1,1', A, extra=thr),
            case(ct, 'hsv-upper', '360,0.5,1', R, extra={**thr, 'hsv-lower': '0,0.9,0'},
                 blame=['hsv-lower', 'hsv-upper'])]
    out += refuse_all(ct, {
        'match-threshold': ['-1', '2', 'nan', 'inf', 'abc'], 'likelihood-threshold': ['nan', '-0.1'],
        'measurement-noise': ['0', '-1', '1e300'], 'process-noise': ['-1', 'nan'],
        'scale-min': ['0.1', '2'], 'scale-max': ['0.5', '3'], 'scale-step': ['0', '1'],
        'search-margin': ['-1', '1e9'], 'max-coast-frames': ['-1', '99999'],
        'click-box-size': ['0', '7', '99999'], 'trail-length': ['-1', '4294967296'],
        'max-objects': ['0', '65'], 'morph-size': ['256'], 'verify-tolerance': ['-1', 'nan'],
        'model-update-rate': ['2'], 'method': ['bogus', '7'], 'color-space': ['9', 'lab'],
        'draw': ['bogus', '0xffffffff'], 'mode': ['5', 'bogus'], 'verify': ['-1'],
        'adapt-aspect': ['maybe'], 'post-messages': ['2']})
    out += many(ct, 'min-area', [('0', R), ('2147483648', R), ('76801', R), ('76800', A)], extra=thr)
    out += [case(ct, 'match-threshold', '0', A), case(ct, 'match-threshold', '1', A),
            case(ct, 'max-coast-frames', '0', A), case(ct, 'trail-length', '0', A),
            case(ct, 'scale-max', '1', A, extra={'scale-min': '1'}),
            case(ct, 'scale-step', '0.5', A, extra={'scale-min': '0.5', 'scale-max': '2'}),
            case(ct, 'morph-size', '0', A, extra=thr)]
    return out


def caps_cases():
    out = []
    for el, verdict in (('colortrack', R), ('robotctl', A), ('trackpublish', A)):
        for caps, v in (('video/x-raw,width=320,height=240,interlace-mode=interleaved', verdict),
                        ('video/x-raw,width=1,height=1', verdict),
                        ('video/x-raw,format=GRAY16_LE,width=320,height=240', verdict),
                        ('video/x-raw,format=ARGB64,width=320,height=240', verdict)):
            out.append(case(el, None, None, v, caps=caps))
        for n in (0, 1):
            out.append(case(el, None, None, A, nbuf=n))
        out.append(case(el, None, None, A))  # the baseline alone: must be silent
    ct = 'colortrack'
    out.append(case('robotctl', None, None, A, tracked=True))
    for caps, v in (('video/x-raw,width=7,height=7', R), ('video/x-raw,format=I420_10LE,width=320,height=240', R),
                    ('video/x-raw,format=GRAY8,width=320,height=240', R),
                    ('video/x-raw,format=NV21,width=320,height=240', R),
                    ('video/x-raw,width=321,height=241', A), ('video/x-raw,width=4096,height=2', R),
                    ('video/x-raw,format=I420,width=320,height=240', A),
                    ('video/x-raw,format=YUY2,width=320,height=240', A),
                    ('video/x-raw,width=320,height=240,framerate=0/1', A)):
        out.append(case(ct, None, None, v, caps=caps))
    out += [case(ct, None, None, R, caps='video/x-raw,width=1,height=1', extra={'mode': 'threshold'}),
            case(ct, 'template-location', '@FX@/good.png', A, nbuf=1),
            case(ct, 'mode', 'threshold', A, nbuf=1),
            case(ct, 'template-location', '@FX@/missing.png', R, nbuf=0)]
    return out


def robotctl_cases():
    rc = 'robotctl'
    out = many(rc, 'location', [
        ('@FX@/nodir/x', R), ('@FX@/dir', R), ('@FX@/fifo_out', R), ('udp:1.2.3.4:5', R),
        ('udp:127.0.0.1:14550', R), ('udp//127.0.0.1:5', R), ('tcp://127.0.0.1:5', R),
        ('serial:///dev/ttyUSB0', R), ('file:///tmp/x', R), ('udp://127.0.0.1:0', R), ('udp://host:0', R),
        ('udp://[::1', R), ('udp://127.0.0.1:65536', R), ('udp://127.0.0.1:-1', R), ('udp://127.0.0.1:', R),
        ('udp://:5', R), ('udp://', R), ('udp://nonexistent.invalid:5', R), ('udp://127.0.0.1:5/path', R),
        ('udp://127.0.0.1:5?x=1', R), ('udp://127.0.0.1', R), ('udp://127.0.0.1:5:6', R),
        ('UDP://127.0.0.1:@UDP@', E), ('C:\\robot.txt', R), ('', R), (' ', E), ('/dev/full', R),
        ('/proc/version', R), ('a' * 5000, R), ('@FX@/loop', R), ('@FX@/dangling', R),
        ('cmds.out\n', E), (BAD + '.out', E), ('-', A), ('./udp:x', A), ('cmds2.out', A), ('/dev/null', A),
        ('udp://127.0.0.1:@UDP@', A), ('udp://localhost:@UDP@', A), ('udp://[::1]:@UDP@', A),
        ('@RFIFO@', A), ('@FX@/good.png', A)])
    out += many(rc, 'device', [('/dev/ttyNOPE', R), ('@FX@/good.png', R), ('@FX@/dir', R), ('/dev/null', R),
                               ('@FX@/fifo_out', R), ('', R), ('COM3', R)])
    out.append(case(rc, 'device', '/dev/null', R, extra={'location': 'cmds.out'}, blame=['device', 'location']))
    mav, follow, text = {'protocol': 'mavlink'}, {'protocol': 'mavlink', 'mavlink-mode': 'follow'}, {'protocol': 'text'}
    out += many(rc, 'hfov', [(v, R) for v in ('0', '0.5', '179.9999', '180', '1e-300', 'nan', 'inf', '-1')]
                + [('1', A), ('170', A)], extra=mav)
    out += many(rc, 'max-rate', [('0', R), ('-1', R), ('721', R), ('nan', R), ('720', A)], extra=mav)
    out += many(rc, 'max-speed', [('0', R), ('51', R), ('50', A)], extra=follow)
    out += many(rc, 'output-scale', [('0', R), ('32768', R), ('1', A)], extra=text)
    out += many(rc, 'zone-chars', [
        ('', R), ('FBLR', R), ('FBLRSX', R), ('FFLRS', R), ('FB RS', R), ('ĉĝĥĵŝ', R), ('FBLR\t', R),
        ('x' * 70000, R), (BAD + 'LRS', R), ('12345', A), ('fblrs', A)])
    out += many(rc, 'roi-type', [('', R), ('x' * 70000, E), (BAD, E), ('a b', A), ('a"b\\c', A)])
    out += refuse_all(rc, {
        'rate': ['0', '0.1', '1001', 'nan', 'inf'], 'baud-rate': ['0', '49', '12345', '4000001'],
        'data-bits': ['4', '9'], 'stop-bits': ['0', '3'], 'lost-timeout': ['0'],
        'turn-gain': ['-1', '-101', 'nan', '101'], 'drive-gain': ['-0.5'], 'turn-integral-gain': ['-1'],
        'turn-rate-gain': ['-1'], 'drive-integral-gain': ['-1'], 'drive-rate-gain': ['-1'],
        'set-point': ['0'], 'min-score': ['2'], 'target-id': ['-2'], 'latency': ['3'], 'max-linear': ['2'],
        'max-angular': ['-1'], 'search-speed': ['2'], 'hysteresis': ['2'], 'max-linear-accel': ['-1'],
        'turn-deadband': ['1.5'], 'protocol': ['bogus', '9'], 'mavlink-mode': ['x'], 'controller': ['7'],
        'parity': ['9'], 'flow-control': ['x'], 'lock-on': ['x'], 'distance-cue': ['x']})
    out += refuse_all(rc, {'system-id': ['0', '256', '4294967295', '-1'], 'component-id': ['0', '256'],
                           'target-system': ['256'], 'target-component': ['256'],
                           'link-timeout': ['60001', '-1']}, extra=mav)
    out += [case(rc, 'rate', '0.5', A), case(rc, 'rate', '1000', A), case(rc, 'baud-rate', '115200', A),
            case(rc, 'turn-gain', '0', A), case(rc, 'hysteresis', '0.5', E, extra={'turn-deadband': '0.1'}),
            case(rc, 'target-system', '0', A, extra=mav), case(rc, 'target-component', '0', A, extra=mav),
            case(rc, 'link-timeout', '0', A, extra=mav)]
    return out


def trackpublish_cases():
    tp = 'trackpublish'
    out = many(tp, 'location', [
        ('@FX@/nodir/x.jsonl', R), ('@FX@/dir', R), ('@FX@/fifo_out', R), ('/proc/version', R),
        ('a' * 5000, R), ('@FX@/loop', R), ('@FX@/dangling', R), ('/dev/full', R), ('', E),
        ('udp:1.2.3.4:5', E), ('tcp://127.0.0.1:1883', E), ('-', A), ('/dev/null', A),
        ('tracks2.jsonl', A), ('@RFIFO@', A), ('./udp:x', A)])
    out += many(tp, 'address', [(v, R) for v in (
        'tcp://127.0.0.1:0', 'tcp://127.0.0.1:65536', 'tcp://127.0.0.1:-1', 'tcp://:1883', 'tcp://',
        'tcp:/127.0.0.1:1883', 'tcp:127.0.0.1:1883', 'udp://127.0.0.1:1883', 'http://127.0.0.1:1883',
        'ws://127.0.0.1:1883', 'tcp://[::1', 'tcp://127.0.0.1:1883/path', '', ' ', 'x' * 70000,
        BAD + ':1883', 'tcp://127.0.0.1:@BROKER@ extra', 'tcp://127.0.0.1:1', 'tcp://host.invalid:1883',
        'tcp://user:' + SECRET + '@127.0.0.1:1', 'ssl://127.0.0.1:@BROKER@')]
        + [('127.0.0.1', E), ('tcp://127.0.0.1:@BROKER@', A), ('127.0.0.1:@BROKER@', A),
           ('tcp://localhost:@BROKER@', A), ('mqtt://127.0.0.1:@BROKER@', E)])
    out.append(case(tp, 'address', 'tcp://127.0.0.1:1', R, extra={'fail-on-connect': 'true'}))
    out += many(tp, 'topic', [(v, R) for v in (
        '', '#', 'a/#', '+', 'a/+/b', '$SYS/x', '$foo', 'a#b', 'a+b', 't' * 65536, 't' * 70000, BAD + '/a')]
        + [('t' * 65535, E), ('a/b/', A), ('/', A), ('a b', A), ('ĉ/ĝ', A), ('{source}{source}', A),
           ('{unknown}', A)])
    out += many(tp, 'client-id', [('x' * 65536, R), ('x' * 70000, R), (BAD, R), ('', E), ('a/#', A),
                                  ('ĉĝ', A), ('x' * 65535, E), ('x' * 23, A)])
    out += many(tp, 'source', [('+', R), ('#', R), ('x' * 70000, R), (BAD, R), ('', E), ('a/b', E),
                               ('a"b', A), ('a\nb', E)], blame=['source', 'topic'])
    out += [case(tp, 'password', 'x', E), case(tp, 'username', '', A), case(tp, 'username', 'u' * 70000, R),
            case(tp, 'password', SECRET, A, extra={'username': 'u'}),
            case(tp, 'password', SECRET, R, extra={'username': 'u', 'address': 'tcp://127.0.0.1:1'},
                 blame=['address'])]
    plain = {'address': 'tcp://127.0.0.1:@BROKER@'}
    for p in ('tls-ca-file', 'tls-cert-file', 'tls-key-file'):
        out.append(case(tp, p, '@FX@/ca.pem', R, extra=plain))
    out += [case(tp, 'tls-ca-file', '/etc/ssl/certs/ca-certificates.crt', R, extra=plain),
            case(tp, 'tls-verify', 'false', E, extra=plain)]
    tls = {'address': 'ssl://127.0.0.1:@BROKER@'}
    out += many(tp, 'tls-ca-file', [(v, R) for v in ('@FX@/missing.pem', '@FX@/ca.pem', '@FX@/empty.png',
                                                     '@FX@/dir', '@FX@/fifo_in')], extra=tls)
    out += many(tp, 'tls-cert-file', [('@FX@/missing.pem', R), ('@FX@/garbage.png', R)], extra=tls)
    out += [case(tp, 'tls-key-file', '@FX@/missing.pem', R, extra=tls),
            case(tp, 'tls-key-file', '@FX@/ca.pem', E, extra=tls),
            case(tp, 'tls-ca-file', '/etc/ssl/certs/ca-certificates.crt', E, extra=tls, blame=['address'])]
    out += refuse_all(tp, {'qos': ['-1', '3', 'nan'], 'max-queued': ['0', '10000001'],
                           'drain-timeout': ['600001', '-1'], 'fail-on-connect': ['maybe']})
    out += many(tp, 'roi-type', [('', R), ('x' * 70000, E)])
    out.append(case(tp, None, None, A, nbuf=0, extra=plain))
    return out


def playing_cases():
    """Values set while PLAYING: the docs promise a warning, the old value kept and read back."""
    P, ct, rc, tp = 'playing', 'colortrack', 'robotctl', 'trackpublish'
    out = many(ct, 'template-location', [(v, R) for v in (
        '@FX@/missing.png', '@FX@/dir', '@FX@/empty.png', '@FX@/garbage.png', '@FX@/one.png',
        '@FX@/huge.png', '@FX@/big.png', '@FX@/fifo_in')] + [('@FX@/good.png', A)], mode=P)
    out += many(ct, 'init-box', [('abc', R), ('0,0,7,7', R), ('400,400,10,10', R)], mode=P)
    out += [case(ct, 'bins', '0,16,8', R, mode=P), case(ct, 'channel-weights', '0,0,0', R, mode=P),
            case(ct, 'mode', 'threshold', R, mode=P), case(ct, 'match-threshold', 'nan', R, mode=P),
            case(ct, 'hsv-lower', '361,0,0', R, mode=P, extra={'mode': 'threshold'}),
            case(ct, 'min-area', '999999', R, mode=P, extra={'mode': 'threshold'})]
    out += many(rc, 'location', [(v, R) for v in (
        'udp://127.0.0.1:0', '/nonexistent/x', '@FX@/fifo_out', '@FX@/dir', 'udp:1.2.3.4:5')]
        + [('cmds2.out', D)], mode=P)
    out += refuse_all(rc, {'device': ['/dev/null'], 'hfov': ['0'], 'zone-chars': ['FBLR'], 'turn-gain': ['-1'],
                           'lost-timeout': ['0'], 'roi-type': ['']}, mode=P)
    out += [case(rc, 'protocol', 'mavlink', D, mode=P), case(rc, 'rate', '5', D, mode=P)]
    out += many(tp, 'location', [('@FX@/nodir/x', R), ('@FX@/fifo_out', R), ('tracks2.jsonl', D)], mode=P)
    out += refuse_all(tp, {'topic': ['#'], 'address': ['tcp://127.0.0.1:0'], 'tls-ca-file': ['@FX@/ca.pem']},
                      mode=P)
    out += [case(tp, 'qos', '2', D, mode=P), case(tp, 'source', 'x', D, mode=P)]
    return out


# ---------------------------------------------------------------- pipelines

def quote(v):
    return '"' + v.replace('\\', '\\\\').replace('"', '\\"') + '"'


def props_for(c):
    """Baseline properties (a run that is silent by itself), then the extras, then the case's own."""
    p, ex = c['prop'], c['extra']
    touched = set(ex) | ({p} if c['mode'] != 'playing' else set())  # playing: p comes later
    base = {}
    if c['el'] == 'colortrack' and not touched & {'template-location', 'init-box', 'mode'}:
        base = {'init-box': '144,104,32,32'}
    elif c['el'] == 'robotctl' and not touched & {'location', 'device'}:
        base = {'location': 'cmds.out'}
    elif c['el'] == 'trackpublish':
        mqtt = bool(({p} | set(ex)) & MQTT_PROPS)
        base = {'address': 'tcp://127.0.0.1:@BROKER@', 'drain-timeout': '4000'} if mqtt else {}
        if not mqtt and 'location' not in touched:
            base = {'location': 'tracks.jsonl'}
    props = {**base, **ex}
    if p is not None and c['mode'] == 'launch':
        props[p] = c['value']
    return props


def pipeline(c, ctx):
    """Tokens as a shell leaves them after its quoting: gst-launch escapes each, gi needs them quoted."""
    live = c['mode'] == 'playing'
    src = ['videotestsrc', 'pattern=ball', f"num-buffers={600 if live else c.get('nbuf', 8)}"]
    src += (['is-live=true'] if live else []) + ['!', c.get('caps', CAPS), '!']
    dut = [c['el'], 'name=dut'] + [(k, subst(v, ctx)) for k, v in props_for(c).items()]
    if c['el'] != 'robotctl':
        return src + dut + ['!', 'fakesink']
    return src + (['colortrack', 'init-box=144,104,32,32', '!'] if c.get('tracked') else []) + dut


def subst(s, ctx):
    for k, v in ctx.items():
        s = s.replace(f'@{k}@', v)
    return s


def named_paths(c, ctx, cwd):
    """Files the input points at: only these may appear."""
    out = set()
    props = {**props_for(c), **({c['prop']: c['value']} if c['prop'] else {})}
    for k, v in props.items():
        v = subst(v, ctx)
        if k in FILE_PROPS and v not in ('', '-') and not URL_LIKE.match(v):
            out.add(os.path.normpath(os.path.join(cwd, v)))
    return out


# ---------------------------------------------------------------- running

def run_case(c, ctx, gi_python, env):
    tmp = tempfile.mkdtemp(prefix='case-', dir=ctx['WORK'])
    cwd, fx = os.path.join(tmp, 'cwd'), os.path.join(tmp, 'fx')
    os.makedirs(cwd)
    populate(fx, ctx['MASTER'])
    cctx = {**ctx, 'FX': fx, 'RFIFO': os.path.join(fx, 'rfifo')}
    os.mkfifo(cctx['RFIFO'])
    reader = os.open(cctx['RFIFO'], os.O_RDONLY | os.O_NONBLOCK)  # the valid "FIFO with a reader" case
    before = snapshot(cwd) | snapshot(fx)
    try:
        res = execute(c, cctx, gi_python, env, cwd)
        named = named_paths(c, cctx, cwd)
        res['stray'] = sorted(os.path.relpath(p, tmp) for p in (snapshot(cwd) | snapshot(fx)) - before
                              if not any(p == n or n.startswith(p + os.sep) for n in named))
    finally:
        os.close(reader)
        shutil.rmtree(tmp, ignore_errors=True)
    return res


def execute(c, ctx, gi_python, env, cwd):
    tokens = pipeline(c, ctx)
    if c['mode'] == 'launch':
        argv = ['gst-launch-1.0'] + [t if isinstance(t, str) else f'{t[0]}={t[1]}' for t in tokens]
        argv = [a.encode('utf-8', 'surrogateescape') for a in argv]
    else:
        desc = ' '.join(t if isinstance(t, str) else f'{t[0]}={quote(t[1])}' for t in tokens)
        spec = os.path.join(cwd, '..', 'spec.json')
        with open(spec, 'w') as f:
            json.dump({'desc': desc, 'mode': c['mode'], 'prop': c['prop'],
                       'value': subst(c['value'], ctx)}, f)
        argv = [gi_python, os.path.abspath(__file__), '--worker', spec]
    t0 = time.monotonic()
    out, err, rc, how = run_group(argv, cwd, env)
    return dict(secs=round(time.monotonic() - t0, 2), rc=rc, killed=how, out=out, err=err)


def run_group(argv, cwd, env):
    """Own process group, output to files. gst-launch catches SIGSEGV and spins: seen, that is a crash.
    On timeout try Ctrl-C (SIGINT) first, as a user would, then SIGKILL."""
    logs = [os.path.join(cwd, '..', n) for n in ('out.log', 'err.log')]
    with open(logs[0], 'wb') as fo, open(logs[1], 'wb') as fe:
        p = subprocess.Popen(argv, cwd=cwd, env=env, stdout=fo, stderr=fe, stdin=subprocess.DEVNULL,
                             start_new_session=True)
        how, end = None, time.monotonic() + TIMEOUT
        while p.poll() is None:
            if b'Spinning.  Please run' in open(logs[1], 'rb').read():
                os.killpg(p.pid, signal.SIGKILL)
            elif time.monotonic() > end:
                how = interrupt(p)
                break
            time.sleep(0.05)
        p.wait()
    return decode(open(logs[0], 'rb').read()), decode(open(logs[1], 'rb').read()), p.returncode, how


def interrupt(p):
    os.killpg(p.pid, signal.SIGINT)
    try:
        p.wait(3)
        return 'timeout, ended by SIGINT'
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        return 'timeout, SIGINT ignored, SIGKILL'


def decode(b):
    return b.decode('utf-8', 'replace')


# ---------------------------------------------------------------- output parsing and classification

ELEMENT_MSG = re.compile(r'^(ERROR|WARNING): from element (/\S+): (.*)$')
PARSE_MSG = re.compile(r'^(?:WARNING: erroneous pipeline|ERROR: pipeline could not be constructed): (.*)$')
GLIB_MSG = re.compile(r'^(?:\*\* )?\([^)]*\): (?:([\w-]+)-)?(WARNING|CRITICAL) \*\*: [\d:.]+: (.*)$')
CRASH = re.compile(r'Caught SIG|AddressSanitizer|runtime error:|terminate called|Segmentation fault|stack smashing|'
                   r'double free|Aborted')


def parse_messages(out, err):
    msgs, lines = [], (out + '\n' + err).splitlines()
    for i, line in enumerate(lines):
        if line.startswith('MSG '):  # from the gi worker
            msgs.append(json.loads(line[4:]))
        elif m := ELEMENT_MSG.match(line):
            dbg = ' '.join(lines[i + 2:i + 4]) if i + 1 < len(lines) and 'debug info' in lines[i + 1] else ''
            msgs.append(dict(kind=m[1].lower(), src=m[2], text=m[3], debug=dbg))
        elif m := PARSE_MSG.match(line):
            msgs.append(dict(kind='error', src='gst-launch parser', text=m[1], debug=''))
        elif m := GLIB_MSG.match(line):
            kind = 'critical' if m[2] == 'CRITICAL' else 'warning'
            msgs.append(dict(kind=kind, src=m[1] or 'glib', text=m[3], debug=''))
    return msgs


def classify(res, msgs):
    if res['killed']:
        return 'hang'
    if (res['rc'] or 0) < 0 or CRASH.search(res['err']):
        return 'crash'
    if 'Traceback (most recent call last)' in res['err']:
        return 'harness-error'  # the gi worker itself failed: not the element's fault
    if any(m['kind'] == 'error' for m in msgs) or res['rc'] not in (0, None):
        return 'error'
    return 'warning' if any(m['kind'] in ('warning', 'critical') for m in msgs) else 'silent-accept'


def names_property(c, cls, msgs):
    """Does the refusal name the property in quotes? None when there is no property or no refusal."""
    blame = c.get('blame') or ([c['prop']] if c['prop'] else [])
    if cls not in ('error', 'warning') or not blame or any(m['text'] == UNDECODABLE for m in msgs):
        return None
    kinds = ('error',) if cls == 'error' else ('warning', 'critical')
    text = ' '.join(m['text'] + ' ' + m['debug'] for m in msgs if m['kind'] in kinds)
    return any(re.search(r"['\"`‘]" + re.escape(p) + r"['\"`’]", text) for p in blame)


def names_value(c, msgs):
    token = (c['value'] or '').replace('@FX@/', '')[:40]
    return len(token) >= 3 and any(token in m['text'] + m['debug'] for m in msgs)


def worker_fields(out):
    stage, result = None, {}
    for line in out.splitlines():
        if line.startswith('STAGE '):
            stage = line[6:]
        elif line.startswith('RESULT '):
            result = json.loads(line[7:])
    return stage, result


def short(v, n=60):
    if v is None:
        return '-'
    s = v if len(v) <= n else f'{v[:24]}...({len(v)} chars)'
    return repr(s)[1:-1]


def record(c, res):
    msgs = parse_messages(res['out'], res['err'])
    cls = classify(res, msgs)
    stage, wres = worker_fields(res['out'])
    rec = dict(element=c['el'], mode=c['mode'], prop=c['prop'], value=short(c['value'], 200),
               value_len=len(c['value'] or ''), extra=c['extra'], tracked=c.get('tracked'), caps=c.get('caps'), nbuf=c.get('nbuf'),
               expect=c['expect'], cls=cls, names_property=names_property(c, cls, msgs),
               names_value=names_value(c, msgs),
               stray=res['stray'], rc=res['rc'], secs=res['secs'], killed=res['killed'],
               criticals=[m['text'][:200] for m in msgs if m['kind'] == 'critical'],
               messages=[{**m, 'text': m['text'][:300], 'debug': m['debug'][:200]} for m in msgs[:4]])
    if SECRET in (c['value'] or '') + json.dumps(c['extra']):
        rec['leaks_secret'] = SECRET in res['out'] + res['err']
    if c['mode'] != 'launch':
        rec.update(stage=stage, readback=wres.get('readback'), old=wres.get('old'),
                   null_s=wres.get('null_s'), harness=wres.get('harness'))
        rec['readback_new_after_refusal'] = (c['mode'] == 'playing' and cls in ('error', 'warning') and c['expect'] != D
                                             and bool(wres.get('reads_new')))
    if cls == 'crash' or (cls == 'error' and not msgs):
        rec['stderr_tail'] = res['err'][-600:]
    return rec


# ---------------------------------------------------------------- gi worker (runs in a child process)

def worker(spec_path):
    spec = json.load(open(spec_path))
    import ctypes
    import gi
    gi.require_version('Gst', '1.0')
    from gi.repository import GObject, Gst
    Gst.init(None)
    pipe = Gst.parse_launch(spec['desc'])
    el, bus = pipe.get_by_name('dut'), pipe.get_bus()
    say('STAGE', 'built')
    old = readback(el, spec['prop'])
    if spec['mode'] == 'before-gi':
        set_value(el, spec, ctypes, GObject, Gst)
        say('STAGE', 'set; starting')
        pipe.set_state(Gst.State.PLAYING)
        pump(bus, 10, Gst)
    else:
        pipe.set_state(Gst.State.PLAYING)
        pipe.get_state(3 * Gst.SECOND)
        if pump(bus, 0.8, Gst) is None:  # still running: now the hostile set
            say('STAGE', 'playing; setting')
            set_value(el, spec, ctypes, GObject, Gst)
            say('STAGE', 'set while playing')
            pump(bus, 1.5, Gst)
        else:
            say('STAGE', 'baseline stopped before the set')
    rb = readback(el, spec['prop'])
    say('STAGE', 'set_state(NULL)')
    t0 = time.monotonic()
    pipe.set_state(Gst.State.NULL)
    say('RESULT', {'readback': rb, 'old': old, 'reads_new': rb == spec['value'] != old,
                   'null_s': round(time.monotonic() - t0, 3)})


def set_value(el, spec, ctypes, GObject, Gst):
    prop, value = spec['prop'], spec['value']
    kind = el.find_property(prop).value_type
    if kind == GObject.TYPE_STRING:
        # Through C so that invalid UTF-8 reaches the element as the bytes a C application would pass.
        lib = ctypes.CDLL('libgobject-2.0.so.0')
        get = ctypes.pythonapi.PyCapsule_GetPointer
        get.restype, get.argtypes = ctypes.c_void_p, [ctypes.py_object, ctypes.c_char_p]
        lib.g_object_set(ctypes.c_void_p(get(el.__gpointer__, None)), prop.encode(),
                         value.encode('utf-8', 'surrogateescape'), None)
    elif kind in (GObject.TYPE_DOUBLE, GObject.TYPE_FLOAT):
        el.set_property(prop, float(value))  # typed, as an application sets it: GLib checks the range
    elif kind in (GObject.TYPE_INT, GObject.TYPE_UINT, GObject.TYPE_INT64, GObject.TYPE_UINT64):
        el.set_property(prop, int(value))
    else:  # enums, flags, booleans: from the string, as gst-launch does
        Gst.util_set_object_arg(el, prop, value)


def readback(el, prop):
    try:
        v = el.get_property(prop)
        return v if isinstance(v, (str, int, float, bool, type(None))) else str(v)
    except Exception as e:  # e.g. invalid UTF-8 cannot become a Python str
        return f'<unreadable: {type(e).__name__}>'


def pump(bus, secs, Gst):
    """Print ERROR/WARNING messages as they come; return 'eos', 'error', or None if time ran out."""
    end = time.monotonic() + secs
    types = Gst.MessageType.ERROR | Gst.MessageType.WARNING | Gst.MessageType.EOS
    while (left := end - time.monotonic()) > 0:
        m = bus.timed_pop_filtered(int(left * Gst.SECOND), types)
        if m is None:
            return None
        if m.type == Gst.MessageType.EOS:
            return 'eos'
        kind = 'error' if m.type == Gst.MessageType.ERROR else 'warning'
        try:
            err, dbg = m.parse_error() if kind == 'error' else m.parse_warning()
            text = err.message
        except UnicodeDecodeError:  # GError messages must be UTF-8: an application cannot read this one
            text, dbg = UNDECODABLE, ''
        say('MSG', dict(kind=kind, src=m.src.get_path_string(), text=text, debug=dbg or ''))
        if kind == 'error':
            return 'error'
    return None


def say(tag, payload):
    print(tag, payload if isinstance(payload, str) else json.dumps(payload), flush=True)


# ---------------------------------------------------------------- services, tally, main

def free_port(kind=socket.SOCK_STREAM):
    with socket.socket(socket.AF_INET, kind) as s:
        s.bind(('127.0.0.1', 0))
        return s.getsockname()[1]


def start_broker(out):
    """A local mosquitto so that valid MQTT inputs run silently and bad ones are not masked."""
    port, exe = free_port(), shutil.which('mosquitto') or '/usr/sbin/mosquitto'
    if not os.path.exists(exe):
        return None, 1
    conf = os.path.join(out, 'mosquitto.conf')
    write(conf, f'listener {port} 127.0.0.1\nallow_anonymous true\n'.encode())
    p = subprocess.Popen([exe, '-c', conf], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                         start_new_session=True)
    time.sleep(0.5)
    return p, port


def find_gi_python():
    probe = "import gi; gi.require_version('Gst','1.0'); from gi.repository import Gst"
    for exe in (sys.executable, '/usr/bin/python3'):
        if exe and os.path.exists(exe) and subprocess.run([exe, '-c', probe], capture_output=True).returncode == 0:
            return exe
    return None


COLUMNS = ['inputs', 'error', 'warning', 'silent-accept', 'hang', 'crash', 'not-naming-prop', 'stray-files',
           'glib-critical', 'secret-leak', 'readback-new']


def tally(recs):
    rows = {}
    for el in ('colortrack', 'robotctl', 'trackpublish', 'total'):
        rs = [r for r in recs if el in ('total', r['element'])]
        row = {'inputs': len(rs), 'not-naming-prop': sum(r['names_property'] is False for r in rs),
               'stray-files': sum(bool(r['stray']) for r in rs), 'glib-critical': sum(bool(r['criticals']) for r in rs),
               'secret-leak': sum(bool(r.get('leaks_secret')) for r in rs),
               'readback-new': sum(bool(r.get('readback_new_after_refusal')) for r in rs)}
        row.update({k: sum(r['cls'] == k for r in rs) for k in ('error', 'warning', 'silent-accept', 'hang', 'crash')})
        rows[el] = row
    print(f"\n{'element':<13}" + ''.join(f'{c:>16}' for c in COLUMNS))
    for el, row in rows.items():
        print(f'{el:<13}' + ''.join(f'{row[c]:>16}' for c in COLUMNS))
    return rows


def label(r):
    where = f"{r['element']} [{r['mode']}{', behind colortrack' if r.get('tracked') else ''}]"
    extra = ' '.join(f'{k}={short(v, 30)}' for k, v in r['extra'].items())
    what = f"{r['prop']}={r['value']!s}" if r['prop'] else f"caps={r['caps']} num-buffers={r['nbuf']}"
    return f'{where} {what} {extra}'.rstrip()


def first_text(r):
    return r['messages'][0]['text'][:160] if r['messages'] else ''


def print_lists(recs):
    sections = [
        ('HANGS', lambda r: r['cls'] == 'hang', lambda r: f"{r['killed']}; stage={r.get('stage')}"),
        ('CRASHES', lambda r: r['cls'] == 'crash', lambda r: f"rc={r['rc']}"),
        ('STRAY FILES', lambda r: r['stray'], lambda r: ', '.join(r['stray'])),
        ('GLIB CRITICALS', lambda r: r['criticals'], lambda r: r['criticals'][0]),
        ('SECRET LEAKED', lambda r: r.get('leaks_secret'), first_text),
        ('REFUSALS NOT NAMING THE PROPERTY', lambda r: r['names_property'] is False,
         lambda r: f"{r['cls']}{' (names the value)' if r['names_value'] else ''}: {first_text(r)}"),
        ('PLAYING: REFUSED BUT READS BACK THE NEW VALUE', lambda r: r.get('readback_new_after_refusal'), first_text),
        ('SLOW set_state(NULL) > 1 s', lambda r: (r.get('null_s') or 0) > 1, lambda r: f"{r['null_s']} s"),
        ('SILENT-ACCEPT OF INPUTS EXPECTED TO BE REFUSED (or, "defer", warned)',
         lambda r: r['cls'] == 'silent-accept' and r['expect'] in (R, D),
         lambda r: ''),
        ('SILENT-ACCEPT, EXPECTATION "either" (judge)', lambda r: r['cls'] == 'silent-accept' and r['expect'] == E,
         lambda r: ''),
        ('VALID INPUTS REFUSED', lambda r: r['expect'] == A and r['cls'] in ('error', 'warning'), first_text),
    ]
    for title, pick, why in sections:
        hits = [r for r in recs if pick(r)]
        print(f'\n== {title}: {len(hits)}')
        for r in hits:
            print(f'  {label(r)}' + (f'  -> {why(r)}' if why(r) else ''))
    ok = sum(r['cls'] == 'silent-accept' and r['expect'] == A for r in recs)
    print(f'\nsilent-accepts of inputs expected valid: {ok} (listed in results.jsonl)')


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--plugin-path', required=True)
    ap.add_argument('--out', default='/tmp/reliability-campaign')
    ap.add_argument('--jobs', type=int, default=2)
    ap.add_argument('--only', help='run only cases whose element or property contains this')
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    env = {**os.environ, 'GST_PLUGIN_PATH': os.path.abspath(args.plugin_path), 'LC_ALL': 'C.UTF-8'}
    env.pop('GST_DEBUG', None)
    work = tempfile.mkdtemp(prefix='campaign-')
    make_master(os.path.join(work, 'master'))
    broker, bport = start_broker(args.out)
    udp = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)  # a listening UDP peer for valid udp:// cases
    udp.bind(('127.0.0.1', 0))
    udp6 = socket.socket(socket.AF_INET6, socket.SOCK_DGRAM)  # localhost may resolve to ::1 first
    udp6.bind(('::1', udp.getsockname()[1]))
    ctx = {'WORK': work, 'MASTER': os.path.join(work, 'master'), 'BROKER': str(bport),
           'UDP': str(udp.getsockname()[1])}
    gi_python = find_gi_python()
    cases = colortrack_cases() + robotctl_cases() + trackpublish_cases() + caps_cases() + playing_cases()
    skipped = [c for c in cases if c['mode'] != 'launch' and not gi_python]
    cases = [c for c in cases if c not in skipped and (not args.only or args.only in f"{c['el']} {c['prop']}")]
    print(f'{len(cases)} cases, gi worker: {gi_python or "none"} ({len(skipped)} skipped), '
          f'broker port {bport if broker else "none"}', flush=True)
    t0, recs = time.monotonic(), []
    try:
        with ThreadPoolExecutor(args.jobs) as pool, open(os.path.join(args.out, 'results.jsonl'), 'w') as f:
            for i, (c, res) in enumerate(zip(cases, pool.map(lambda c: run_case(c, ctx, gi_python, env), cases))):
                rec = record(c, res)
                recs.append(rec)
                f.write(json.dumps(rec) + '\n')
                print(f"[{i + 1}/{len(cases)}] {rec['cls']:<13} {res['secs']:5.1f}s {label(rec)[:110]}", flush=True)
    finally:
        if broker:
            broker.terminate()
            broker.wait()
        udp.close()
        udp6.close()
        shutil.rmtree(work, ignore_errors=True)
    rows = tally(recs)
    print_lists(recs)
    with open(os.path.join(args.out, 'summary.json'), 'w') as f:
        json.dump({'tally': rows, 'seconds': round(time.monotonic() - t0), 'skipped': len(skipped)}, f, indent=1)
    print(f'\n{len(recs)} inputs in {time.monotonic() - t0:.0f} s; per-case results: {args.out}/results.jsonl')


if __name__ == '__main__':
    if len(sys.argv) == 3 and sys.argv[1] == '--worker':
        worker(sys.argv[2])
    else:
        main()
