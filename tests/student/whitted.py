#!/usr/bin/env python3
"""A student's Whitted ray tracer, written from docs/MODEL.md and docs/RAYLOG.md.

It traces one pixel (or a rectangle of pixels) of a raystep TOML scene and
prints every ray it casts as a ray log, for `raystep compare SCENE --rays LOG`,
or renders the whole image to a PNG, for `raystep compare SCENE IMAGE.png`:

    python3 tests/student/whitted.py scenes/glass.toml 72 45 > mine.jsonl
    python3 tests/student/whitted.py scenes/glass.toml 70 40 --size 4x3
    python3 tests/student/whitted.py scenes/glass.toml -o mine.png --size 80x60

With X, Y, --size WxH traces the W x H pixels whose top-left one is X, Y.
With -o, --size WxH is the image's size (the scene's own without it; the
field of view stays, as with `raystep render --size`); with X, Y, --image
WxH traces them as pixels of a W x H image (the size trap of issue 39).
--mistake NAME switches on one of the slips students make (see MISTAKES);
each is a one-line change at the place marked `if "NAME" in mistakes`.
Python 3.11, standard library only.
"""
import argparse
import json
import math
import struct
import tomllib
import zlib

EPS = 1e-4
MISTAKES = {
    "reflect-sign": "R = 2 (N.d) N - d",
    "outward-normal": "refraction uses N_g, not N, when leaving",
    "unnormalised-l": "L = P_L - p is not normalised",
    "abs-ndotl": "|N.L|: lights behind the surface count",
    "fov-radians": "fov read as radians",
    "fov-horizontal": "fov taken as the horizontal field of view",
    "no-shadow-ray": "lights are never blocked, no shadow rays",
    "past-max-depth": "one level deeper than max_depth",
    "nan": "V = normalize(p - p), a zero vector: NaN",
    "no-epsilon": "t > 0 instead of t > EPS",
    "pixel-corner": "the primary ray through (x, y), not (x + 0.5, y + 0.5)",
    "no-ambient": "the ambient term forgotten",
    "any-hit-shadows": "a shadow ray that hits anything gives S = 0",
    "no-clamp": "byte = int(255 c + 0.5) & 0xff, not clamped first",
    "gamma": "bytes gamma-corrected: 255 c^(1/2.2)",
    "rows-bottom-up": "the PNG's rows written bottom row first",
    # Slips whose log raystep must word right, or not call bugs (issue 39).
    "pixel-span": "px = 2 x / (W - 1) - 1: the pixels span the image edge to edge",
    "shadow-behind": "a shadow ray cast to a light behind the surface (it adds nothing)",
    "no-min-weight": "secondary rays cast below min_weight",
    "miss-t-infinity": "a miss logs t = Infinity",
    "miss-t-minus-one": "a miss logs t = -1",
    "miss-t-null": "a miss logs t = null",
    "reflect-plus": "R = d + 2 (d.N) N",
    "unweighted-reflection": "the reflected colour added without its weight k_s",
    "unweighted-transmission": "the transmitted colour added without its weight k_t",
    "specular-times-od": "the specular term multiplied by the object colour O_d",
    "fatt-ambient": "the ambient term multiplied by f_att of the first light",
    "h-unnormalised": "H = L + V, not normalised",
    "shadow-past-light": "shadow rays blocked past the light too (t < inf, not t < d_L)",
}
# Slips outside raystep's catalogue that change the image (issue 39): compare
# must not name a catalogued mistake the slip does not make.
MISTAKES |= {
    "no-tir": "no total internal reflection test: sqrt(k < 0) is NaN, the ray misses",
    "polygon-miss": "the crossing test drops the smallest normal axis, not the largest",
    "turn-180": "the image written turned half a turn",
    "channels-swapped": "the PNG's bytes written B, G, R",
    "dim": "every colour multiplied by 0.8 before the bytes",
    "antialias": "2 x 2 rays a pixel, averaged (anti-aliasing)",
    "jpeg-noise": "the bytes saved through a lossy codec: up to 6 steps of noise",
}
mistakes = set()


