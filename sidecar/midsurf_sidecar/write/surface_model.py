"""One SHELL_BASED_SURFACE_MODEL for all the shells of the mid-surface, in the STEP file as written.

OCCT's writer puts each shell of a compound into a surface model of its own. Its reader translates each surface
model apart, so an edge shared by two shells (a T-joint's edge, the shells being manifold) comes back as two
edges: the mid-surface falls apart into as many pieces as shells. Shells listed in one surface model are read
with one map of the entities already translated, so the shared edge stays one edge. Measured on a box with a T
(two manifold shells sharing three edges): read back as 2 components from two surface models, 1 from one.
"""

import bisect
import re

_MODEL_NAME = re.compile(r"SHELL_BASED_SURFACE_MODEL")
_STRING = re.compile(r"'(?:[^']|'')*'")
_MODEL = re.compile(r"^#(\d+)\s*=\s*SHELL_BASED_SURFACE_MODEL\s*\(\s*'([^']*)'\s*,\s*\(([^()]*)\)\s*\)$", re.S)


def merge_surface_models(path: str) -> None:
    """Rewrites the STEP file `path` so the surface models items of one representation become one, holding all
    their shells. Left as it is when there is one model, or when a model is referenced by anything but that
    one representation's list of items (a style, a name): nothing is merged that the file ties to a model."""
    with open(path, encoding="latin-1", newline="") as f:
        text = f.read()
    data = text.find("DATA;")
    stop = text.find("ENDSEC;", data)
    # The DATA section with every string's inside blanked (same length, so offsets hold): a ';' or '#12' in a
    # name is no record end or reference. Whole-file scans by the regex engine, not a loop over characters: a
    # mid-surface of a thousand freeform faces is a file of 30 MB.
    blank = _STRING.sub(lambda m: "'" + " " * (len(m.group()) - 2) + "'", text[data:stop])
    ends = [data + m.start() for m in re.finditer(";", blank)]
    starts = [data + len("DATA;")] + [end + 1 for end in ends[:-1]]
    models = {}
    for k in sorted({bisect.bisect_left(ends, data + m.start()) for m in re.finditer(_MODEL_NAME, blank)}):
        if k < len(ends):
            match = _MODEL.match(text[starts[k] : ends[k]].strip())
            if match:
                models[match.group(1)] = (starts[k], ends[k], [r.strip() for r in match.group(3).split(",")])
    if len(models) < 2:
        return
    referrers: dict[str, list[tuple[int, int]]] = {m: [] for m in models}
    pattern = re.compile("#(" + "|".join(sorted(models)) + r")(?!\d)")
    for m in pattern.finditer(blank):
        at = data + m.start()
        k = bisect.bisect_left(ends, at)
        if k == len(ends):
            continue  # past the last record's ';'
        start, end = starts[k], ends[k]
        equals = text.find("=", start, end)
        own = text[start:equals].strip().lstrip("#") if equals >= 0 else None
        if equals >= 0 and at > equals and m.group(1) != own:
            referrers[m.group(1)].append((start, end))
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
    pieces, at = [], len(text)
    for start, end, replacement in sorted(edits, reverse=True):
        pieces += [text[end:at], replacement]
        at = start
    pieces.append(text[:at])
    with open(path, "w", encoding="latin-1", newline="") as f:
        f.write("".join(reversed(pieces)))
