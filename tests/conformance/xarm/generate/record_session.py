#!/usr/bin/python3
"""Records the UFACTORY xArm Python SDK (xArm-Developer/xArm-Python-SDK) driving robotd-xarm-sim:
a scripted session through the SDK's public XArmAPI, every request and reply on the wire
recorded per connection by a proxy on the SDK's fixed ports (502, 30000-30003), written to
transcript.json with provenance.json.

The SDK connects to fixed ports on the address it is given, so the session runs in a private
network namespace of its own (unshare -n as root, unshare -rn otherwise): the proxy listens on the
SDK's ports there and relays to the simulator on other ports. Nothing of the SDK is copied; it is
imported from the checkout given.

usage: record_session.py --sdk PATH_TO_SDK_CHECKOUT --sim PATH_TO_robotd-xarm-sim [--out DIR]
"""
import argparse
import datetime
import fcntl
import json
import os
import socket
import struct
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from recording_proxy import RecordingProxy  # noqa: E402
from session import run_session  # noqa: E402

# SDK port → (simulator port, what it carries)
ROUTES = [(502, 15020, 'command'), (30003, 15030, 'real'), (30001, 15031, 'normal'),
          (30002, 15032, 'rich'), (30000, 15033, 'realtime')]
SIM_PORT_OPTIONS = {'command': '--port', 'real': '--report-port', 'normal': '--normal-report-port',
                    'rich': '--rich-report-port', 'realtime': '--realtime-report-port'}
# Report streams run at up to 250 Hz: the first packets of each connection are kept.
REPORT_PACKETS_KEPT = 3
MODEL = 'xarm6'
FIRMWARE = '2.3.0'


def in_private_namespace(argv):
    """Re-runs this script in a network namespace of its own (util-linux's unshare)."""
    unshare = ['unshare', '-n'] if os.geteuid() == 0 else ['unshare', '-rn']
    return subprocess.call(unshare + [sys.executable, os.path.abspath(__file__)] + argv + ['--inside-namespace'])


def loopback_up():
    """A new network namespace starts with loopback down: SIOCSIFFLAGS |= IFF_UP (no iproute2)."""
    siocgifflags, siocsifflags, iff_up = 0x8913, 0x8914, 0x1
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        request = struct.pack('16sH14x', b'lo', 0)
        flags = struct.unpack('16sH14x', fcntl.ioctl(s, siocgifflags, request))[1]
        fcntl.ioctl(s, siocsifflags, struct.pack('16sH14x', b'lo', flags | iff_up))


def start_simulator(sim, control_path):
    args = [sim, '--model', MODEL, '--firmware', FIRMWARE, '--quiet', '--control', control_path]
    for _, sim_port, kind in ROUTES:
        args += [SIM_PORT_OPTIONS[kind], str(sim_port)]
    process = subprocess.Popen(args, stdout=subprocess.PIPE, text=True)
    if process.stdout.readline().strip() != 'ready':
        raise SystemExit('robotd-xarm-sim did not start: ' + ' '.join(args))
    return process


def sim_control(control_path, request):
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as channel:
        channel.connect(control_path)
        channel.sendall((json.dumps(request) + '\n').encode())
        return json.loads(channel.makefile().readline())


def git(args, cwd):
    return subprocess.run(['git'] + args, cwd=cwd, capture_output=True, text=True, check=False).stdout.strip()


def sdk_commit(sdk):
    commit = git(['rev-parse', 'HEAD'], sdk)
    if commit:
        return commit
    # an exported tree (git archive) names its commit in this file when asked for
    marker = os.path.join(sdk, '.commit')
    return open(marker).read().strip() if os.path.exists(marker) else 'unknown'


def transcript_of(proxy):
    connections = []
    # The command connection first; the threads that accepted them may have raced.
    for connection in sorted(proxy.connections, key=lambda c: (c.kind != 'command', c.number)):
        with connection.lock:
            frames = [{'t_ms': round(t * 1000, 1), 'dir': direction, 'step': step, 'hex': data.hex(' ')}
                      for t, direction, data, step in connection.frames]
        connections.append({'id': len(connections), 'port': connection.port, 'kind': connection.kind,
                            'frames': frames})
    return connections