def log_ray(x, y, path, **fields):
    print(json.dumps({"pixel": [x, y], "path": path, **fields}))


# --- vectors are tuples of three floats ---------------------------------------
def add(a, b): return (a[0] + b[0], a[1] + b[1], a[2] + b[2])
def sub(a, b): return (a[0] - b[0], a[1] - b[1], a[2] - b[2])
def mul(a, s): return (a[0] * s, a[1] * s, a[2] * s)
def vmul(a, b): return (a[0] * b[0], a[1] * b[1], a[2] * b[2])
def dot(a, b): return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
def length(a): return math.sqrt(dot(a, a))


def normalize(a):
    n = length(a)
    if n == 0:
        return (math.nan, math.nan, math.nan)  # what 0/0 gives in C
    return (a[0] / n, a[1] / n, a[2] / n)


# --- shapes: every t where the ray's line meets the surface, and N_g at p -----
def sphere_ts(s, o, d):
    oc = sub(o, s["center"])
    a, b, c = dot(d, d), 2 * dot(d, oc), dot(oc, oc) - s["radius"] ** 2
    disc = b * b - 4 * a * c
    if disc < 0:
        return []
    root = math.sqrt(disc)
    return [(-b - root) / (2 * a), (-b + root) / (2 * a)]


def plane_ts(pn, dd, o, d):
    vd = dot(pn, d)
    return [] if vd == 0 else [-(dot(pn, o) + dd) / vd]


def polygon_ts(s, o, d):
    ts = plane_ts(s["normal"], s["D"], o, d)
    return [t for t in ts if inside(s, add(o, mul(d, t)))]


def inside(s, p):
    """Jordan curve test: drop the largest normal axis, count edges crossing +U."""
    n = [abs(c) for c in s["normal"]]
    drop = n.index(max(n))
    if "polygon-miss" in mistakes:
        drop = n.index(min(n))  # the plane seen edge-on: no crossing counted
    u, v = [i for i in range(3) if i != drop]
    pts = [(q[u] - p[u], q[v] - p[v]) for q in s["vertices"]]
    crossings = 0
    for i, (ua, va) in enumerate(pts):
        ub, vb = pts[(i + 1) % len(pts)]
        if (va >= 0) != (vb >= 0) and ua - va * (ub - ua) / (vb - va) > 0:
            crossings += 1
    return crossings % 2 == 1


def patch_normal(s, p):
    """The vertex normals interpolated on the fan triangle (v0, vi, vi+1) holding p."""
    vs, ns = s["vertices"], s["normals"]
    for i in range(1, len(vs) - 1):
        a, b, c = vs[0], vs[i], vs[i + 1]
        n = cross(sub(b, a), sub(c, a))
        wa = dot(cross(sub(c, b), sub(p, b)), n) / dot(n, n)
        wb = dot(cross(sub(a, c), sub(p, c)), n) / dot(n, n)
        wc = 1 - wa - wb
        if min(wa, wb, wc) >= 0 or i == len(vs) - 2:
            blend = add(mul(ns[0], wa), add(mul(ns[i], wb), mul(ns[i + 1], wc)))
            return normalize(blend) if length(blend) > 0 else s["normal"]


def cone_ts(s, o, d):
    """Open cone or cylinder: |q - (q.a) a| = r0 + k (q.a) with 0 <= q.a <= h."""
    a, h, r0, k = s["axis"], s["height"], s["r0"], s["k"]
    q = sub(o, s["base"])
    yo, yd = dot(q, a), dot(d, a)
    ro, rd = sub(q, mul(a, yo)), sub(d, mul(a, yd))
    ro_r = r0 + k * yo
    qa = dot(rd, rd) - k * k * yd * yd
    qb = 2 * (dot(ro, rd) - k * ro_r * yd)
    qc = dot(ro, ro) - ro_r * ro_r
    if qa == 0:
        ts = [] if qb == 0 else [-qc / qb]
    else:
        disc = qb * qb - 4 * qa * qc
        if disc < 0:
            return []
        root = math.sqrt(disc)
        ts = [(-qb - root) / (2 * qa), (-qb + root) / (2 * qa)]
    return [t for t in ts if 0 <= yo + t * yd <= h]


