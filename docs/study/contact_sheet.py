#!/usr/bin/env python3
"""Tiles same-size 8-bit RGB/RGBA PNGs (as visual-client writes them) into one contact sheet.

usage: contact_sheet.py OUT.png COLUMNS IN.png...   (standard library only: zlib, struct)
Rows are filled left to right; a missing cell at the end stays black.
"""
import struct
import sys
import zlib


def read_png(path):
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit(f"{path}: not a PNG")
    pos, idat, width = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            width, height, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or color not in (2, 6) or interlace:
                sys.exit(f"{path}: expected 8-bit RGB or RGBA, not interlaced (got depth {depth}, color type {color})")
            bpp = 3 if color == 2 else 4
        elif kind == b"IDAT":
            idat += body
    raw, stride = zlib.decompress(idat), width * bpp
    rows, prev = [], bytearray(stride)
    for y in range(height):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        prev = line
        rows.append(bytes(line[k] for k in range(stride) if k % bpp < 3) if bpp == 4 else bytes(line))
    return width, height, rows


def write_png(path, width, height, rows):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    raw = b"".join(b"\x00" + r for r in rows)  # no filter: smallest for these renderings (tried up and sub)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def main():
    if len(sys.argv) < 4 or sys.argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        sys.exit(0 if len(sys.argv) > 1 and sys.argv[1] in ("-h", "--help") else 2)
    out, cols, images = sys.argv[1], int(sys.argv[2]), [read_png(p) for p in sys.argv[3:]]
    w, h = images[0][0], images[0][1]
    if any(im[0] != w or im[1] != h for im in images):
        sys.exit("all pictures must have the same size")
    n_rows = (len(images) + cols - 1) // cols
    black = bytes(3 * w)
    sheet = []
    for r in range(n_rows):
        for y in range(h):
            sheet.append(b"".join(images[r * cols + c][2][y] if r * cols + c < len(images) else black
                                  for c in range(cols)))
    write_png(out, cols * w, n_rows * h, sheet)


if __name__ == "__main__":
    main()
