# SPDX-License-Identifier: LGPL-2.1-or-later
"""The reliability campaign's inputs (tests/campaign/reliability-campaign.py): each case is one bad or edge
value for one property of one element, with what a careful user expects of it."""
SECRET = 'hunter2x'  # a password that must never appear in any message
BAD = b'\xff\xfe'.decode('utf-8', 'surrogateescape')  # invalid UTF-8, carried in a str
# What a careful user expects: refused; accepted; 'either' = judge by hand; 'defer' = a valid start-time
# property changed while playing: a warning naming it, applied at the next start.
R, A, E, D = 'refuse', 'accept', 'either', 'defer'

def case(el, prop, value, expect, mode='launch', extra=None, **kw):
    """One input. extra: other properties of the element; kw: caps, nbuf, tracked, blame."""
    if mode == 'launch' and value is not None and (
            value == '' or len(value) > 100000 or any(c < ' ' or '\udc80' <= c <= '\udcff' for c in value)):
        mode = 'before-gi'  # no command line carries these ("prop=" alone takes the next token as value)
    return dict(el=el, prop=prop, value=value, expect=expect, mode=mode, extra=extra or {}, **kw)

def group(el, prop, refuse=(), accept=(), either=(), **kw):
    return ([case(el, prop, v, R, **kw) for v in refuse] + [case(el, prop, v, A, **kw) for v in accept]
            + [case(el, prop, v, E, **kw) for v in either])

def each(el, table, expect=R, **kw):
    """table: {property: 'values separated by spaces'}, all with the same expectation."""
    return [case(el, prop, v, expect, **kw) for prop, values in table.items() for v in values.split()]

def fx(*names):
    return ['@FX@/' + n for n in names]

def colortrack_cases():
    ct, thr = 'colortrack', {'mode': 'threshold'}
    out = group(ct, 'template-location', refuse=['/dev/zero', '/dev/null', '/' + 'a' * 5000] + fx(*(
        'missing.png dir empty.png garbage.png one.png seven.png huge.png big.png bomb.png trunc.png fifo_in loop '
        'dangling dir/ transparent.png').split(), 'good.png\n', BAD + '.png'),
        accept=fx('good.png', 'eight.png', 'frame.png', 'good_link'), either=[''])
    out += group(ct, 'init-box', refuse=(
        'abc 1,2,3 1,2,3,4,5 0,0,7,7 400,400,10,10 0,0,321,241 0,0,0,0 nan,0,10,10 inf,0,10,10 1e309,0,10,10 '
        '10;10;16;16 2147483647,2147483647,2147483647,2147483647 -2147483648,0,16,16 99999999999999999999,0,16,16'
        ).split() + [',' * 35000], accept='0,0,8,8 0,0,320,240 312,232,8,8'.split(),
        either=['', ' 10 , 10 , 16 , 16 '] + '-10,-10,64,64 300,200,64,64 10,10,16.5,16.5 0x10,0,16,16 '
        '10,10,16,16,'.split())
    out += group(ct, 'bins', refuse=['', '1' * 70000] + (
        '0,16,8 257,16,8 16,16 16,16,8,8 -1,16,8 a,b,c 16.5,16,8 nan,16,8 99999999999999999999,16,8 ,, 16,,8 16,16,8,'
        ).split(), accept=['1,1,1', '256,256,256'], either=[' 16,16,8'])
    out += group(ct, 'channel-weights', refuse=[''] + (
        '0,0,0 -0,0,1e-320 1,1,2 -1,1,1 nan,1,1 inf,1,1 1,1 1e-320,1e-320,1e-320 0.0005,0,0 1,1,1,1 a,b,c '
        '0,0,0.0009999').split(), accept=['0.001,0,0', '1,1,1', '0,0,1'])
    bad_hsv = [''] + '361,0,0 -1,0,0 0,1.5,0 0,0,-0.1 nan,0,0 inf,0.5,0.5 0,0 a,b,c 0,0,0,0'.split()
    out += group(ct, 'hsv-lower', refuse=bad_hsv, accept=['0,0,0'], extra=thr)
    out += group(ct, 'hsv-upper', refuse=bad_hsv, accept=['360,1,1'], extra=thr)
    out.append(case(ct, 'hsv-upper', '360,0.5,1', R, extra={**thr, 'hsv-lower': '0,0.9,0'}, blame=['hsv-lower']))
    out += each(ct, {
        'match-threshold': '-1 2 nan inf abc', 'likelihood-threshold': 'nan -0.1', 'measurement-noise': '0 -1 1e300',
        'process-noise': '-1 nan', 'scale-min': '0.1 2', 'scale-max': '0.5 3', 'scale-step': '0 1',
        'search-margin': '-1 1e9', 'max-coast-frames': '-1 99999', 'click-box-size': '0 7 99999',
        'trail-length': '-1', 'max-objects': '0 65', 'morph-size': '256', 'verify-tolerance': '-1 nan',
        'model-update-rate': '2', 'method': 'bogus 7', 'color-space': '9 lab', 'draw': 'bogus 0xffffffff',
        'mode': '5 bogus', 'verify': '-1', 'adapt-aspect': 'maybe', 'post-messages': '2'})
    out += group(ct, 'min-area', refuse=['0', '2147483648', '76801'], accept=['76800'], extra=thr)
    out += each(ct, {'match-threshold': '0 1', 'max-coast-frames': '0', 'trail-length': '0'}, A)
    # GStreamer's parser (gst_value_deserialize for a guint, 1.22) wraps 2^32 to 0 before colortrack sees it:
    # the element is given 0, a valid length. Through gi the same value is refused by GLib.
    out += each(ct, {'trail-length': '4294967296'}, E)
    out += [case(ct, 'template-location', '@FX@/good.png', R, extra={'init-box': '144,104,32,32'},
                 blame=['template-location', 'init-box']),
            case(ct, 'template-location', '@FX@/good.png', R, extra=thr, blame=['template-location'])]
    out += [case(ct, 'scale-max', '1', A, extra={'scale-min': '1'}), case(ct, 'morph-size', '0', A, extra=thr),
            case(ct, 'scale-step', '0.5', A, extra={'scale-min': '0.5', 'scale-max': '2'})]
    return out