def hits(s, o, d):
    kind = s["kind"]
    if kind == "sphere":
        return sphere_ts(s, o, d)
    if kind == "plane":
        return plane_ts(s["normal"], s["D"], o, d)
    if kind in ("polygon", "patch"):
        return polygon_ts(s, o, d)
    return cone_ts(s, o, d)


def geometric_normal(s, p):
    if s["kind"] == "sphere":
        return mul(sub(p, s["center"]), 1 / s["radius"])
    if s["kind"] in ("plane", "polygon"):
        return s["normal"]
    if s["kind"] == "patch":
        return patch_normal(s, p)
    q = sub(p, s["base"])
    y = dot(q, s["axis"])
    radial = sub(q, mul(s["axis"], y))
    if length(radial) == 0:  # the tip: the axis, from the wide end towards it
        return s["axis"] if s["k"] < 0 else mul(s["axis"], -1)
    return normalize(sub(radial, mul(s["axis"], s["k"] * (s["r0"] + s["k"] * y))))


# --- the scene ---------------------------------------------------------------
def load(path):
    with open(path, "rb") as f:
        toml = tomllib.load(f)
    cam, img, st = toml["camera"], toml.get("image", {}), toml.get("settings", {})
    scene = {
        "eye": tuple(cam["eye"]), "look_at": tuple(cam["look_at"]),
        "up": tuple(cam.get("up", (0, 1, 0))), "fov": cam.get("fov", 45),
        "width": img.get("width", 320), "height": img.get("height", 240),
        "background": tuple(st.get("background", (0, 0, 0))),
        "ambient": tuple(st.get("ambient", (0, 0, 0))),
        "light_att": st.get("light_attenuation", (1, 0, 0)),
        "ray_att": st.get("ray_attenuation", (1, 0, 0)),
        "max_depth": st.get("max_depth", 5), "min_weight": st.get("min_weight", 1 / 512),
        "max_rays": st.get("max_rays", 4096), "specular": st.get("specular", "blinn"),
    }
    materials = {}
    for name, m in toml.get("materials", {}).items():
        materials[name] = {
            "color": tuple(m.get("color", (1, 1, 1))), "kd": m.get("kd", 1), "ks": m.get("ks", 0),
            "n": m.get("n", 20), "kt": m.get("kt", 0), "ior": m.get("ior", 1), "ka": m.get("ka", 1),
            "specular": m.get("specular", scene["specular"]),
        }
    scene["lights"] = [(tuple(l["position"]), tuple(l.get("color", (1, 1, 1)))) for l in toml.get("light", [])]
    scene["objects"] = [shape(o) | {"material": materials[o["material"]]} for o in toml.get("object", [])]
    return scene


def shape(obj):
    if "sphere" in obj:
        s = obj["sphere"]
        return {"kind": "sphere", "center": tuple(s["center"]), "radius": s["radius"]}
    if "plane" in obj:
        n = normalize(tuple(obj["plane"]["normal"]))
        return {"kind": "plane", "normal": n, "D": -dot(n, tuple(obj["plane"]["point"]))}
    if "polygon" in obj or "patch" in obj:
        kind = "polygon" if "polygon" in obj else "patch"
        vs = [tuple(v) for v in obj[kind]["vertices"]]
        n = normalize(cross(sub(vs[1], vs[0]), sub(vs[2], vs[0])))
        normals = [normalize(tuple(v)) for v in obj[kind].get("normals", [])]
        return {"kind": kind, "vertices": vs, "normals": normals, "normal": n, "D": -dot(n, vs[0])}
    if "cylinder" in obj or "cone" in obj:
        c = obj.get("cylinder") or obj["cone"]
        base, apex = tuple(c["base"]), tuple(c["apex"])
        r0, r1 = c.get("radius", c.get("base_radius")), c.get("radius", c.get("apex_radius"))
        h = length(sub(apex, base))
        return {"kind": "cone", "base": base, "axis": normalize(sub(apex, base)), "height": h,
                "r0": r0, "k": (r1 - r0) / h}
    raise SystemExit(f"whitted.py: shape not supported: {obj.get('name')}")


