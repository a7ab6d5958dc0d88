#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Hostile-user reliability campaign for colortrack, robotctl and trackpublish (issue 22): several hundred bad
or edge inputs, each in its own process group with a hard timeout and a fresh empty working directory; tallies
error / warning / silent-accept / hang / crash, refusals not naming the property, stray files. Before-start
values go through gst-launch-1.0 command lines (what a user types); values set while PLAYING, or that no
command line carries (empty, invalid UTF-8, control characters, > 100 kB), through this script's worker mode
under a Python with PyGObject (this one, else /usr/bin/python3), skipped without one. Run from the source tree:
  python3 tests/campaign/reliability-campaign.py --plugin-path build/gst [--out DIR] [--jobs 2] [--only TEXT]"""
import argparse, json, os, re, shutil, signal, socket, struct, subprocess, sys, tempfile, time, zlib  # noqa: E401
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from campaign_cases import A, D, E, R, SECRET, all_cases

TIMEOUT = 15  # s per case: every element promises to start, run 8 frames and stop far within this
CAPS = 'video/x-raw,width=320,height=240,framerate=30/1'
FILE_PROPS = {'template-location', 'location', 'device', 'tls-ca-file', 'tls-cert-file', 'tls-key-file'}
MQTT_PROPS = {'address', 'topic', 'client-id', 'source', 'username', 'password', 'mqtt-qos', 'max-queued',
              'drain-timeout', 'fail-on-connect', 'tls-ca-file', 'tls-cert-file', 'tls-key-file', 'tls-verify'}
URL_LIKE = re.compile(r'^[A-Za-z][A-Za-z0-9+.-]*:')  # "scheme:..." is an address, never a file name
UNDECODABLE = '<message text is not valid UTF-8>'

# ---- fixtures
def png_bytes(w, h, alpha=False, with_data=True):
    def row(y):
        px = b'\x00\x00\x00\x00' if alpha else b'\xff\xff\xff' if h // 3 <= y < 2 * h // 3 else b'\xc8\x1e\x1e'
        return b'\x00' + px * w
    def chunk(kind, data):
        return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data))
    ihdr = struct.pack('>IIBBBBB', w, h, 8, 6 if alpha else 2, 0, 0, 0)
    idat = chunk(b'IDAT', zlib.compress(b''.join(row(y) for y in range(h)), 1)) if with_data else b''
    return b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', ihdr) + idat + chunk(b'IEND', b'')

def make_master(fx):
    os.makedirs(fx)
    sizes = {'good': (32, 32), 'eight': (8, 8), 'one': (1, 1), 'seven': (7, 8), 'frame': (320, 240),
             'big': (400, 300), 'huge': (4096, 4096)}
    files = {f'{n}.png': png_bytes(w, h) for n, (w, h) in sizes.items()}
    files.update({'transparent.png': png_bytes(32, 32, alpha=True), 'trunc.png': png_bytes(32, 32)[:60],
                  'bomb.png': png_bytes(100000, 100000, with_data=False),  # a header promising 10^10 pixels
                  'empty.png': b'', 'garbage.png': bytes(range(256)) * 64,
                  'ca.pem': b'-----BEGIN CERTIFICATE-----\nnot base64 !!\n-----END CERTIFICATE-----\n',
                  'client.key': b'-----BEGIN PRIVATE KEY-----\nAA==\n-----END PRIVATE KEY-----\n'})
    for name, data in files.items():
        Path(fx, name).write_bytes(data)

def populate(fx, master):
    """Per-case fixtures: FIFOs, links and folders made fresh so that no case sees another's state."""
    os.makedirs(os.path.join(fx, 'dir'))
    for name in os.listdir(master):  # copies: a case may write into one (robotctl location=good.png)
        shutil.copyfile(os.path.join(master, name), os.path.join(fx, name))
    # fifo_in: never a writer, fifo_out: never a reader (no open may wait); rfifo: the parent reads (valid output)
    for name in ('fifo_in', 'fifo_out', 'rfifo'):
        os.mkfifo(os.path.join(fx, name))
    for name, target in (('loop', 'loop'), ('dangling', 'nodir/x'), ('good_link', 'good.png')):
        os.symlink(target, os.path.join(fx, name))

def snapshot(*roots):
    return {os.path.join(d, n) for root in roots for d, dirs, files in os.walk(root) for n in dirs + files}


