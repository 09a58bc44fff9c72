"""One SHELL_BASED_SURFACE_MODEL for all the shells of the mid-surface, in the STEP file as written.

OCCT's writer puts each shell of a compound into a surface model of its own. Its reader translates each surface
model apart, so an edge shared by two shells (a T-joint's edge, the shells being manifold) comes back as two
edges: the mid-surface falls apart into as many pieces as shells. Shells listed in one surface model are read
with one map of the entities already translated, so the shared edge stays one edge. Measured on a box with a T
(two manifold shells sharing three edges): read back as 2 components from two surface models, 1 from one.
"""

import re

_MODEL = re.compile(r"^#(\d+)\s*=\s*SHELL_BASED_SURFACE_MODEL\s*\(\s*'([^']*)'\s*,\s*\(([^()]*)\)\s*\)$", re.S)
_REFERENCE = re.compile(r"#(\d+)")


def merge_surface_models(path: str) -> None:
    """Rewrites the STEP file `path` so the surface models items of one representation become one, holding all
    their shells. Left as it is when there is one model, or when a model is referenced by anything but that
    one representation's list of items (a style, a name): nothing is merged that the file ties to a model."""
    with open(path, encoding="latin-1", newline="") as f:
        text = f.read()
    records = _records(text)
    models = {}
    for start, end in records:
        match = _MODEL.match(text[start:end].strip())
        if match:
            models[match.group(1)] = (start, end, [r.strip() for r in match.group(3).split(",")])
    if len(models) < 2:
        return
    referrers: dict[str, list[tuple[int, int]]] = {m: [] for m in models}
    for start, end in records:
        record = text[start:end]
        own = record.split("=", 1)[0].strip().lstrip("#")
        body = record.split("=", 1)[1] if "=" in record else ""
        for ref in _REFERENCE.findall(_without_strings(body)):
            if ref in referrers and ref != own:
                referrers[ref].append((start, end))
    holders = {span for spans in referrers.values() for span in spans}
    if len(holders) != 1 or any(len(spans) != 1 for spans in referrers.values()):
        return
    (holder_start, holder_end), = holders
    ids = sorted(models, key=lambda m: models[m][0])
    first = ids[0]
    shells = [shell for m in ids for shell in models[m][2]]
    edits = []  # (start, end, replacement), applied from the back
    holder = text[holder_start:holder_end]
    for m in ids[1:]:
        dropped = re.sub(rf",\s*#{m}(?!\d)", "", holder, count=1)
        holder = dropped if dropped != holder else re.sub(rf"#{m}(?!\d)\s*,\s*", "", holder, count=1)
        start, end, _ = models[m]
        edits.append((start, end + 1, ""))  # the record and its ';'
    start, end, _ = models[first]
    edits.append((start, end, f"\n#{first} = SHELL_BASED_SURFACE_MODEL('',({','.join(shells)}))"))
    edits.append((holder_start, holder_end, holder))
    for start, end, replacement in sorted(edits, reverse=True):
        text = text[:start] + replacement + text[end:]
    with open(path, "w", encoding="latin-1", newline="") as f:
        f.write(text)


def _records(text: str) -> list[tuple[int, int]]:
    """(start, end) of each entity record of the DATA section, without its ';' (strings may hold ';')."""
    data = text.find("DATA;")
    stop = text.find("ENDSEC;", data)
    records, start, quoted = [], data + len("DATA;"), False
    for i in range(start, stop):
        c = text[i]
        if c == "'":
            quoted = not quoted  # a doubled quote inside a string toggles twice
        elif c == ";" and not quoted:
            records.append((start, i))
            start = i + 1
    return records


def _without_strings(record: str) -> str:
    return re.sub(r"'(?:[^']|'')*'", "''", record)