# --- tracing -------------------------------------------------------------------
def nearest_hit(scene, o, d):
    eps = 0 if "no-epsilon" in mistakes else EPS
    best, best_t = None, math.inf
    for i, s in enumerate(scene["objects"]):
        for t in hits(s, o, d):
            if eps < t < best_t:
                best, best_t = i, t
    return best, best_t


def shadow(scene, p, L, d_l):
    """S: the product of k_t over every crossing with EPS < t < d_L."""
    eps = 0 if "no-epsilon" in mistakes else EPS
    s_factor = 1.0
    for s in scene["objects"]:
        for t in hits(s, p, L):
            if eps < t < (math.inf if "shadow-past-light" in mistakes else d_l):
                s_factor *= s["material"]["kt"]
                if "any-hit-shadows" in mistakes:
                    s_factor = 0.0
    return s_factor


def attenuation(c, dist):
    return min(1.0, 1 / (c[0] + c[1] * dist + c[2] * dist * dist))


class Pixel:
    def __init__(self, scene, x, y, logging=True):
        self.scene, self.x, self.y, self.rays, self.logging = scene, x, y, 0, logging

    def log(self, path, **fields):
        if self.logging:
            log_ray(self.x, self.y, path, **fields)

    def trace(self, o, d, depth, weight, path):
        scene = self.scene
        self.rays += 1
        i, t = nearest_hit(scene, o, d)
        if i is None:
            miss_t = {}
            for slip, t_logged in (("miss-t-infinity", math.inf), ("miss-t-minus-one", -1.0), ("miss-t-null", None)):
                if slip in mistakes:
                    miss_t = {"t": t_logged}
            self.log(path, origin=o, dir=d, hit=None, color=scene["background"], weight=weight, **miss_t)
            return scene["background"], None
        obj = scene["objects"][i]
        m = obj["material"]
        p = add(o, mul(d, t))
        n_g = geometric_normal(obj, p)
        side = n_g  # MODEL §3: a patch's side is its plane's, turned to n_g's side
        if obj["kind"] == "patch":
            side = obj["normal"] if dot(obj["normal"], n_g) >= 0 else mul(obj["normal"], -1)
        entering = dot(side, d) < 0
        n = n_g if entering else mul(n_g, -1)
        v = mul(d, -1)
        if "nan" in mistakes:
            v = normalize(sub(p, p))  # meant o - p: a zero vector, normalised to NaN
        ambient = mul(vmul(scene["ambient"], m["color"]), m["ka"])
        if "no-ambient" in mistakes:
            ambient = (0.0, 0.0, 0.0)
        if "fatt-ambient" in mistakes and scene["lights"]:
            ambient = mul(ambient, attenuation(scene["light_att"], length(sub(scene["lights"][0][0], p))))
        color = ambient
        diffuse, specular = [], []
        for li, (pos, intensity) in enumerate(scene["lights"]):
            to_light = sub(pos, p)
            d_l = length(to_light)
            l = normalize(to_light)
            if "unnormalised-l" in mistakes:
                l = to_light
            ndotl = dot(n, l)
            if "abs-ndotl" in mistakes:
                ndotl = abs(ndotl)
            if d_l < EPS or ndotl <= 0:
                if "shadow-behind" in mistakes and d_l >= EPS:
                    self.log(f"{path}/S{li}", origin=p, dir=l, S=shadow(scene, p, l, d_l))
                diffuse.append((0.0, 0.0, 0.0))
                specular.append((0.0, 0.0, 0.0))
                continue
            s_factor = 1.0
            if "no-shadow-ray" not in mistakes:
                s_factor = shadow(scene, p, l, d_l)
                self.log(f"{path}/S{li}", origin=p, dir=l, S=s_factor)
            light = mul(intensity, s_factor * attenuation(scene["light_att"], d_l))
            if m["specular"] == "phong":
                cosine = dot(sub(mul(n, 2 * ndotl), l), v)
            else:
                cosine = dot(n, normalize(add(l, v)))
                if "h-unnormalised" in mistakes:
                    cosine = dot(n, add(l, v))
            diffuse.append(mul(vmul(light, m["color"]), m["kd"] * ndotl))
            specular.append(mul(light, m["ks"] * max(cosine, 0.0) ** m["n"]))
            if "specular-times-od" in mistakes:
                specular[-1] = vmul(specular[-1], m["color"])
            color = add(color, add(diffuse[-1], specular[-1]))

        max_depth = scene["max_depth"] + (1 if "past-max-depth" in mistakes else 0)
        if depth < max_depth:
            transmitted, tir = None, False
            if m["kt"] > 0:
                cos_i = -dot(d, n)
                eta = 1 / m["ior"] if entering else m["ior"]
                k = 1 - eta * eta * (1 - cos_i * cos_i)
                if k < 0 and "no-tir" not in mistakes:
                    tir = True
                elif k < 0:  # sqrt of a negative: NaN in C, the ray then meets nothing
                    transmitted = (math.nan, math.nan, math.nan)
                else:
                    n_t = n_g if "outward-normal" in mistakes and not entering else n
                    cos_t = -dot(d, n_t)
                    transmitted = add(mul(d, eta), mul(n_t, eta * cos_t - math.sqrt(k)))
            children = []
            if m["ks"] > 0 or tir:
                r = sub(d, mul(n, 2 * dot(d, n)))
                if "reflect-sign" in mistakes:
                    r = sub(mul(n, 2 * dot(n, d)), d)
                if "reflect-plus" in mistakes:
                    r = add(d, mul(n, 2 * dot(d, n)))
                children.append(("R", r, m["ks"] + (m["kt"] if tir else 0)))
            if transmitted is not None:
                children.append(("T", transmitted, m["kt"]))
            for step, direction, w in children:
                below = weight * w < scene["min_weight"] and "no-min-weight" not in mistakes
                if below or self.rays >= scene["max_rays"]:
                    continue
                child, child_t = self.trace(p, direction, depth + 1, weight * w, f"{path}/{step}")
                att = 1.0 if child_t is None else attenuation(scene["ray_att"], child_t)
                if f"unweighted-{'reflection' if step == 'R' else 'transmission'}" in mistakes:
                    w = 1.0
                color = add(color, mul(child, w * att))
        self.log(path, origin=o, dir=d, hit=i, t=t, point=p, normal=n, color=color,
                 ambient=ambient, diffuse=diffuse, specular=specular, weight=weight)
        return color, t


