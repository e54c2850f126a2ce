#!/usr/bin/env python3
"""PNG checks for the renderer tests, Python standard library only.

  png_tools.py colours IMAGE.png
      prints each distinct colour as "r,g,b count", most frequent first
  png_tools.py path-mask PLANS.jsonl W H MAP_W MAP_H ORIGIN_X ORIGIN_Y OUT.png
      draws where the plan's path must be in a top view rendered with
      --no-annotations (the map fitted into the image less a 10-pixel margin,
      centred): 4-pixel lines between waypoints, discs at start, goal and
      guard points. Computed here, independently of the renderer.
  png_tools.py alternatives-mask PLANS.jsonl W H MAP_W MAP_H ORIGIN_X ORIGIN_Y OUT.png
      the same for the lines of the plan's alternatives (index >= 1), 2 pixels
      wide
"""
import json
import struct
import sys
import zlib


def read_png(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    pos, idat, w = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and ctype in (2, 6), "8-bit RGB(A) only"
            bpp = 3 if ctype == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else b if pb <= pc else c
                line[i] = (line[i] + pred) & 255
        rows.append(line)
        prev = line
    return w, h, bpp, rows


def write_png(path, w, h, pixels):
    """pixels: bytearray of w*h RGB."""
    raw = b"".join(b"\x00" + bytes(pixels[y * w * 3:(y + 1) * w * 3]) for y in range(h))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(raw)))
        f.write(chunk(b"IEND", b""))


def colours(path):
    w, h, bpp, rows = read_png(path)
    count = {}
    for line in rows:
        for x in range(w):
            c = tuple(line[x * bpp:x * bpp + 3])
            count[c] = count.get(c, 0) + 1
    for c, n in sorted(count.items(), key=lambda kv: -kv[1]):
        print(f"{c[0]},{c[1]},{c[2]} {n}")


def fit(w, h, mw, mh, ox, oy):
    """World to image pixels (y down) of a top view rendered with
    --no-annotations: the map fitted into the image less a 10-pixel margin,
    centred."""
    margin = 10
    s = min((w - 2 * margin) / mw, (h - 2 * margin) / mh)
    px0 = margin + 0.5 * (w - 2 * margin - s * mw)
    py0 = margin + 0.5 * (h - 2 * margin - s * mh)
    return lambda p: (px0 + s * (p[0] - ox), h - (py0 + s * (p[1] - oy)))


def write_mask(out, w, h, segs, discs):
    """Black where a pixel centre lies within r of a segment (a, b, r) or a
    disc (c, r), white elsewhere."""
    img = bytearray(b"\xff" * (w * h * 3))

    def cover(x0, y0, x1, y1, inside):
        for y in range(max(0, int(y0)), min(h, int(y1) + 2)):
            for x in range(max(0, int(x0)), min(w, int(x1) + 2)):
                if inside(x + 0.5, y + 0.5):
                    img[3 * (y * w + x):3 * (y * w + x) + 3] = b"\x00\x00\x00"

    for (ax, ay), (bx, by), r in segs:
        def on_segment(cx, cy, ax=ax, ay=ay, bx=bx, by=by, r=r):
            dx, dy = bx - ax, by - ay
            n2 = dx * dx + dy * dy
            t = 0 if n2 == 0 else max(0, min(1, ((cx - ax) * dx + (cy - ay) * dy) / n2))
            ex, ey = ax + t * dx - cx, ay + t * dy - cy
            return ex * ex + ey * ey <= r * r
        cover(min(ax, bx) - r, min(ay, by) - r, max(ax, bx) + r, max(ay, by) + r, on_segment)
    for (dx, dy), r in discs:
        cover(dx - r, dy - r, dx + r, dy + r,
              lambda cx, cy, dx=dx, dy=dy, r=r: (dx - cx) ** 2 + (dy - cy) ** 2 <= r * r)
    write_png(out, w, h, img)


def points(plan):
    return [(wp["state"][0], wp["state"][1]) for wp in plan["waypoints"]]


def path_mask(plans, w, h, mw, mh, ox, oy, out):
    plan = [json.loads(l) for l in open(plans) if l.strip()][-1]
    pts = points(plan)
    guards = [(wp["state"][0], wp["state"][1]) for wp in plan["waypoints"] if wp.get("guard")]
    to_px = fit(w, h, mw, mh, ox, oy)
    segs = [(to_px(a), to_px(b), 2.0) for a, b in zip(pts, pts[1:])]
    discs = [(to_px(pts[0]), 6.0), (to_px(pts[-1]), 6.0)] + [(to_px(g), 5.5) for g in guards]
    write_mask(out, w, h, segs, discs)


def alternatives_mask(plans, w, h, mw, mh, ox, oy, out):
    """The lines of every alternative but the plan's own (index >= 1) of the
    hylo-listen --json records, 2 pixels wide, no discs."""
    alts = [r for r in (json.loads(l) for l in open(plans) if l.strip())
            if r.get("type") == "alternative" and r["index"] >= 1]
    assert alts, f"{plans} holds no alternative with index >= 1"
    to_px = fit(w, h, mw, mh, ox, oy)
    segs = []
    for a in alts:
        pts = points(a["plan"])
        segs += [(to_px(p), to_px(q), 1.0) for p, q in zip(pts, pts[1:])]
    write_mask(out, w, h, segs, [])


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "colours":
        colours(sys.argv[2])
    elif len(sys.argv) == 10 and sys.argv[1] in ("path-mask", "alternatives-mask"):
        a = sys.argv[2:]
        mask = path_mask if sys.argv[1] == "path-mask" else alternatives_mask
        mask(a[0], int(a[1]), int(a[2]), float(a[3]), float(a[4]), float(a[5]), float(a[6]), a[7])
    else:
        sys.exit(__doc__)
