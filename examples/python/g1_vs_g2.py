#!/usr/bin/env python3
"""G¹ against G²: the cost of evaluating 10⁶ domain points of one face with
Model.evaluate_positions (the batched fast path), on one thread and on all,
then a reflection-line picture of the G² surface.

Usage (with the module on PYTHONPATH, e.g. build/python, or installed):
    /usr/bin/python3 examples/python/g1_vs_g2.py [INPUT] [--points N] [--image FILE.png] [--size WxH]
INPUT defaults to the default network of `curvenet demo`."""

import argparse
import struct
import time
import zlib

import numpy as np

import curvenet

DEFAULT_NETWORK = "builtin:ellipsoid-truncated-icosahedron"


def domain_points(model, face, count, seed=1):
    """Uniform random points of the face's domain polygon: points of its fan
    triangles (centre, corner k, corner k + 1), as examples/batch-evaluate draws them."""
    corners = model.domain_corners(face)
    n = len(corners)
    rng = np.random.default_rng(seed)
    k = rng.integers(0, n, count)
    a, b = rng.random(count), rng.random(count)
    flip = a + b > 1
    a[flip], b[flip] = 1 - a[flip], 1 - b[flip]
    return corners[k] * a[:, None] + corners[(k + 1) % n] * b[:, None]


def fastest(run, repeats=3):
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        best = min(best, time.perf_counter() - start)
    return best


def write_png(path, pixels):
    """An (H, W, 3) uint8 array as an 8-bit RGB PNG (standard library only)."""
    height, width, _ = pixels.shape
    rows = b"".join(b"\x00" + pixels[y].tobytes() for y in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(rows, 6)) + chunk(b"IEND", b""))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("input", nargs="?", default=DEFAULT_NETWORK)
    parser.add_argument("--points", type=int, default=1_000_000)
    parser.add_argument("--face", type=int, default=0)
    parser.add_argument("--image", default="g1_vs_g2_reflection.png")
    parser.add_argument("--size", default="800x600", help="picture size WxH")
    args = parser.parse_args()

    models = {scheme: curvenet.Model.load(args.input, scheme=scheme) for scheme in ("gregory-g1", "gregory-g2")}
    uv = domain_points(models["gregory-g1"], args.face, args.points)
    out = np.empty((args.points, 3))
    sides = models["gregory-g1"].domain_sides(args.face)
    print(f"{args.input}, face {args.face} ({sides} sides), {args.points} positions, fastest of 3 "
          f"(curvenet {curvenet.__version__})")
    seconds = {}
    for threads, label in ((1, "1 thread"), (0, "all threads")):
        for scheme, model in models.items():
            model.evaluate_positions(args.face, uv[:1], threads=1)  # builds the face's tables: not timed
            seconds[scheme, threads] = fastest(lambda: model.evaluate_positions(args.face, uv, threads=threads, out=out))
            print(f"  {scheme:10s} {label:11s}: {seconds[scheme, threads]:.3f} s, "
                  f"{args.points / seconds[scheme, threads]:.3g} points/s")
    for threads, label in ((1, "1 thread"), (0, "all threads")):
        print(f"  G2/G1 cost, {label}: {seconds['gregory-g2', threads] / seconds['gregory-g1', threads]:.2f}")

    g1, g2 = (models[s].evaluate_positions(args.face, uv[:100_000]) for s in ("gregory-g1", "gregory-g2"))
    print(f"  largest distance between the G1 and G2 surfaces at 10^5 of the points: "
          f"{np.linalg.norm(g1 - g2, axis=1).max():.3g}")

    width, height = (int(v) for v in args.size.lower().split("x"))
    picture = models["gregory-g2"].render(mode="reflection", size=(width, height), resolution=32)
    write_png(args.image, picture)
    print(f"wrote {args.image} (gregory-g2 reflection lines, {picture.shape[1]}x{picture.shape[0]})")


if __name__ == "__main__":
    main()
