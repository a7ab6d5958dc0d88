// SPDX-License-Identifier: LGPL-2.1-or-later
// The tests' independent MAVLink implementation: node-mavlink (npm, installed here by tests/bootstrap.sh),
// so robotctl's frames are checked against someone else's reading of the MAVLink definitions.
//   node mavlink-check.cjs encode < cases    one JSON case a line in, one frame as hex a line out:
//     {"message": "heartbeat" | "gimbal" | "position", "sysid", "compid", "seq", ...fields (camelCase as
//      node-mavlink names them; "NaN" for NaN), "version": 1 for a MAVLink 1 frame (default 2)}
//   node mavlink-check.cjs decode FILE       FILE: records of (float64 LE receive time in s, uint32 LE
//     length, datagram); one JSON line out per frame: time, crcValid, seq, sysid, compid, msgid, name, fields
'use strict';
const fs = require('fs');
const { MavLinkProtocolV1, MavLinkProtocolV2, minimal, common, MSG_ID_MAGIC_NUMBER, x25crc } = require('node-mavlink');

const classes = {
  heartbeat: minimal.Heartbeat,
  gimbal: common.GimbalManagerSetPitchyaw,
  position: common.SetPositionTargetLocalNed,
};
const registry = { ...minimal.REGISTRY, ...common.REGISTRY };

function encode(text) {
  const out = [];
  for (const line of text.split('\n')) {
    if (!line.trim()) continue;
    const c = JSON.parse(line);
    const message = new classes[c.message]();
    for (const [key, value] of Object.entries(c)) {
      if (['message', 'sysid', 'compid', 'seq', 'version'].includes(key)) continue;
      message[key] = value === 'NaN' ? NaN : value;
    }
    const Protocol = c.version === 1 ? MavLinkProtocolV1 : MavLinkProtocolV2;
    out.push(new Protocol(c.sysid, c.compid).serialize(message, c.seq).toString('hex'));
  }
  process.stdout.write(out.join('\n') + '\n');
}

function decode(path) {
  const data = fs.readFileSync(path);
  const protocol = new MavLinkProtocolV2();
  for (let at = 0; at + 12 <= data.length;) {
    const time = data.readDoubleLE(at);
    const length = data.readUInt32LE(at + 8);
    let datagram = data.subarray(at + 12, at + 12 + length);
    at += 12 + length;
    // A datagram may carry several frames.
    while (datagram.length >= 12 && datagram[0] === MavLinkProtocolV2.START_BYTE) {
      const size = MavLinkProtocolV2.PAYLOAD_OFFSET + datagram[1] + 2;
      const buffer = datagram.subarray(0, size);
      datagram = datagram.subarray(size);
      const header = protocol.header(buffer);
      const magic = MSG_ID_MAGIC_NUMBER[header.msgid];
      const crcValid = magic !== undefined && buffer.length === size &&
                       x25crc(buffer, 1, 2, magic) === protocol.crc(buffer);
      const clazz = registry[header.msgid];
      const fields = {};
      if (clazz) {
        const message = protocol.data(protocol.payload(buffer), clazz);
        for (const field of clazz.FIELDS) {
          const value = message[field.name];
          fields[field.name] = typeof value === 'number' && !Number.isFinite(value) ? String(value) : value;
        }
      }
      process.stdout.write(JSON.stringify({
        time, crcValid, seq: header.seq, sysid: header.sysid, compid: header.compid, msgid: header.msgid,
        name: clazz ? clazz.MSG_NAME : null, fields,
      }) + '\n');
    }
    if (datagram.length > 0) process.stdout.write(JSON.stringify({ time, garbage: datagram.length }) + '\n');
  }
}

if (process.argv[2] === 'encode') encode(fs.readFileSync(0, 'utf8'));
else if (process.argv[2] === 'decode') decode(process.argv[3]);
else {
  process.stderr.write('usage: mavlink-check.cjs encode < cases | decode FILE\n');
  process.exit(2);
}