def stream_cases():
    """Caps, first-frame EOS and each element's baseline, which must run silently (videotestsrc: 320x240)."""
    out, ct = [case('robotctl', None, None, A, tracked=True)], 'colortrack'
    for el, verdict in ((ct, R), ('robotctl', A), ('trackpublish', A)):
        out += [case(el, None, None, verdict, caps='video/x-raw,' + caps) for caps in
                'interlace-mode=interleaved width=1,height=1 format=GRAY16_LE format=ARGB64'.split()]
        out += [case(el, None, None, A, nbuf=0), case(el, None, None, A, nbuf=1), case(el, None, None, A)]
    out += [case(ct, None, None, R, caps='video/x-raw,' + caps) for caps in
            'width=7,height=7 width=4096,height=2 format=I420_10LE format=GRAY8 format=NV21'.split()]
    out += [case(ct, None, None, A, caps='video/x-raw,' + caps) for caps in
            'width=321,height=241 format=I420 format=YUY2 framerate=0/1'.split()]
    return out + [case(ct, None, None, R, caps='video/x-raw,width=1,height=1', extra={'mode': 'threshold'}),
                  case(ct, 'template-location', '@FX@/good.png', A, nbuf=1), case(ct, 'mode', 'threshold', A, nbuf=1),
                  case(ct, 'template-location', '@FX@/missing.png', R, nbuf=0)]

