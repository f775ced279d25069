#!/usr/bin/env python3
"""Writes assets/meshes/icosphere.obj: a unit icosahedron subdivided once (80 triangles), with
unit vertex normals, so that stage 2's Whitted scene has a mesh whose shading normals are
interpolated. Usage: tools/make_icosphere.py > assets/meshes/icosphere.obj
"""
import math

t = (1 + math.sqrt(5)) / 2
vertices = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t),
            (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
         (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]


def unit(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


vertices = [unit(v) for v in vertices]
midpoints = {}


def midpoint(a, b):
    key = (min(a, b), max(a, b))
    if key not in midpoints:
        vertices.append(unit(tuple((x + y) / 2 for x, y in zip(vertices[a], vertices[b]))))
        midpoints[key] = len(vertices) - 1
    return midpoints[key]


subdivided = []
for a, b, c in faces:
    ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
    subdivided += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]

print("# Icosphere: icosahedron subdivided once, 80 triangles; written by tools/make_icosphere.py")
for v in vertices:
    print("v %.6f %.6f %.6f" % v)
for v in vertices:
    print("vn %.6f %.6f %.6f" % v)
for a, b, c in subdivided:
    print("f %d//%d %d//%d %d//%d" % (a + 1, a + 1, b + 1, b + 1, c + 1, c + 1))
