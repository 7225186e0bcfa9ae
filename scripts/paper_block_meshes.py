#!/usr/bin/env python3
"""Writes the mesh files under cases/meshes/ that tests/mesh_reader.rs reads.

From cases/meshes/paper_block.geo, Gmsh (4.15.2, `pip install gmsh`) meshes the block once and
writes it as
    paper_block.msh          MSH 4.1 ASCII
    paper_block_binary.msh   MSH 4.1 binary
    paper_block_v2.msh       MSH 2.2 ASCII
    paper_block_saveall.msh  MSH 4.1 ASCII with Mesh.SaveAll = 1, after removing the physical
                             group "body": its cells (and the corner points) are in no group
Then this script derives paper_block_shuffled.msh from paper_block.msh: the same mesh with its
node and element tags replaced by a random permutation of sparse, non-contiguous tags, its node
and element blocks in reverse order, and every 2-D cell's nodes reversed (clockwise). The random
generator is seeded, so the output is the same on every run.

From cases/meshes/triangles.geo it writes triangles_v2.msh (MSH 2.2 ASCII) and
triangles_parametric.msh (MSH 4.1 ASCII with Mesh.SaveParametric = 1).

Usage (from the repository root):

    python3 -m pip install gmsh==4.15.2
    python3 scripts/paper_block_meshes.py
"""

import random
from pathlib import Path

import gmsh

MESHES = Path(__file__).resolve().parent.parent / "cases" / "meshes"


def write_with_gmsh():
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    assert gmsh.option.getString("General.Version") == "4.15.2", "these files are written with Gmsh 4.15.2"
    write_paper_block()
    gmsh.clear()
    write_triangles()
    gmsh.finalize()


def write_paper_block():
    gmsh.open(str(MESHES / "paper_block.geo"))
    gmsh.model.mesh.generate(2)
    for name, version, binary in [
        ("paper_block.msh", 4.1, 0),
        ("paper_block_binary.msh", 4.1, 1),
        ("paper_block_v2.msh", 2.2, 0),
    ]:
        gmsh.option.setNumber("Mesh.MshFileVersion", version)
        gmsh.option.setNumber("Mesh.Binary", binary)
        gmsh.write(str(MESHES / name))
    body = [(dim, tag) for dim, tag in gmsh.model.getPhysicalGroups(2)]
    gmsh.model.removePhysicalGroups(body)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 0)
    gmsh.option.setNumber("Mesh.SaveAll", 1)
    gmsh.write(str(MESHES / "paper_block_saveall.msh"))
    gmsh.option.setNumber("Mesh.SaveAll", 0)


def write_triangles():
    gmsh.open(str(MESHES / "triangles.geo"))
    gmsh.model.mesh.generate(2)
    gmsh.option.setNumber("Mesh.Binary", 0)
    gmsh.option.setNumber("Mesh.MshFileVersion", 2.2)
    gmsh.write(str(MESHES / "triangles_v2.msh"))
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.SaveParametric", 1)
    gmsh.write(str(MESHES / "triangles_parametric.msh"))
    gmsh.option.setNumber("Mesh.SaveParametric", 0)


def section(lines, name):
    """The index of the line after `$name` and that of `$Endname`."""
    start = lines.index("$" + name) + 1
    return start, lines.index("$End" + name)


def blocks(lines, start, end, rows_per_item):
    """The blocks of a $Nodes or $Elements section: (header line, item lines) each, where an item
    takes `rows_per_item(header)` lines."""
    out, i = [], start + 1
    while i < end:
        header = lines[i]
        count = int(header.split()[3])
        rows = rows_per_item(header) * count
        out.append((header, lines[i + 1 : i + 1 + rows]))
        i += 1 + rows
    return out


def shuffle(text, rng):
    lines = text.split("\n")
    n0, n1 = section(lines, "Nodes")
    e0, e1 = section(lines, "Elements")
    node_blocks = blocks(lines, n0, n1, lambda header: 2)
    element_blocks = blocks(lines, e0, e1, lambda header: 1)
    node_count = int(lines[n0].split()[1])
    element_count = int(lines[e0].split()[1])
    node_tag = dict(zip(range(1, node_count + 1), rng.sample(range(100, 100_000, 7), node_count)))
    element_tag = dict(zip(range(1, element_count + 1), rng.sample(range(50, 90_000, 13), element_count)))

    nodes = [lines[n0].split()[0] + f" {node_count} {min(node_tag.values())} {max(node_tag.values())}"]
    for header, rows in reversed(node_blocks):
        count = len(rows) // 2
        nodes.append(header)
        nodes += [str(node_tag[int(tag)]) for tag in rows[:count]]
        nodes += rows[count:]

    elements = [lines[e0].split()[0] + f" {element_count} {min(element_tag.values())} {max(element_tag.values())}"]
    for header, rows in reversed(element_blocks):
        dim = int(header.split()[0])
        elements.append(header)
        for row in rows:
            tag, *element_nodes = [int(t) for t in row.split()]
            element_nodes = [node_tag[n] for n in element_nodes]
            if dim == 2:
                element_nodes.reverse()
            elements.append(" ".join(str(t) for t in [element_tag[tag], *element_nodes]) + " ")
    return "\n".join(lines[:n0] + nodes + lines[n1:e0] + elements + lines[e1:])


if __name__ == "__main__":
    write_with_gmsh()
    text = (MESHES / "paper_block.msh").read_text()
    (MESHES / "paper_block_shuffled.msh").write_text(shuffle(text, random.Random(20261201)))
