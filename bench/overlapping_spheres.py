"""Random overlapping UV spheres written as ONE binary STL: a self-overlapping mesh for
`meshbool resolve` (issue 14's benchmarks).

Usage: python3 bench/overlapping_spheres.py COUNT SEGMENTS SEED OUT.stl
  COUNT spheres, centres uniform in [0, 3]^3, radii uniform in [0.6, 1.2], each with
  SEGMENTS segments around and SEGMENTS/2 rings (2 * SEGMENTS * (SEGMENTS/2 - 1)
  triangles; 256 gives 65,024). Needs numpy.
"""

import struct
import sys

import numpy as np


def sphere(c, r, nu, nv):
    """Triangles (three corner arrays each) of a UV sphere facing outward."""
    th = np.linspace(0, np.pi, nv + 1)
    ph = np.linspace(0, 2 * np.pi, nu + 1)[:-1]

    def v(i, j):
        if i == 0:
            return c + np.array([0, 0, r])
        if i == nv:
            return c + np.array([0, 0, -r])
        return c + r * np.array(
            [np.sin(th[i]) * np.cos(ph[j % nu]), np.sin(th[i]) * np.sin(ph[j % nu]), np.cos(th[i])]
        )

    out = []
    for i in range(nv):
        for j in range(nu):
            a, b, cc, d = v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)
            if i > 0:
                out.append((a, b, d))
            if i < nv - 1:
                out.append((b, cc, d))
    return out


def main():
    count, seg, seed, path = int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
    rng = np.random.default_rng(seed)
    tris = []
    for _ in range(count):
        c = rng.uniform(0, 3, 3)
        r = rng.uniform(0.6, 1.2)
        tris += sphere(c, r, seg, seg // 2)
    with open(path, "wb") as f:
        f.write(b"\0" * 80)
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", 0, 0, 0))
            for p in t:
                f.write(struct.pack("<3f", *p))
            f.write(b"\0\0")
    print(len(tris))


if __name__ == "__main__":
    main()
