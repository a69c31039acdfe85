#!/usr/bin/env python3
"""Frames two decoders output after one flipped byte in the first packet of each type.

    scripts/damage_table.py OLD_M4D_DECODE NEW_M4D_DECODE STREAM...

For each stream and each packet type, a byte of the first such packet is flipped (XOR 0x24)
in its header (frame_index) or in the middle of its payload; both m4d_decode binaries decode
the damaged copy. Prints a Markdown table per stream: frames output by each, and how many of
the new decoder's frames it reported concealed (bitstream-spec 6.8).
"""
import os
import struct
import subprocess
import sys
import tempfile

NAMES = {1: 'SEQUENCE_HEADER', 2: 'KEYFRAME_STATIC', 3: 'KEYFRAME_DYNAMIC', 4: 'MLP_WEIGHTS',
         5: 'MOTION_GRID', 6: 'COMPENSATION', 7: 'STATIC_UPDATE', 8: 'APPEARANCE'}


def decode(binary, data, path):
    with open(path, 'wb') as f:
        f.write(data)
    r = subprocess.run([binary, path], capture_output=True, text=True)
    frames = sum(1 for line in r.stdout.splitlines() if line.strip())
    return frames, r.stderr.count('concealed (damaged')


def first_packets(data):
    first, p = {}, 0
    while p + 24 <= len(data):
        size = struct.unpack_from('<I', data, p + 12)[0]
        first.setdefault(data[p + 4], (p, size))
        p += 24 + size
    return first


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    old, new = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as work:
        path = os.path.join(work, 'damaged.m4d')
        for stream in sys.argv[3:]:
            data = open(stream, 'rb').read()
            print(f'\n{os.path.basename(stream)}: {decode(new, data, path)[0]} frames\n')
            print('| packet (first of its type) | byte flipped | frames output before |'
                  ' after (concealed) |\n|---|---|---|---|')
            for kind, (p, size) in sorted(first_packets(data).items()):
                for where, at in (('header: frame_index', p + 8),
                                  ('payload: middle', p + 24 + size // 2)):
                    damaged = bytearray(data)
                    damaged[at] ^= 0x24
                    before = decode(old, bytes(damaged), path)[0]
                    after, concealed = decode(new, bytes(damaged), path)
                    print(f'| {NAMES.get(kind, kind)} | {where} | {before} | {after} ({concealed}) |')


if __name__ == '__main__':
    main()