# ---- pipelines
def props_for(c):
    """Baseline properties (a run that is silent by itself), then the extras, then the case's own."""
    p, ex = c['prop'], c['extra']
    touched = set(ex) | ({p} if c['mode'] != 'playing' else set())  # playing: p is set later
    base = {}
    if c['el'] == 'colortrack' and not touched & {'template-location', 'init-box', 'mode'}:
        base = {'init-box': '144,104,32,32'}
    elif c['el'] == 'robotctl' and not touched & {'location', 'device'}:
        base = {'location': 'cmds.out'}
    elif c['el'] == 'trackpublish' and ({p} | set(ex)) & MQTT_PROPS:
        base = {'address': 'tcp://127.0.0.1:@BROKER@', 'drain-timeout': '4000'}
    elif c['el'] == 'trackpublish' and 'location' not in touched:
        base = {'location': 'tracks.jsonl'}
    if c['el'] == 'trackpublish':
        base['add-empty-results'] = 'true'  # a document for every frame: videotestsrc's carry no object
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
    return re.sub(r'@([A-Z]+)@', lambda m: ctx.get(m[1], m[0]), s)

def named_paths(c, ctx, cwd):
    """Files the input points at: only these may appear."""
    props = list(props_for(c).items()) + [(c['prop'], c['value'])]  # playing: the base value, then the case's
    paths = [subst(v, ctx) for k, v in props if k in FILE_PROPS]
    return {os.path.normpath(os.path.join(cwd, v)) for v in paths if v not in ('', '-') and not URL_LIKE.match(v)}