def robotctl_cases():
    rc, mav = 'robotctl', {'protocol': 'mavlink'}
    out = group(rc, 'location', refuse=fx('nodir/x', 'dir', 'fifo_out', 'loop', 'dangling') + [
        '', '/dev/full', '/proc/version', 'a' * 5000, 'C:\\robot.txt'] + (
        'udp:1.2.3.4:5 udp:127.0.0.1:14550 udp//127.0.0.1:5 tcp://127.0.0.1:5 serial:///dev/ttyUSB0 file:///tmp/x '
        'udp://127.0.0.1:0 udp://host:0 udp://[::1 udp://127.0.0.1:65536 udp://127.0.0.1:-1 udp://127.0.0.1: '
        'udp://:5 udp:// udp://nonexistent.invalid:5 udp://127.0.0.1:5/path udp://127.0.0.1:5?x=1 udp://127.0.0.1 '
        'udp://127.0.0.1:5:6 udp://224.0.0.1:14550 udp://239.255.255.250:1900 udp://[ff02::1]:14550').split(),
        accept=('- ./udp:x cmds2.out /dev/null udp://127.0.0.1:@UDP@ udp://localhost:@UDP@ udp://[::1]:@UDP@ '
                '@FX@/rfifo @FX@/good.png').split(),
        either=['UDP://127.0.0.1:@UDP@', ' ', 'cmds.out\n', BAD + '.out'])
    out += group(rc, 'device', refuse=['/dev/ttyNOPE', '/dev/null', '', 'COM3'] + fx('good.png', 'dir', 'fifo_out'))
    out.append(case(rc, 'device', '/dev/null', R, extra={'location': 'cmds.out'}, blame=['device', 'location']))
    out += group(rc, 'hfov', refuse='0 0.5 179.9999 180 1e-300 nan inf -1'.split(), accept=['1', '170'], extra=mav)
    out += group(rc, 'max-rate', refuse=['0', '-1', '721', 'nan'], accept=['720'], extra=mav)
    out += group(rc, 'max-speed', refuse=['0', '51'], accept=['50'], extra={**mav, 'mavlink-mode': 'follow'})
    out += group(rc, 'output-scale', refuse=['0', '32768'], accept=['1'], extra={'protocol': 'text'})
    out += group(rc, 'zone-chars', refuse=['', 'FB RS', 'ĉĝĥĵŝ', 'FBLR\t', 'x' * 70000, BAD + 'LRS', 'FBLR', 'FBLRSX',
                                           'FFLRS'], accept=['12345', 'fblrs'])
    out += group(rc, 'roi-type', refuse=[''], accept=['a b', 'a"b\\c'], either=['x' * 70000, BAD])
    out += each(rc, {
        'rate': '0 0.1 1001 nan inf', 'baud-rate': '0 49 4000001', 'data-bits': '4 9', 'stop-bits': '0 3',
        'lost-timeout': '0', 'turn-gain': '-1 -101 nan 101', 'drive-gain': '-0.5', 'turn-integral-gain': '-1',
        'turn-rate-gain': '-1', 'drive-integral-gain': '-1', 'drive-rate-gain': '-1', 'set-point': '0',
        'min-score': '2', 'target-id': '-2', 'latency': '3', 'max-linear': '2', 'max-angular': '-1',
        'search-speed': '2', 'hysteresis': '2', 'max-linear-accel': '-1', 'turn-deadband': '1.5',
        'protocol': 'bogus 9', 'mavlink-mode': 'x', 'controller': '7', 'parity': '9', 'flow-control': 'x',
        'lock-on': 'x', 'distance-cue': 'x'})
    out += each(rc, {'system-id': '0 256 4294967295 -1', 'component-id': '0 256', 'target-system': '256',
                            'target-component': '256', 'link-timeout': '60001 -1'}, extra=mav)
    out += each(rc, {'rate': '0.5 1000', 'turn-gain': '0'}, A)
    # A non-standard rate is refused with device= (start); with location= (here) any serial setting away from
    # its default is warned about as ignored.
    out += each(rc, {'baud-rate': '12345 115200'}, E)
    out += each(rc, {'target-system': '0', 'target-component': '0', 'link-timeout': '0'}, A, extra=mav)
    return out + [case(rc, 'hysteresis', '0.5', E, extra={'turn-deadband': '0.1'})]

