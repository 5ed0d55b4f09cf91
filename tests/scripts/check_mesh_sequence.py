#!/usr/bin/env python3
"""`tallow mesh --frames N` (issue 42, point 4): the melting candle written as a numbered PLY and
OBJ sequence, read back by a second reader written here from the formats' specifications (Python
standard library only, nothing of Tallow's): exactly N files of each, every one a
triangle mesh whose header counts match its body, indices in range, one unit normal per vertex,
finite coordinates, and the candle's model comment giving each frame's time t0 + i / fps.
Usage: check_mesh_sequence.py TALLOW_BINARY"""
import math
import os
import re
import struct
import subprocess
import sys
import tempfile

FRAMES, FPS, T0 = 3, 2.0, 16.0


def read_ply(path):
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    assert header[0] == "ply" and header[1] == "format binary_little_endian 1.0", header[:2]
    vertices = faces = None
    props = []
    comments = []
    for line in header:
        words = line.split()
        if words[:2] == ["element", "vertex"]:
            vertices = int(words[2])
        elif words[:2] == ["element", "face"]:
            faces = int(words[2])
        elif words[0] == "property" and faces is None:
            props.append(words[2])
        elif words[0] == "comment":
            comments.append(line[len("comment "):])
    assert props == ["x", "y", "z", "nx", "ny", "nz"], props
    body = data[end:]
    stride = 6 * 4
    verts = [struct.unpack_from("<6f", body, i * stride) for i in range(vertices)]
    offset = vertices * stride
    tris = []
    for _ in range(faces):
        (count,) = struct.unpack_from("<B", body, offset)
        assert count == 3, count
        tris.append(struct.unpack_from("<3I", body, offset + 1))
        offset += 1 + 12
    assert offset == len(body), "the body holds exactly the counted elements"
    return [v[:3] for v in verts], [v[3:] for v in verts], tris, comments


def read_obj(path):
    positions, normals, tris, comments = [], [], [], []
    with open(path) as f:
        for line in f:
            words = line.split()
            if not words:
                continue
            if words[0] == "#":
                comments.append(line[2:].rstrip("\n"))
            elif words[0] == "v":
                positions.append(tuple(float(w) for w in words[1:4]))
            elif words[0] == "vn":
                normals.append(tuple(float(w) for w in words[1:4]))
            elif words[0] == "f":
                corners = [w.split("//") for w in words[1:]]
                assert len(corners) == 3 and all(a == b for a, b in corners), line
                tris.append(tuple(int(a) - 1 for a, _ in corners))
            else:
                raise AssertionError("unexpected OBJ line: " + line)
    return positions, normals, tris, comments


def check(mesh, name, t):
    positions, normals, tris, comments = mesh
    assert len(tris) > 1000, (name, len(tris))
    assert len(normals) == len(positions), name
    assert all(math.isfinite(c) for p in positions for c in p), name
    for n in normals:
        assert abs(math.sqrt(sum(c * c for c in n)) - 1.0) < 1e-4, (name, n)
    assert all(0 <= i < len(positions) for tri in tris for i in tri), name
    times = [float(m.group(1)) for c in comments for m in [re.search(r"tallow\.candle \S+ t (\S+)", c)] if m]
    assert times and abs(times[0] - t) < 1e-6, (name, times, t)


def main():
    tallow = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        for ext, reader in ((".ply", read_ply), (".obj", read_obj)):
            out = os.path.join(tmp, "seq" + ext.replace(".", "_"), "candle" + ext)
            subprocess.run([tallow, "mesh", "--preset", "candle", "--res", "24", "--time", str(T0), "--fps", str(FPS),
                            "--frames", str(FRAMES), "--out", out], check=True, stdout=subprocess.DEVNULL)
            files = sorted(os.listdir(os.path.dirname(out)))
            assert files == ["candle_%04d%s" % (i, ext) for i in range(FRAMES)], files
            for i, name in enumerate(files):
                check(reader(os.path.join(os.path.dirname(out), name)), name, T0 + i / FPS)
    print("mesh sequence: %d PLY and %d OBJ frames read back" % (FRAMES, FRAMES))


if __name__ == "__main__":
    main()