# ---- running
def run_case(c, ctx, gi_python, env):
    tmp = tempfile.mkdtemp(prefix='case-', dir=ctx['WORK'])
    cwd, fxd = os.path.join(tmp, 'cwd'), os.path.join(tmp, 'fx')
    os.makedirs(cwd)
    populate(fxd, ctx['MASTER'])
    cctx = {**ctx, 'FX': fxd}
    reader = os.open(os.path.join(fxd, 'rfifo'), os.O_RDONLY | os.O_NONBLOCK)
    before = snapshot(cwd, fxd)
    try:
        res = execute(c, cctx, gi_python, env, cwd)
        named = named_paths(c, cctx, cwd)
        res['stray'] = sorted(os.path.relpath(p, tmp) for p in snapshot(cwd, fxd) - before
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
        spec = os.path.join(cwd, '..', 'spec.json')
        quote = lambda v: '"' + v.replace('\\', '\\\\').replace('"', '\\"') + '"'  # noqa: E731
        desc = ' '.join(t if isinstance(t, str) else f'{t[0]}={quote(t[1])}' for t in tokens)
        Path(spec).write_text(json.dumps({'desc': desc, 'mode': c['mode'], 'prop': c['prop'],
                                          'value': subst(c['value'], ctx)}))
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
            if b'Spinning.  Please run' in Path(logs[1]).read_bytes():
                os.killpg(p.pid, signal.SIGKILL)
            elif time.monotonic() > end:
                how = interrupt(p)
                break
            time.sleep(0.05)
        p.wait()
    out, err = (Path(log).read_bytes().decode('utf-8', 'replace') for log in logs)
    return out, err, p.returncode, how

def interrupt(p):
    os.killpg(p.pid, signal.SIGINT)
    try:
        p.wait(3)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        return 'timeout, SIGINT ignored, SIGKILL'
    return 'timeout, ended by SIGINT'


# ---- output parsing and classification
ELEMENT_MSG = re.compile(r'^(ERROR|WARNING): from element (/\S+): (.*)$')
PARSE_MSG = re.compile(r'^(?:WARNING: erroneous pipeline|ERROR: pipeline could not be constructed): (.*)$')
GLIB_MSG = re.compile(r'^(?:\*\* )?\([^)]*\): (?:([\w-]+)-)?(WARNING|CRITICAL) \*\*: [\d:.]+: (.*)$')
PYGLIB_MSG = re.compile(r'^\S+:\d+: (Warning): (.*)$')  # GLib's warning as PyGObject re-raises it
CRASH = re.compile(r'Caught SIG|AddressSanitizer|runtime error:|terminate called|Segmentation fault|double free')

def parse_messages(out, err):
    msgs, lines = [], (out + '\n' + err).splitlines()
    for i, line in enumerate(lines):
        if line.startswith('MSG '):  # from the gi worker
            msgs.append(json.loads(line[4:]))
        elif m := ELEMENT_MSG.match(line):
            dbg = ' '.join(lines[i + 2:i + 4]) if 'debug info' in ''.join(lines[i + 1:i + 2]) else ''
            msgs.append(dict(kind=m[1].lower(), src=m[2], text=m[3], debug=dbg))
        elif m := PARSE_MSG.match(line):
            msgs.append(dict(kind='error', src='gst-launch parser', text=m[1], debug=''))
        elif m := GLIB_MSG.match(line) or PYGLIB_MSG.match(line):
            msgs.append(dict(kind=m[m.lastindex - 1].lower(), src='glib', text=m[m.lastindex], debug=''))
    return msgs

def classify(res, msgs):
    # An ERROR at the first frame, then gst-launch waits until Ctrl-C: its own preroll race (identity
    # error-after=1 does it too, about 1 run in 50), so an error; a hang is a timeout without that.
    if res['killed'] and not ('by SIGINT' in res['killed'] and any(m['kind'] == 'error' for m in msgs)):
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
    blame = c.get('blame', []) + ([c['prop']] if c['prop'] else [])  # blame: other names that also count
    if cls not in ('error', 'warning') or not blame or any(m['text'] == UNDECODABLE for m in msgs):
        return None
    kinds = ('error',) if cls == 'error' else ('warning', 'critical')
    text = ' '.join(m['text'] + ' ' + m['debug'] for m in msgs if m['kind'] in kinds)
    return any(re.search(r"['\"`‘]" + re.escape(p) + r"['\"`’]", text) for p in blame)

def short(v, n=60):
    return '-' if v is None else repr(v if len(v) <= n else f'{v[:24]}...({len(v)} chars)')[1:-1]

def record(c, res):
    msgs = parse_messages(res['out'], res['err'])
    cls, token = classify(res, msgs), (c['value'] or '').replace('@FX@/', '')[:40]
    rec = dict(element=c['el'], mode=c['mode'], prop=c['prop'], value=short(c['value'], 200),
               value_len=len(c['value'] or ''), extra=c['extra'], tracked=c.get('tracked'), caps=c.get('caps'),
               nbuf=c.get('nbuf'), expect=c['expect'], cls=cls, names_property=names_property(c, cls, msgs),
               names_value=len(token) >= 3 and any(token in m['text'] + m['debug'] for m in msgs),
               stray=res['stray'], rc=res['rc'], secs=res['secs'], killed=res['killed'],
               criticals=[m['text'][:200] for m in msgs if m['kind'] == 'critical'],
               undecodable=any(m['text'] == UNDECODABLE for m in msgs), stderr_tail=res['err'][-400:],
               messages=[{**m, 'text': m['text'][:300], 'debug': m['debug'][:200]} for m in msgs[:4]])
    if SECRET in (c['value'] or '') + json.dumps(c['extra']):
        rec['leaks_secret'] = SECRET in res['out'] + res['err']
    if c['mode'] != 'launch':
        w = {'stage': None}
        for tag, _, rest in (line.partition(' ') for line in res['out'].splitlines()):
            if tag in ('STAGE', 'RESULT'):
                w.update({'stage': rest} if tag == 'STAGE' else json.loads(rest))
        rec.update(stage=w['stage'], readback=w.get('readback'), null_s=w.get('null_s'))
        rec['readback_new_after_refusal'] = bool(c['mode'] == 'playing' and c['expect'] != D
                                                 and cls in ('error', 'warning') and w.get('reads_new'))
    return rec


# ---- gi worker (a child process)
def worker(spec_path):
    spec = json.loads(Path(spec_path).read_text())
    import gi
    gi.require_version('Gst', '1.0')
    from gi.repository import Gst
    Gst.init(None)
    pipe = Gst.parse_launch(spec['desc'])
    el, bus, playing = pipe.get_by_name('dut'), pipe.get_bus(), spec['mode'] == 'playing'
    old = readback(el, spec['prop'])
    if not playing:
        set_value(el, spec)
    pipe.set_state(Gst.State.PLAYING)
    say('STAGE', 'started' if playing else 'set before start, started')
    if playing and pipe.get_state(3 * Gst.SECOND) and pump(bus, 0.8) is None:  # still running: the hostile set
        say('STAGE', 'setting while playing')
        set_value(el, spec)
        say('STAGE', 'set while playing')
    pump(bus, 1.5 if playing else 10)
    rb = readback(el, spec['prop'])
    say('STAGE', 'set_state(NULL)')
    t0 = time.monotonic()
    pipe.set_state(Gst.State.NULL)
    same = lambda v: spec['value'] in (str(v), str(v).removesuffix('.0'))  # noqa: E731 (60.0 is the 60 set)
    say('RESULT', {'readback': rb, 'reads_new': same(rb) and not same(old),
                   'null_s': round(time.monotonic() - t0, 3)})

def set_value(el, spec):
    import ctypes
    from gi.repository import GObject, Gst
    prop, value, kind = spec['prop'], spec['value'], el.find_property(spec['prop']).value_type
    if kind == GObject.TYPE_STRING:  # through C, so invalid UTF-8 arrives as the bytes a C program passes
        lib, get = ctypes.CDLL('libgobject-2.0.so.0'), ctypes.pythonapi.PyCapsule_GetPointer
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
        return json.loads(json.dumps(getattr(v, 'value_nick', v), default=str))  # enums by nick
    except Exception as e:  # e.g. invalid UTF-8 cannot become a Python str
        return f'<unreadable: {type(e).__name__}>'

def pump(bus, secs):
    """Print ERROR/WARNING messages as they come; return 'eos', 'error', or None if time ran out."""
    from gi.repository import Gst
    end, types = time.monotonic() + secs, Gst.MessageType.ERROR | Gst.MessageType.WARNING | Gst.MessageType.EOS
    while (left := end - time.monotonic()) > 0:
        m = bus.timed_pop_filtered(int(left * Gst.SECOND), types)
        if m is None or m.type == Gst.MessageType.EOS:
            return m and 'eos'
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


# ---- services, tally, main
def start_broker(out):
    """A local mosquitto, so that valid MQTT inputs run silently and bad ones are not masked."""
    exe, conf = shutil.which('mosquitto') or '/usr/sbin/mosquitto', Path(out, 'mosquitto.conf')
    with socket.socket() as s:
        s.bind(('127.0.0.1', 0))
        port = s.getsockname()[1]
    if not os.path.exists(exe):
        return None, 1
    conf.write_text(f'listener {port} 127.0.0.1\nallow_anonymous true\n')
    p = subprocess.Popen([exe, '-c', conf], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                         start_new_session=True)
    time.sleep(0.5)
    return p, port

def udp_peers():
    """A listening UDP peer on 127.0.0.1 and ::1 (localhost may resolve to either) for valid udp:// cases."""
    v4, v6 = socket.socket(socket.AF_INET, socket.SOCK_DGRAM), socket.socket(socket.AF_INET6, socket.SOCK_DGRAM)
    v4.bind(('127.0.0.1', 0))
    v6.bind(('::1', v4.getsockname()[1]))
    return [v4, v6]

def find_gi_python():
    probe = "import gi; gi.require_version('Gst','1.0'); from gi.repository import Gst"
    return next((exe for exe in (sys.executable, '/usr/bin/python3') if exe and os.path.exists(exe)
                 and subprocess.run([exe, '-c', probe], capture_output=True).returncode == 0), None)

CLASSES = ['error', 'warning', 'silent-accept', 'hang', 'crash', 'harness-error']
FLAGS = {'not-naming-prop': lambda r: r['names_property'] is False, 'stray-files': lambda r: r['stray'],
         'glib-critical': lambda r: r['criticals'], 'secret-leak': lambda r: r.get('leaks_secret'),
         'readback-new': lambda r: r.get('readback_new_after_refusal')}

def tally(recs):
    rows = {}
    for el in ('colortrack', 'robotctl', 'trackpublish', 'total'):
        rs = [r for r in recs if el in ('total', r['element'])]
        rows[el] = {'inputs': len(rs), **{k: sum(r['cls'] == k for r in rs) for k in CLASSES},
                    **{k: sum(bool(f(r)) for r in rs) for k, f in FLAGS.items()}}
    print()
    for el, row in [('element', {c: c[:15] for c in rows['total']})] + list(rows.items()):
        print(f'{el:<13}' + ''.join(f'{v:>16}' for v in row.values()))
    return rows

def label(r):
    mode = r['mode'] + (', behind colortrack' if r.get('tracked') else '')
    extra = ' '.join(f'{k}={short(v, 30)}' for k, v in r['extra'].items())
    what = f"{r['prop']}={r['value']}" if r['prop'] else f"caps={r['caps']} num-buffers={r['nbuf']}"
    return f"{r['element']} [{mode}] {what} {extra}".rstrip()

def first_text(r):
    return r['messages'][0]['text'][:170] if r['messages'] else ''

def print_lists(recs):
    silent = lambda r: r['cls'] == 'silent-accept'  # noqa: E731
    sections = [
        ('HANGS', lambda r: r['cls'] == 'hang', lambda r: f"{r['killed']}; stage={r.get('stage')}"),
        ('CRASHES, HARNESS ERRORS', lambda r: r['cls'] in ('crash', 'harness-error'),
         lambda r: f"rc={r['rc']} {(r['criticals'] or [''])[0]} {r.get('stderr_tail', '')[-150:]}"),
        ('ERROR, THEN gst-launch EXITED ONLY ON Ctrl-C', lambda r: r['cls'] == 'error' and r['killed'], first_text),
        ('STRAY FILES', lambda r: r['stray'], lambda r: ', '.join(r['stray'])),
        ('GLIB CRITICALS, NO CRASH', lambda r: r['criticals'] and r['cls'] != 'crash', lambda r: r['criticals'][0]),
        ('SECRET LEAKED', lambda r: r.get('leaks_secret'), first_text),
        ('MESSAGE NOT VALID UTF-8', lambda r: r['undecodable'], lambda r: r['cls']),
        ('REFUSALS NOT NAMING THE PROPERTY', FLAGS['not-naming-prop'],
         lambda r: f"{r['cls']}{' (names the value)' if r['names_value'] else ''}: {first_text(r)}"),
        ('PLAYING: REFUSED BUT READS BACK THE NEW VALUE', FLAGS['readback-new'], first_text),
        ('SLOW set_state(NULL) > 1 s', lambda r: (r.get('null_s') or 0) > 1, lambda r: f"{r['null_s']} s"),
        ('SILENT-ACCEPT, EXPECTED A REFUSAL (defer: a warning)', lambda r: silent(r) and r['expect'] in (R, D), None),
        ('SILENT-ACCEPT, EXPECTATION "either" (judge)', lambda r: silent(r) and r['expect'] == E, None),
        ('VALID INPUTS REFUSED', lambda r: r['expect'] == A and r['cls'] in ('error', 'warning'), first_text)]
    for title, pick, why in sections:
        hits = [r for r in recs if pick(r)]
        print(f'\n== {title}: {len(hits)}')
        for r in hits:
            print(f'  {label(r)}' + (f'  -> {why(r)}' if why else ''))
    print(f"\nsilent-accepts of inputs expected valid: {sum(silent(r) and r['expect'] == A for r in recs)}")

def run_all(cases, ctx, gi_python, env, jobs, out):
    recs = []
    with ThreadPoolExecutor(jobs) as pool, open(os.path.join(out, 'results.jsonl'), 'w') as f:
        for i, (c, res) in enumerate(zip(cases, pool.map(lambda c: run_case(c, ctx, gi_python, env), cases))):
            recs.append(rec := record(c, res))
            f.write(json.dumps(rec) + '\n')
            print(f"[{i + 1}/{len(cases)}] {rec['cls']:<13} {res['secs']:5.1f}s {label(rec)[:100]}", flush=True)
    return recs

def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--plugin-path', required=True)
    ap.add_argument('--out', default='/tmp/reliability-campaign')
    ap.add_argument('--jobs', type=int, default=2)
    ap.add_argument('--only', help='run only the cases whose element or property contains this text')
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    env = {**{k: v for k, v in os.environ.items() if k != 'GST_DEBUG'}, 'LC_ALL': 'C.UTF-8',
           'GST_PLUGIN_PATH': os.path.abspath(args.plugin_path)}
    work = tempfile.mkdtemp(prefix='campaign-')
    make_master(os.path.join(work, 'master'))
    broker, port = start_broker(args.out)
    peers = udp_peers()
    ctx = dict(WORK=work, MASTER=os.path.join(work, 'master'), BROKER=str(port), UDP=str(peers[0].getsockname()[1]))
    gi_python = find_gi_python()
    cases = all_cases()
    skipped = [c for c in cases if c['mode'] != 'launch' and not gi_python]
    cases = [c for c in cases if c not in skipped and (not args.only or args.only in f"{c['el']} {c['prop']}")]
    print(f"{len(cases)} cases; gi worker: {gi_python or 'none'} ({len(skipped)} skipped); "
          f"MQTT broker: {'port ' + str(port) if broker else 'none'}", flush=True)
    t0 = time.monotonic()
    try:
        recs = run_all(cases, ctx, gi_python, env, args.jobs, args.out)
    finally:
        if broker:
            broker.terminate()
            broker.wait()
        for s in peers:
            s.close()
        shutil.rmtree(work, ignore_errors=True)
    rows = tally(recs)
    print_lists(recs)
    Path(args.out, 'summary.json').write_text(json.dumps({'tally': rows, 'seconds': round(time.monotonic() - t0),
                                                         'skipped': len(skipped)}, indent=1))
    print(f'\n{len(recs)} inputs in {time.monotonic() - t0:.0f} s; per-case results: {args.out}/results.jsonl')

if __name__ == '__main__':
    if len(sys.argv) == 3 and sys.argv[1] == '--worker':
        worker(sys.argv[2])
    else:
        main()