def trackpublish_cases():
    tp, plain, tls = 'trackpublish', {'address': 'tcp://127.0.0.1:@BROKER@'}, {'address': 'ssl://127.0.0.1:@BROKER@'}
    out = group(tp, 'location', refuse=fx('nodir/x.jsonl', 'dir', 'fifo_out', 'loop', 'dangling') + [
        '/proc/version', 'a' * 5000, '/dev/full'], accept='- /dev/null tracks2.jsonl @FX@/rfifo ./udp:x'.split(),
        either=['', 'udp:1.2.3.4:5', 'tcp://127.0.0.1:1883'])
    out += group(tp, 'address', refuse=['', ' ', 'x' * 70000, BAD + ':1883', 'tcp://127.0.0.1:@BROKER@ extra'] + (
        'tcp://127.0.0.1:0 tcp://127.0.0.1:65536 tcp://127.0.0.1:-1 tcp://:1883 tcp:// tcp:/127.0.0.1:1883 '
        'tcp:127.0.0.1:1883 udp://127.0.0.1:1883 http://127.0.0.1:1883 ws://127.0.0.1:1883 tcp://[::1 '
        f'tcp://127.0.0.1:1883/path tcp://127.0.0.1:1 tcp://host.invalid:1883 tcp://user:{SECRET}@127.0.0.1:1 '
        'ssl://127.0.0.1:@BROKER@').split(),
        accept=['tcp://127.0.0.1:@BROKER@', '127.0.0.1:@BROKER@', 'tcp://localhost:@BROKER@'],
        either=['127.0.0.1', 'mqtt://127.0.0.1:@BROKER@'])
    out.append(case(tp, 'address', 'tcp://127.0.0.1:1', R, extra={'fail-on-connect': 'true'}))
    out += group(tp, 'topic', refuse=['', ' ', '   ', 't' * 65536, 't' * 70000, BAD + '/a', '{unknown}', 'a/{x'] +
                 '# a/# + a/+/b $SYS/x $foo a#b a+b'.split(),
                 accept=['a b', 'ĉ/ĝ', '{source}{source}'], either=['t' * 65535, 'a/b/', '/', 'a//b'])
    out += group(tp, 'client-id', refuse=['x' * 65536, 'x' * 70000, BAD], accept=['a/#', 'ĉĝ', 'x' * 23],
                 either=['', 'x' * 65535])
    out += group(tp, 'source', refuse=['+', '#', 'x' * 70000, BAD, 'a\nb', 'a\tb'], accept=['a"b'], either=['', 'a/b'],
                 blame=['source', 'topic'])
    out += [case(tp, 'password', 'x', E), case(tp, 'username', '', A), case(tp, 'username', 'u' * 70000, R),
            case(tp, 'password', SECRET, A, extra={'username': 'u'}),
            case(tp, 'password', SECRET, R, extra={'username': 'u', 'address': 'tcp://127.0.0.1:1'},
                 blame=['address']),
            case(tp, 'tls-verify', 'false', E, extra=plain), case(tp, 'tls-key-file', '@FX@/ca.pem', E, extra=tls),
            case(tp, 'tls-ca-file', '/etc/ssl/certs/ca-certificates.crt', E, extra=tls, blame=['address'])]
    out += each(tp, {'tls-ca-file': '@FX@/ca.pem /etc/ssl/certs/ca-certificates.crt', 'tls-cert-file': '@FX@/ca.pem',
                     'tls-key-file': '@FX@/ca.pem'}, extra=plain)
    out += each(tp, {'tls-ca-file': '@FX@/missing.pem @FX@/ca.pem @FX@/empty.png @FX@/dir @FX@/fifo_in',
                     'tls-cert-file': '@FX@/missing.pem @FX@/garbage.png', 'tls-key-file': '@FX@/missing.pem'},
                extra=tls)
    out += each(tp, {'mqtt-qos': '-1 3 nan', 'max-queued': '0 10000001', 'drain-timeout': '600001 -1',
                            'fail-on-connect': 'maybe'})
    out += group(tp, 'roi-type', refuse=[''], either=['x' * 70000])
    out += group(tp, 'tags', refuse=['{', '[1]', '"x"', 'null', '{"a":1}{}', BAD, '{"a":1,"a":2}', '{"a":"x\\u0000"}',
                                     '{"b":{"c":1,"c":2}}'], accept=['{"site":"dock-3"}', '{}'])
    out += [case(tp, 'tls-key-file', '@FX@/client.key', R, extra=tls, blame=['tls-key-file', 'tls-cert-file'])]
    return out + [case(tp, None, None, A, nbuf=0, extra=plain)]

def playing_cases():
    """Values set while PLAYING: the docs promise a warning, the old value kept and read back."""
    P, ct, rc, tp = 'playing', 'colortrack', 'robotctl', 'trackpublish'
    out = group(ct, 'template-location', refuse=fx(*'missing.png dir empty.png garbage.png one.png huge.png big.png '
                                                   'fifo_in'.split()), accept=fx('good.png'), mode=P)
    out += group(ct, 'init-box', refuse=['abc', '0,0,7,7', '400,400,10,10'], mode=P)
    out += each(ct, {'bins': '0,16,8', 'channel-weights': '0,0,0', 'mode': 'threshold',
                            'match-threshold': 'nan'}, mode=P)
    out += each(ct, {'hsv-lower': '361,0,0', 'min-area': '999999'}, mode=P, extra={'mode': 'threshold'})
    out += each(rc, {'location': 'udp://127.0.0.1:0 /nonexistent/x @FX@/fifo_out @FX@/dir udp:1.2.3.4:5'},
                       mode=P)
    out += each(rc, {'device': '/dev/null', 'hfov': '0', 'zone-chars': 'FBLR', 'turn-gain': '-1',
                            'lost-timeout': '0'}, mode=P) + [case(rc, 'roi-type', '', R, mode=P)]
    out += group(tp, 'location', refuse=['@FX@/nodir/x', '@FX@/fifo_out'], mode=P)
    out += each(tp, {'topic': '#', 'address': 'tcp://127.0.0.1:0', 'tls-ca-file': '@FX@/ca.pem'}, mode=P)
    out += each(rc, {'location': 'cmds2.out', 'protocol': 'mavlink', 'rate': '5'}, D, mode=P)
    return out + each(tp, {'location': 'tracks2.jsonl', 'mqtt-qos': '2', 'source': 'x'}, D, mode=P)


def all_cases():
    return colortrack_cases() + robotctl_cases() + trackpublish_cases() + stream_cases() + playing_cases()