def record(args):
    sys.path.insert(0, args.sdk)
    from xarm.wrapper import XArmAPI  # the vendor's SDK, from the checkout given
    from xarm import version as sdk_version

    with tempfile.TemporaryDirectory() as tmp:
        control_path = os.path.join(tmp, 'xarm.ctl')
        simulator = start_simulator(args.sim, control_path)
        proxy = RecordingProxy([(port, target, kind) for port, target, kind in ROUTES], REPORT_PACKETS_KEPT)
        proxy.start()
        try:
            controls = []

            def control(request):
                # replayed before the request that followed it on the command connection
                controls.append({'before_request': proxy.requests_sent('command'), 'request': request})
                return sim_control(control_path, request)

            calls = run_session(XArmAPI, proxy, control)
            time.sleep(0.3)  # the last replies and the report thread's close
        finally:
            proxy.close()
            simulator.terminate()
            simulator.wait()

    os.makedirs(args.out, exist_ok=True)
    transcript = {
        'about': 'The xArm Python SDK driving robotd-xarm-sim, recorded on the wire by '
                 'tests/conformance/xarm/generate/record_session.py; frames in order per connection, '
                 'dir request = SDK to controller, reply = controller to SDK; step = the session step '
                 'that was running; report connections keep their first %d packets; simulator_control: what '
                 'the session asked the simulator (its control channel) before the command connection\'s '
                 'request number before_request (from 0).' % REPORT_PACKETS_KEPT,
        'simulator': {'model': MODEL, 'firmware': FIRMWARE},
        'connections': transcript_of(proxy),
        'simulator_control': controls,
        'calls': calls,
    }
    with open(os.path.join(args.out, 'transcript.json'), 'w') as f:
        json.dump(transcript, f, indent=1)
        f.write('\n')
    robotd_root = os.path.abspath(os.path.join(HERE, '..', '..', '..', '..'))
    provenance = {
        'repository': 'https://github.com/xArm-Developer/xArm-Python-SDK',
        'commit': sdk_commit(args.sdk),
        'sdk_version': sdk_version.__version__,
        'files_run': ['xarm/wrapper/xarm_api.py (XArmAPI)', 'xarm/x3/*.py', 'xarm/core/**/*.py'],
        'how': 'the SDK\'s public XArmAPI calls of tests/conformance/xarm/generate/session.py against '
               'robotd-xarm-sim --model %s --firmware %s, through a recording proxy on the SDK\'s ports '
               '(502, 30000-30003) in a private network namespace' % (MODEL, FIRMWARE),
        'regenerate': 'mkdir -p /tmp/xarm-sdk && git -C <xArm-Python-SDK clone> archive <commit> | '
                      'tar -x -C /tmp/xarm-sdk && echo <commit> > /tmp/xarm-sdk/.commit && '
                      'tests/conformance/xarm/generate/record_session.py --sdk /tmp/xarm-sdk '
                      '--sim build/bin/robotd-xarm-sim --out tests/conformance/xarm',
        'python': sys.version.split()[0],
        'robotd_commit': git(['rev-parse', 'HEAD'], robotd_root),
        'date': datetime.datetime.now(datetime.timezone.utc).strftime('%Y-%m-%dT%H:%M:%SZ'),
    }
    with open(os.path.join(args.out, 'provenance.json'), 'w') as f:
        json.dump(provenance, f, indent=1)
        f.write('\n')
    print('wrote %d connections, %d calls to %s' % (len(transcript['connections']), len(calls), args.out))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--sdk', required=True, help='a checkout of xArm-Developer/xArm-Python-SDK')
    parser.add_argument('--sim', required=True, help='the robotd-xarm-sim executable')
    parser.add_argument('--out', default=os.path.abspath(os.path.join(HERE, '..')))
    parser.add_argument('--inside-namespace', action='store_true', help=argparse.SUPPRESS)
    args = parser.parse_args()
    args.sdk, args.sim, args.out = map(os.path.abspath, (args.sdk, args.sim, args.out))
    if not os.path.isfile(os.path.join(args.sdk, 'xarm', 'wrapper', 'xarm_api.py')):
        raise SystemExit('--sdk %s is not an xArm-Python-SDK checkout (no xarm/wrapper/xarm_api.py)' % args.sdk)
    if not args.inside_namespace:
        return in_private_namespace(sys.argv[1:])
    loopback_up()
    record(args)
    return 0


if __name__ == '__main__':
    sys.exit(main())