def primary_ray(scene, x, y, dx=0.5, dy=0.5):
    w, h = scene["width"], scene["height"]
    f = normalize(sub(scene["look_at"], scene["eye"]))
    r = normalize(cross(f, scene["up"]))
    u = cross(r, f)
    fov = scene["fov"] if "fov-radians" in mistakes else math.radians(scene["fov"])
    s = math.tan(fov / 2)
    cx, cy = (x, y) if "pixel-corner" in mistakes else (x + dx, y + dy)
    px = (2 * cx / w - 1) * s * (w / h)
    py = (1 - 2 * cy / h) * s
    if "pixel-span" in mistakes:
        px, py = (2 * x / (w - 1) - 1) * s * (w / h), (1 - 2 * y / (h - 1)) * s
    if "fov-horizontal" in mistakes:
        px, py = px * h / w, py * h / w
    return normalize(add(f, add(mul(r, px), mul(u, py))))


# --- the image ------------------------------------------------------------------
def to_byte(c):
    if "dim" in mistakes:
        c *= 0.8
    if "gamma" in mistakes:
        c = max(c, 0.0) ** (1 / 2.2)
    if "no-clamp" in mistakes:
        return int(255 * c + 0.5) & 0xFF
    return int(255 * max(0.0, min(1.0, c)) + 0.5)  # a NaN passes min() as 1.0


