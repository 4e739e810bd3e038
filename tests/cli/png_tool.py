#!/usr/bin/env python3
"""Reads the PNGs glcollide writes (8-bit RGB or RGBA, not interlaced) with the standard library only,
for the viewer's tests (tests/cli/view_test.sh).

  png_tool.py size FILE                         prints WIDTH HEIGHT
  png_tool.py diff A B X0 Y0 X1 Y1              prints how many pixels of the rectangle differ
  png_tool.py count FILE X0 Y0 X1 Y1 KIND       prints the fraction of the rectangle's pixels of a kind:
      panel: Dear ImGui's dark window background (every channel < 60, within 12 of each other)
      body:  the first body's blue (render's palette entry 0), lit or in shade, front or back (the
             back side is mixed halfway with a warm grey: blue still above red by about 24): blue
             above red by > 15, which the neutral grey grid and white background never are
      pairs: the candidate-pair overlay's green (0, 191, 51), unlit: within 8 per channel (the
             window's multisampling blends line edges)
      contacts: the feature-contact overlay's cyan (0, 204, 230), the same way
      boxes: the broad-phase box overlay's violet (128, 51, 204), the same way
Rectangles are [X0, X1) x [Y0, Y1) in pixels from the top left.
"""
import struct
import sys
import zlib


def read_png(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit(f"{path}: not a PNG")
    pos, idat, width = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or colour not in (2, 6) or interlace:
                sys.exit(f"{path}: only 8-bit RGB/RGBA, not interlaced")
            channels = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous, i = [], bytearray(stride), 0
    for _ in range(height):
        filt, line = raw[i], bytearray(raw[i + 1:i + 1 + stride])
        i += 1 + stride
        for x in range(stride):  # PNG filters: none, sub, up, average, Paeth
            a = line[x - channels] if x >= channels else 0
            b = previous[x]
            c = previous[x - channels] if x >= channels else 0
            if filt == 1:
                line[x] = (line[x] + a) & 255
            elif filt == 2:
                line[x] = (line[x] + b) & 255
            elif filt == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif filt == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * channels:x * channels + 3]) for x in range(width)])
        previous = line
    return width, height, rows


def rect(args):
    return [int(v) for v in args]


def main(argv):
    cmd = argv[1]
    if cmd == "size":
        w, h, _ = read_png(argv[2])
        print(w, h)
    elif cmd == "diff":
        _, _, a = read_png(argv[2])
        _, _, b = read_png(argv[3])
        x0, y0, x1, y1 = rect(argv[4:8])
        print(sum(a[y][x] != b[y][x] for y in range(y0, y1) for x in range(x0, x1)))
    elif cmd == "count":
        _, _, rows = read_png(argv[2])
        x0, y0, x1, y1 = rect(argv[3:7])
        kind = argv[7]
        def panel(p):
            return max(p) < 60 and max(p) - min(p) <= 12
        def body(p):
            return p[2] > p[0] + 15
        def pairs(p):
            return abs(p[0] - 0) <= 8 and abs(p[1] - 191) <= 8 and abs(p[2] - 51) <= 8
        def near(p, c):
            return all(abs(p[i] - c[i]) <= 8 for i in range(3))
        def contacts(p):
            return near(p, (0, 204, 230))
        def boxes(p):
            return near(p, (128, 51, 204))
        test = {"panel": panel, "body": body, "pairs": pairs, "contacts": contacts, "boxes": boxes}[kind]
        hits = sum(test(rows[y][x]) for y in range(y0, y1) for x in range(x0, x1))
        print(f"{hits / ((x1 - x0) * (y1 - y0)):.4f}")
    else:
        sys.exit(f"unknown command {cmd}")


if __name__ == "__main__":
    main(sys.argv)
