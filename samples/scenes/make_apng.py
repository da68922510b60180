#!/usr/bin/env python3
"""Joins PNG frames of one size and format (shadow_render's frames/color_<k>.png) into an
animated PNG, without decoding them: each frame's compressed image data becomes the APNG
frame's data as it is.

    python3 samples/scenes/make_apng.py OUT.png FPS FRAME.png [FRAME.png ...]
"""
import os
import struct
import sys
import zlib


def chunks(data):
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG file")
    at = 8
    while at < len(data):
        (length,) = struct.unpack(">I", data[at:at + 4])
        kind = data[at + 4:at + 8]
        yield kind, data[at + 8:at + 8 + length]
        at += 12 + length


def chunk(kind, body):
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)


def main(argv):
    if len(argv) < 4:
        sys.exit("usage: make_apng.py OUT.png FPS FRAME.png [FRAME.png ...]")
    out, fps, frames = argv[1], int(argv[2]), argv[3:]
    if fps < 1:
        sys.exit("make_apng.py: FPS must be at least 1")
    header = None
    parts = []
    for path in frames:
        with open(path, "rb") as f:
            found = list(chunks(f.read()))
        ihdr = next(body for kind, body in found if kind == b"IHDR")
        if header is None:
            header = ihdr
        elif ihdr != header:
            sys.exit(f"make_apng.py: {path}: size or format differs from the first frame")
        parts.append(b"".join(body for kind, body in found if kind == b"IDAT"))
    width, height = struct.unpack(">II", header[:8])
    body = [b"\x89PNG\r\n\x1a\n", chunk(b"IHDR", header), chunk(b"acTL", struct.pack(">II", len(parts), 0))]
    sequence = 0
    for k, data in enumerate(parts):
        control = struct.pack(">IIIIIHHBB", sequence, width, height, 0, 0, 1, fps, 0, 0)
        body.append(chunk(b"fcTL", control))
        sequence += 1
        if k == 0:
            body.append(chunk(b"IDAT", data))  # the first frame is the still image too
        else:
            body.append(chunk(b"fdAT", struct.pack(">I", sequence) + data))
            sequence += 1
    body.append(chunk(b"IEND", b""))
    with open(out + ".part", "wb") as f:
        f.write(b"".join(body))
    os.replace(out + ".part", out)


if __name__ == "__main__":
    main(sys.argv)