def render(scene):
    """The image's rows of RGB bytes, top row first."""
    rows = []
    for y in range(scene["height"]):
        row = bytearray()
        for x in range(scene["width"]):
            if "antialias" in mistakes:
                color = (0.0, 0.0, 0.0)
                for dx, dy in ((0.25, 0.25), (0.75, 0.25), (0.25, 0.75), (0.75, 0.75)):
                    c, _ = Pixel(scene, x, y, logging=False).trace(scene["eye"], primary_ray(scene, x, y, dx, dy), 1, 1.0, "P")
                    color = add(color, mul(tuple(max(0.0, min(1.0, v)) for v in c), 0.25))
            else:
                color, _ = Pixel(scene, x, y, logging=False).trace(scene["eye"], primary_ray(scene, x, y), 1, 1.0, "P")
            row.extend(to_byte(c) for c in color)
        rows.append(bytes(row))
    if "rows-bottom-up" in mistakes:
        rows.reverse()
    if "turn-180" in mistakes:
        rows = [bytes(b for px in reversed(range(len(r) // 3)) for b in r[3 * px:3 * px + 3]) for r in reversed(rows)]
    if "channels-swapped" in mistakes:
        rows = [bytes(b for px in range(len(r) // 3) for b in reversed(r[3 * px:3 * px + 3])) for r in rows]
    if "jpeg-noise" in mistakes:
        seed = 12345  # a fixed linear congruential sequence: the same bytes every run
        noisy = []
        for r in rows:
            out = bytearray()
            for b in r:
                seed = (seed * 1103515245 + 12345) % 2**31
                out.append(max(0, min(255, b + seed % 13 - 6)))
            noisy.append(bytes(out))
        rows = noisy
    return rows


def write_png(path, width, height, rows):
    """An 8-bit RGB PNG: the signature, then the IHDR, IDAT and IEND chunks."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)  # depth 8, colour type 2: RGB
    pixels = b"".join(b"\x00" + row for row in rows)  # each row starts with its filter: 0, none
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(pixels)) + chunk(b"IEND", b""))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene")
    ap.add_argument("x", type=int, nargs="?")
    ap.add_argument("y", type=int, nargs="?")
    ap.add_argument("-o", dest="png", help="render the whole image to this PNG")
    ap.add_argument("--size", help="WxH pixels from X, Y (default 1x1); with -o, the image's size")
    ap.add_argument("--image", help="WxH: trace the log's pixels as if the image were this size")
    ap.add_argument("--mistake", action="append", default=[], choices=sorted(MISTAKES))
    args = ap.parse_args()
    mistakes.update(args.mistake)
    scene = load(args.scene)
    if args.png:
        if args.x is not None:
            ap.error("-o renders the whole image: give no X, Y")
        if args.size:
            scene["width"], scene["height"] = (int(v) for v in args.size.split("x"))
        write_png(args.png, scene["width"], scene["height"], render(scene))
        return
    if args.y is None:
        ap.error("give a pixel X Y, or -o IMAGE.png")
    if args.image:
        scene["width"], scene["height"] = (int(v) for v in args.image.split("x"))
    w, h = (int(v) for v in (args.size or "1x1").split("x"))
    for y in range(args.y, args.y + h):
        for x in range(args.x, args.x + w):
            Pixel(scene, x, y).trace(scene["eye"], primary_ray(scene, x, y), 1, 1.0, "P")


if __name__ == "__main__":
    main()
