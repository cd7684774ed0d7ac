#!/usr/bin/env python3
"""A CSE 167 (UCSD; CSE167x on edX) ray tracer, from the course's HW3 spec.

Usage: cse167.py SCENE.test -o IMAGE.png

Written from the course's own words (the HW3 raytracer spec and HW2's
skeleton readfile.cpp for the transform stack), never from raystep's code.
Where the course is silent, the choices are raystep's documented ones
(docs/MODEL.md §2-§6 and §11, the module docs of scene/test_format), each
marked "MODEL" below. Python 3.11, standard library only.
"""

import argparse
import math
import struct
import zlib

EPS = 1e-4  # MODEL §3: every ray ignores hits with t <= EPS


# --- vectors and 3x4 affine matrices ----------------------------------------
def add(a, b): return (a[0] + b[0], a[1] + b[1], a[2] + b[2])
def sub(a, b): return (a[0] - b[0], a[1] - b[1], a[2] - b[2])
def mul(a, s): return (a[0] * s, a[1] * s, a[2] * s)
def vmul(a, b): return (a[0] * b[0], a[1] * b[1], a[2] * b[2])
def dot(a, b): return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    n = math.sqrt(dot(a, a))
    return (a[0] / n, a[1] / n, a[2] / n) if n > 0 else (0.0, 0.0, 0.0)


IDENTITY = ((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0))


def matmul(a, b):
    """a * b for affine matrices (rows of 4, the last row 0 0 0 1 implied)."""
    return tuple(tuple(sum(a[i][k] * b[k][j] for k in range(3)) + (a[i][3] if j == 3 else 0.0)
                       for j in range(4)) for i in range(3))


def point(m, p): return tuple(m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3] for i in range(3))
def vector(m, v): return tuple(m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2] for i in range(3))
def transpose_vector(m, v): return tuple(m[0][i] * v[0] + m[1][i] * v[1] + m[2][i] * v[2] for i in range(3))


def inverse(m):
    """The inverse of an affine matrix: the 3x3 part by its adjugate, then the translation."""
    a = [row[:3] for row in m]
    c = [[a[(i + 1) % 3][(j + 1) % 3] * a[(i + 2) % 3][(j + 2) % 3]
          - a[(i + 1) % 3][(j + 2) % 3] * a[(i + 2) % 3][(j + 1) % 3] for j in range(3)] for i in range(3)]
    det = sum(a[0][j] * c[0][j] for j in range(3))
    inv = [[c[j][i] / det for j in range(3)] for i in range(3)]  # adjugate = cofactors transposed
    t = [-sum(inv[i][k] * m[k][3] for k in range(3)) for i in range(3)]
    return tuple((inv[i][0], inv[i][1], inv[i][2], t[i]) for i in range(3))


def rotation(axis, degrees):
    """glRotate's matrix: counter-clockwise about the normalised axis (Rodrigues)."""
    x, y, z = normalize(axis)
    th = math.radians(degrees)
    c, s = math.cos(th), math.sin(th)
    k = 1 - c
    return ((x * x * k + c, x * y * k - z * s, x * z * k + y * s, 0.0),
            (y * x * k + z * s, y * y * k + c, y * z * k - x * s, 0.0),
            (z * x * k - y * s, z * y * k + x * s, z * z * k + c, 0.0))


