"""The mesh gmsh made, read into the reply's form: nodes (with the dimension of their CAD entity) and each
surface's quads and triangles by node index."""

import gmsh


def collect(tags: list[int], as_surface: int | None = None) -> dict:
    """Nodes entity by entity (vertices, then curves, then surfaces), remembering the entity's dimension: Rust's
    clean-up keeps the more constrained node of a collapsed edge where it is. Then the elements of the surfaces
    `tags`, each block named by its tag (or `as_surface`: a healed copy stands for the surface it replaces)."""
    index, nodes, node_dims = {}, [], []
    for dim in (0, 1, 2):
        for _, etag in gmsh.model.getEntities(dim):
            tags_, coords, _ = gmsh.model.mesh.getNodes(dim, etag)
            for i, t in enumerate(tags_):
                if int(t) in index:
                    continue
                index[int(t)] = len(nodes)
                nodes.append([float(coords[3 * i]), float(coords[3 * i + 1]), float(coords[3 * i + 2])])
                node_dims.append(dim)
    elements = []
    for tag in tags:
        quads, trias = [], []
        types, _, node_tags = gmsh.model.mesh.getElements(2, tag)
        for etype, enodes in zip(types, node_tags):
            k = {2: 3, 3: 4}.get(int(etype))
            if k is None:
                raise RuntimeError(f"surface {tag} has elements of gmsh type {etype}, not triangles or quads")
            out = trias if k == 3 else quads
            for j in range(0, len(enodes), k):
                out.append([index[int(t)] for t in enodes[j : j + k]])
        elements.append({"surface": tag if as_surface is None else as_surface, "quads": quads, "trias": trias})
    return {"nodes": nodes, "node_dims": node_dims, "elements": elements}


def empty_surfaces(tags: list[int]) -> list[int]:
    """The surfaces of `tags` without an element (gmsh failed on them)."""
    empty = []
    for tag in tags:
        _, element_tags, _ = gmsh.model.mesh.getElements(2, tag)
        if sum(len(e) for e in element_tags) == 0:
            empty.append(tag)
    return empty
