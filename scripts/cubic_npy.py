#!/usr/bin/env python3
"""Writes the inputs of the `bezinv invert` file benchmark (BENCHMARKS.md): N points on the README's
cubic (control points (0,0) (1,2) (3,2) (4,0)) at uniformly random t, as a float64 (N, 2) .npy
file, and the curves file. Standard library only (no NumPy), streamed in blocks.

    python3 scripts/cubic_npy.py DIR [N]      # DIR/cubic.json, DIR/cubic-points.npy; N = 10,000,000
"""
import array
import json
import os
import random
import sys

CUBIC = [(0.0, 0.0), (1.0, 2.0), (3.0, 2.0), (4.0, 0.0)]


def point(t):
    s = 1.0 - t
    b = [s * s * s, 3 * s * s * t, 3 * s * t * t, t * t * t]
    return sum(w * p[0] for w, p in zip(b, CUBIC)), sum(w * p[1] for w, p in zip(b, CUBIC))


def main():
    directory = sys.argv[1]
    count = int(sys.argv[2]) if len(sys.argv) > 2 else 10_000_000
    os.makedirs(directory, exist_ok=True)
    with open(os.path.join(directory, "cubic.json"), "w") as f:
        json.dump({"curves": [{"id": "cubic", "kind": "bezier", "points": [list(p) for p in CUBIC]}]}, f)
    header = "{'descr': '<f8', 'fortran_order': False, 'shape': (%d, 2), }" % count
    header += " " * ((64 - (10 + len(header) + 1) % 64) % 64) + "\n"
    rng = random.Random(2026)
    with open(os.path.join(directory, "cubic-points.npy"), "wb") as f:
        f.write(b"\x93NUMPY\x01\x00" + len(header).to_bytes(2, "little") + header.encode("latin1"))
        done = 0
        while done < count:
            block = array.array("d")
            for _ in range(min(1_000_000, count - done)):
                block.extend(point(rng.random()))
            if sys.byteorder != "little":
                block.byteswap()
            block.tofile(f)
            done += len(block) // 2


if __name__ == "__main__":
    main()