# --- reading a .test file -------------------------------------------------------
def load(path):
    sc = {"maxdepth": 5, "attenuation": (1.0, 0.0, 0.0), "objects": [], "lights": [], "output": "raytrace.png"}
    stack = [IDENTITY]
    mat = {"ambient": (0.2, 0.2, 0.2), "diffuse": (0.0,) * 3, "specular": (0.0,) * 3,
           "emission": (0.0,) * 3, "shininess": 0.0}  # the spec's defaults: ambient .2, the rest 0
    verts, vnorms = [], []
    for line in open(path):
        words = line.split("#", 1)[0].split() if not line.lstrip().startswith("#") else []
        if not words:
            continue
        cmd, v = words[0], [float(w) for w in words[1:]] if words[0] != "output" else words[1:]
        top = stack[-1]
        if cmd == "size":
            sc["width"], sc["height"] = int(v[0]), int(v[1])
        elif cmd == "maxdepth":
            sc["maxdepth"] = int(v[0])
        elif cmd == "output":
            sc["output"] = v[0]
        elif cmd == "camera":
            sc["eye"], sc["at"], sc["up"], sc["fovy"] = tuple(v[0:3]), tuple(v[3:6]), tuple(v[6:9]), v[9]
        elif cmd in ("maxverts", "maxvertnorms"):
            pass  # only a hint for preallocation
        elif cmd == "vertex":
            verts.append(tuple(v))
        elif cmd == "vertexnormal":
            vnorms.append((tuple(v[0:3]), tuple(v[3:6])))
        elif cmd in ("sphere", "tri", "trinormal"):
            obj = dict(mat, kind=cmd)
            if cmd == "sphere":
                # kept in its own space with its matrix: an ellipsoid under a non-uniform scale
                obj.update(centre=tuple(v[0:3]), radius=v[3], m=top, inv=inverse(top))
            elif cmd == "tri":
                # the skeleton transforms a triangle's vertices when it is made
                obj["v"] = [point(top, verts[int(i)]) for i in v]
            else:
                inv = inverse(top)  # normals by the inverse transpose
                obj["v"] = [point(top, vnorms[int(i)][0]) for i in v]
                obj["n"] = [normalize(transpose_vector(inv, vnorms[int(i)][1])) for i in v]
            if cmd != "sphere":
                a, b, c = obj["v"]
                obj["plane"] = normalize(cross(sub(b, a), sub(c, a)))  # counter-clockwise is the front
            sc["objects"].append(obj)
        elif cmd == "translate":
            stack[-1] = matmul(top, ((1.0, 0.0, 0.0, v[0]), (0.0, 1.0, 0.0, v[1]), (0.0, 0.0, 1.0, v[2])))
        elif cmd == "scale":
            stack[-1] = matmul(top, ((v[0], 0.0, 0.0, 0.0), (0.0, v[1], 0.0, 0.0), (0.0, 0.0, v[2], 0.0)))
        elif cmd == "rotate":
            stack[-1] = matmul(top, rotation(v[0:3], v[3]))  # the skeleton's rightmultiply: T = T * M
        elif cmd == "pushTransform":
            stack.append(top)
        elif cmd == "popTransform":
            stack.pop()
        elif cmd == "directional":
            # "as in OpenGL": transformed by the matrix in force, as a vector (w = 0)
            sc["lights"].append(("directional", normalize(vector(top, v[0:3])), tuple(v[3:6])))
        elif cmd == "point":
            sc["lights"].append(("point", point(top, v[0:3]), tuple(v[3:6])))
        elif cmd == "attenuation":
            sc["attenuation"] = tuple(v)  # MODEL §11: one global value, the file's last
        elif cmd in ("ambient", "diffuse", "specular", "emission"):
            mat[cmd] = tuple(v)
        elif cmd == "shininess":
            mat["shininess"] = v[0]
        else:
            raise SystemExit(f"{path}: unknown command {cmd}")
    return sc


# --- hits -------------------------------------------------------------------------
def hit_t(obj, o, d):
    """The nearest t > EPS where the ray o + t d meets obj, or None."""
    if obj["kind"] == "sphere":
        # the ray into the sphere's own space (not renormalised, so t is shared)
        oo, dd = sub(point(obj["inv"], o), obj["centre"]), vector(obj["inv"], d)
        a, b, c = dot(dd, dd), 2 * dot(dd, oo), dot(oo, oo) - obj["radius"] ** 2
        disc = b * b - 4 * a * c
        if disc < 0:
            return None
        sq = math.sqrt(disc)
        for t in ((-b - sq) / (2 * a), (-b + sq) / (2 * a)):
            if t > EPS:
                return t
        return None
    n, v0 = obj["plane"], obj["v"][0]
    den = dot(n, d)
    if den == 0:
        return None
    t = dot(n, sub(v0, o)) / den
    if t <= EPS or barycentric(obj, add(o, mul(d, t))) is None:
        return None
    return t


def barycentric(obj, p):
    """p's weights on the triangle's corners, or None when p is outside it."""
    a, b, c = obj["v"]
    n = obj["plane"]
    wa = dot(n, cross(sub(c, b), sub(p, b)))
    wb = dot(n, cross(sub(a, c), sub(p, c)))
    wc = dot(n, cross(sub(b, a), sub(p, a)))
    if wa < 0 or wb < 0 or wc < 0:
        return None
    s = wa + wb + wc
    return (wa / s, wb / s, wc / s)


def nearest(sc, o, d, t_max=math.inf):
    best, best_t = None, t_max
    for obj in sc["objects"]:
        t = hit_t(obj, o, d)
        if t is not None and t < best_t:  # equal t: the first in file order stays
            best, best_t = obj, t
    return best, best_t


def shading_normal(obj, p, d):
    """The normal at p, facing the incoming ray d (every surface two-sided)."""
    if obj["kind"] == "sphere":
        q = mul(sub(point(obj["inv"], p), obj["centre"]), 1 / obj["radius"])
        n = normalize(transpose_vector(obj["inv"], q))  # M^-T n'
    elif obj["kind"] == "tri":
        n = obj["plane"]  # flat
    else:
        w = barycentric(obj, p) or (1 / 3, 1 / 3, 1 / 3)
        ns = normalize(add(add(mul(obj["n"][0], w[0]), mul(obj["n"][1], w[1])), mul(obj["n"][2], w[2])))
        if ns == (0.0, 0.0, 0.0):
            ns = obj["plane"]
        # MODEL §3 patch rule: the side is the plane's (turned to ns), N is ±ns as it is
        npl = obj["plane"] if dot(obj["plane"], ns) >= 0 else mul(obj["plane"], -1)
        return ns if dot(npl, d) < 0 else mul(ns, -1)
    return n if dot(n, d) <= 0 else mul(n, -1)


# --- the equation --------------------------------------------------------------
def trace(sc, o, d, depth):
    obj, t = nearest(sc, o, d)
    if obj is None:
        return (0.0, 0.0, 0.0)  # the background is black
    p = add(o, mul(d, t))
    n = shading_normal(obj, p, d)
    view = mul(d, -1)
    color = add(obj["ambient"], obj["emission"])  # I = A + E + ...
    for kind, pos, lcol in sc["lights"]:
        if kind == "point":
            to_l = sub(pos, p)
            dist = math.sqrt(dot(to_l, to_l))
            if dist < EPS:
                continue  # MODEL §4: a light at the point has no direction
            ldir = mul(to_l, 1 / dist)
            c0, c1, c2 = sc["attenuation"]
            att = 1 / (c0 + c1 * dist + c2 * dist * dist)  # the spec's: no clamp
        else:
            ldir, dist, att = pos, math.inf, 1.0  # directional: never attenuated
        # V_i: 0/1. MODEL §11: cast even when the light is behind the surface
        if nearest(sc, p, ldir, dist)[0] is not None:
            continue
        h = normalize(add(ldir, view))
        diffuse = mul(obj["diffuse"], max(dot(n, ldir), 0.0))
        specular = mul(obj["specular"], max(dot(n, h), 0.0) ** obj["shininess"])
        color = add(color, mul(vmul(lcol, add(diffuse, specular)), att))
    # mirror: maxdepth n = n bounces, so the primary ray (depth 1) and n more (MODEL §11)
    if depth < sc["maxdepth"] + 1 and max(obj["specular"]) > 0:
        r = sub(d, mul(n, 2 * dot(d, n)))
        color = add(color, vmul(obj["specular"], trace(sc, p, r, depth + 1)))
    return color


def primary_ray(sc, x, y):
    """MODEL §2: through the pixel's centre, fovy edge to edge of the image."""
    f = normalize(sub(sc["at"], sc["eye"]))
    r = normalize(cross(f, sc["up"]))
    u = cross(r, f)
    s = math.tan(math.radians(sc["fovy"]) / 2)
    w, h = sc["width"], sc["height"]
    px = (2 * (x + 0.5) / w - 1) * s * (w / h)
    py = (1 - 2 * (y + 0.5) / h) * s
    return normalize(add(f, add(mul(r, px), mul(u, py))))


def to_byte(c):
    return int(255 * max(0.0, min(1.0, c)) + 0.5)  # MODEL §6: floor(255 c + 0.5), no gamma


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
    ap.add_argument("-o", dest="png", help="the image (default: the file's output)")
    args = ap.parse_args()
    sc = load(args.scene)
    rows = []
    for y in range(sc["height"]):
        row = bytearray()
        for x in range(sc["width"]):
            row.extend(to_byte(c) for c in trace(sc, sc["eye"], primary_ray(sc, x, y), 1))
        rows.append(bytes(row))
    write_png(args.png or sc["output"], sc["width"], sc["height"], rows)


if __name__ == "__main__":
    main()
