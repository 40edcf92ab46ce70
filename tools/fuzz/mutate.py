"""Mutations of a scene for tools/fuzz_scenes.py.

A scene is parsed into plain Python values with objects kept as Obj (a list
of [key, value] pairs), so a mutant can hold a key twice and keys keep their
order. Raw is a token written into the text as it is (1e999, NaN, -0), which
Python's json module cannot produce. Every mutation draws only from the
random.Random it is given, so a seed reproduces a mutant exactly.
"""
import copy
import json
import math

__all__ = ["Obj", "Raw", "parse", "dump", "mutate", "MeshFile"]


class Obj(list):
    """A JSON object as [key, value] pairs (duplicates allowed)."""


class Raw(str):
    """A token copied into the text unchanged."""


def parse(text):
    return json.loads(text, object_pairs_hook=lambda pairs: Obj([list(p) for p in pairs]))


def dump(value, indent=0):
    pad = " " * indent
    if isinstance(value, Raw):
        return str(value)
    if isinstance(value, Obj):
        if not value:
            return "{}"
        items = [pad + "  " + json.dumps(k) + ": " + dump(v, indent + 2) for k, v in value]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(value, list):
        if not value:
            return "[]"
        # Long flat arrays on one line: a huge-array mutant stays a small file.
        if all(not isinstance(v, list) for v in value):
            return "[" + ", ".join(dump(v, indent) for v in value) + "]"
        return "[\n" + ",\n".join(pad + "  " + dump(v, indent + 2) for v in value) + "\n" + pad + "]"
    if isinstance(value, float) and not math.isfinite(value):
        return "1e999" if value > 0 else ("-1e999" if value < 0 else "NaN")
    return json.dumps(value)


# Values that probe ranges, integer conversion and number parsing.
EXTREME_NUMBERS = [0, 0.0, Raw("-0.0"), -1, 1, 2, 3, -2.5, 0.5, 1.5, 1e-9, 1e-308, 5e-324, -1e-300, 1e9, 1e30, 1e308,
                   -1e308, Raw("1e999"), Raw("-1e999"), Raw("1e-999"), 2**31 - 1, 2**31, 2**32, 4294967297, 2**53 + 1,
                   2**63, 2**64 + 1, -2**63 - 1, Raw("1" + "0" * 400)]
ODD_STRINGS = ["", " ", "NaN", "nan", "inf", "-Infinity", "1e999", "0", "-1", "true", "null", "x", "\u0000",
               "a\u0000b", "\x01\x1f\x7f", "\u00e9t\u00e9", "\u202e", "\U0001f30a" * 3, "\ud800", "a" * 5000,
               "../" * 20 + "etc/passwd", "/dev/null", "/", ".", "%s%n%x", "{}", "[]", "\n\t", "type", "box"]
# Tokens that are not JSON: each must be a syntax error with a line and column.
BAD_TOKENS = ["NaN", "Infinity", "-Infinity", "nan", "0x10", "01", ".5", "1.", "+1", "1e", "--1", "tru", "nul",
              "'x'", "\"\\x\"", "\"\\u12\"", "\"\\ud800\\u0041\"", "\u00ff", "\x00", "/*", "//\n"]
KEY_NAMES = ["type", "stage", "dim", "dp", "end", "max_steps", "every", "every_steps", "fields", "points", "gauges",
             "periodic", "min", "max", "kernel", "h_over_dp", "density", "file", "shape", "kind", "material",
             "layers", "faces", "vertices", "name", "materials", "bodies", "pipeline", "outputs", "time", "domain",
             "talus", "gravity", "eos", "rheology", "boundary", "contact", "motion", "checkpoint", "plugins"]


def nodes(value, path=()):
    """Every (parent, key_or_index, path) below value."""
    out = []
    if isinstance(value, Obj):
        for i, (k, v) in enumerate(value):
            out.append((value, i, path + (k,)))
            out.extend(nodes(v, path + (k,)))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            out.append((value, i, path + (i,)))
            out.extend(nodes(v, path + (i,)))
    return out


def copy_of(value):
    return copy.deepcopy(value)


def get(parent, i):
    return parent[i][1] if isinstance(parent, Obj) else parent[i]


def put(parent, i, v):
    if isinstance(parent, Obj):
        parent[i][1] = v
    else:
        parent[i] = v


def containers(doc):
    found = [doc] if isinstance(doc, list) else []
    found += [get(p, i) for p, i, _ in nodes(doc) if isinstance(get(p, i), list)]
    return found


def random_scalar(rng):
    pick = rng.random()
    if pick < 0.5:
        return rng.choice(EXTREME_NUMBERS)
    if pick < 0.8:
        return rng.choice(ODD_STRINGS)
    return rng.choice([None, True, False])


def random_value(rng, like=None):
    pick = rng.random()
    if pick < 0.5:
        return random_scalar(rng)
    if pick < 0.6:
        return []
    if pick < 0.7:
        return Obj()
    if pick < 0.85 and like is not None:
        return [like] if rng.random() < 0.5 else Obj([[rng.choice(KEY_NAMES), like]])
    return [random_scalar(rng) for _ in range(rng.randint(1, 4))]


def pick_node(rng, doc, want=None):
    found = [n for n in nodes(doc) if want is None or want(get(n[0], n[1]))]
    return rng.choice(found) if found else None


def is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool)


# Each mutation changes doc in place (or returns a replacement root) and
# names what it did, for the saved failure's notes.
def m_delete(rng, doc, ctx):
    n = pick_node(rng, doc)
    if not n:
        return "nothing to delete"
    parent, i, path = n
    del parent[i]
    return "deleted %s" % (path,)


def m_duplicate(rng, doc, ctx):
    n = pick_node(rng, doc)
    if not n:
        return "nothing to duplicate"
    parent, i, path = n
    entry = parent[i]
    copy = copy_of(entry[1]) if isinstance(parent, Obj) else copy_of(entry)
    parent.insert(i + 1, [entry[0], copy] if isinstance(parent, Obj) else copy)
    return "duplicated %s" % (path,)


def m_rename(rng, doc, ctx):
    objects = [x for x in nodes(doc) if isinstance(x[0], Obj)]
    if not objects:
        return "no key"
    parent, i, path = rng.choice(objects)
    old = parent[i][0]
    choice = rng.random()
    if choice < 0.3 and old:
        k = rng.randrange(len(old))
        new = old[:k] + old[k + 1:]
    elif choice < 0.5:
        new = old.upper()
    elif choice < 0.7:
        new = rng.choice(KEY_NAMES)
    else:
        new = old + rng.choice(ODD_STRINGS[:20])
    parent[i][0] = new
    return "renamed %s to %r" % (path, new[:40])


def m_retype(rng, doc, ctx):
    n = pick_node(rng, doc)
    if not n:
        return "nothing"
    parent, i, path = n
    put(parent, i, random_value(rng, get(parent, i)))
    return "retyped %s" % (path,)


def m_extreme(rng, doc, ctx):
    n = pick_node(rng, doc, is_number) or pick_node(rng, doc)
    if not n:
        return "nothing"
    parent, i, path = n
    v = rng.choice(EXTREME_NUMBERS)
    put(parent, i, v)
    return "set %s to %s" % (path, dump(v))


def m_scale(rng, doc, ctx):
    n = pick_node(rng, doc, is_number)
    if not n:
        return "no number"
    parent, i, path = n
    old = get(parent, i)
    factor = rng.choice([-1, 0.5, 2, 10, 0.1, 1e3, 1e-3, 1e6, -1e-6])
    new = old * factor if not isinstance(old, int) or factor == int(factor) else float(old) * factor
    if isinstance(old, int) and isinstance(new, float) and new == int(new) and abs(new) < 2**62:
        new = int(new)
    put(parent, i, new)
    return "scaled %s by %s" % (path, factor)


def m_string(rng, doc, ctx):
    n = pick_node(rng, doc, lambda v: isinstance(v, str)) or pick_node(rng, doc)
    if not n:
        return "nothing"
    parent, i, path = n
    v = rng.choice(ODD_STRINGS)
    put(parent, i, v)
    return "set %s to the string %r" % (path, v[:40])


def m_huge_array(rng, doc, ctx):
    n = pick_node(rng, doc)
    if not n:
        return "nothing"
    parent, i, path = n
    size = rng.choice([1000, 20000, 100000])
    kind = rng.random()
    if kind < 0.4:
        v = [rng.choice([0, 1, 0.5])] * size
    elif kind < 0.7:
        v = [[0.0, 0.0, 0.0] for _ in range(size // 10)]  # distinct lists: a later swap must not make a cycle
    else:
        v = ["x"] * size
    put(parent, i, v)
    return "set %s to an array of %d" % (path, len(v))


def m_deep(rng, doc, ctx):
    n = pick_node(rng, doc)
    if not n:
        return "nothing"
    parent, i, path = n
    depth = rng.choice([10, 63, 64, 65, 300, 5000, 100000])
    if rng.random() < 0.5:
        v = Raw("[" * depth + "1" + "]" * depth)
    else:
        v = Raw('{"a":' * depth + "1" + "}" * depth)
    put(parent, i, v)
    return "nested %s %d deep" % (path, depth)


def m_swap(rng, doc, ctx):
    all_nodes = nodes(doc)
    if len(all_nodes) < 2:
        return "nothing"
    (p1, i1, a), (p2, i2, b) = rng.sample(all_nodes, 2)
    if a[:len(b)] == b or b[:len(a)] == a:
        return "swap skipped (nested)"
    v1, v2 = get(p1, i1), get(p2, i2)
    put(p1, i1, copy_of(v2))
    put(p2, i2, copy_of(v1))
    return "swapped %s and %s" % (a, b)


def m_crossover(rng, doc, ctx):
    """A value of the same key from another shipped scene: mostly valid, new combinations."""
    other = rng.choice(ctx["corpus"])
    theirs = [n for n in nodes(other) if isinstance(n[0], Obj)]
    ours = [n for n in nodes(doc) if isinstance(n[0], Obj)]
    if not theirs or not ours:
        return "nothing"
    parent, i, path = rng.choice(ours)
    same = [n for n in theirs if n[0][n[1]][0] == parent[i][0]]
    if not same:
        return "no same key"
    tp, ti, tpath = rng.choice(same)
    put(parent, i, copy_of(get(tp, ti)))
    return "crossed %s from %s" % (path, tpath)


def m_array_edit(rng, doc, ctx):
    arrays = [a for a in containers(doc) if not isinstance(a, Obj) and a]
    if not arrays:
        return "no array"
    a = rng.choice(arrays)
    op = rng.random()
    if op < 0.4:
        del a[rng.randrange(len(a))]
        return "dropped an array element"
    if op < 0.7:
        k = rng.randrange(len(a))
        a.insert(k, copy_of(a[k]))
        return "repeated an array element"
    rng.shuffle(a)
    return "shuffled an array"


def m_add_key(rng, doc, ctx):
    objs = [o for o in containers(doc) if isinstance(o, Obj)]
    if not objs:
        return "no object"
    o = rng.choice(objs)
    key = rng.choice(KEY_NAMES + ODD_STRINGS[:12])
    o.append([key, random_value(rng)])
    return "added key %r" % key[:40]


def member(obj, key):
    if isinstance(obj, Obj):
        for k, v in obj:
            if k == key:
                return v
    return None


def m_periodic(rng, doc, ctx):
    domain = member(doc, "domain")
    if not isinstance(domain, Obj):
        return "no domain"
    axes = [a for a in ["x", "y", "z", "w", "x"] if rng.random() < 0.4] or ["x"]
    domain.append(["periodic", axes])
    if rng.random() < 0.3:
        for k, v in domain:
            if k in ("min", "max") and isinstance(v, list) and v and is_number(v[0]):
                v[0] = v[0] * rng.choice([1e-3, 1e308, 1e300]) if k == "max" else v[0]
    return "periodic %s" % axes


def outputs_of(doc):
    """The scene's "outputs" array, made if absent; None if it is not an array."""
    outputs = member(doc, "outputs")
    if outputs is None and isinstance(doc, Obj):
        outputs = []
        doc.append(["outputs", outputs])
    return outputs if type(outputs) is list else None


def m_probes(rng, doc, ctx):
    """A probes writer with points, gauges and fields that may not fit the scene."""
    outputs = outputs_of(doc)
    if outputs is None:
        return "outputs not an array"
    dim = member(member(doc, "domain"), "dim")
    n = 3 if dim != 2 else 2
    probe = Obj([["type", "probes"]])
    point = lambda: [rng.choice([0.0, 0.05, 0.5, -1.0, 1e3, 1e308]) for _ in range(n)]
    if rng.random() < 0.6:
        probe.append(["points", [point() for _ in range(rng.randint(1, 3))]])
    if rng.random() < 0.6:
        probe.append(["gauges", [point() for _ in range(rng.randint(1, 2))]])
    if rng.random() < 0.6:
        probe.append(["fields", rng.sample(["pressure", "velocity", "velocity_x", "velocity_mag", "density",
                                            "bogus", "id", "body", "velocity_w", "mu_eff", ""], 2)])
    if rng.random() < 0.3:
        probe.append(["wall_forces", [rng.choice(["walls", "tank", "nope"])]])
    if rng.random() < 0.5:
        probe.append(["every_steps", 1])
    outputs.append(probe)
    return "added a probes writer"


def m_writer_fields(rng, doc, ctx):
    outputs = outputs_of(doc)
    if outputs is None:
        return "outputs not an array"
    w = Obj([["type", rng.choice(["vtu", "hdf5"])],
             ["fields", rng.sample(["velocity", "pressure", "density", "bogus", "id", "mass", "mu_eff", ""], 2)]])
    outputs.append(w)
    return "added a writer with fields"


class MeshFile:
    """An auxiliary mesh file the mutant refers to: (name, bytes)."""

    def __init__(self, name, data):
        self.name, self.data = name, data


CUBE_V = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
CUBE_F = ("f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\n"
          "f 4 5 8\n")


def mesh_bytes(rng):
    kind = rng.random()
    scale = rng.choice(["0.01", "0.1", "1", "1e308", "nan", "-0.05"])
    verts = CUBE_V.replace("1", scale) if rng.random() < 0.3 else CUBE_V
    if kind < 0.2:
        return "cube.obj", (verts + CUBE_F).encode()
    if kind < 0.45:
        bad = rng.choice(["f 1 2 4294967297\n", "f 1 2 -100\n", "f 1 2\n", "f 0 1 2\n", "v 1 2\n", "f a b c\n",
                          "v 1e999 0 0\n", "f 1 2 99999999999999999999\n", "f 1/2/3 2//1 3\n"])
        return "bad.obj", (verts + CUBE_F + bad).encode()
    if kind < 0.55:
        text = (verts + CUBE_F).encode()
        return "cut.obj", text[: rng.randrange(len(text))]
    if kind < 0.7:
        facets = "".join("facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
                         for _ in range(2))
        text = ("solid s\n" + facets + "endsolid s\n").encode()
        return "tri.stl", text if rng.random() < 0.5 else text[: rng.randrange(len(text))]
    if kind < 0.85:
        count = rng.choice([0, 1, 12, 2**32 - 1, 2**31])
        body = bytes(rng.randrange(256) for _ in range(rng.choice([0, 50, 600])))
        return "bin.stl", b"\0" * 80 + count.to_bytes(4, "little") + body
    return rng.choice(["empty.obj", "empty.stl", "mesh.ply", "noext"]), b""


def m_mesh_shape(rng, doc, ctx):
    bodies = member(doc, "bodies")
    if type(bodies) is not list or not bodies:
        return "no bodies"
    body = rng.choice(bodies)
    if not isinstance(body, Obj):
        return "body not an object"
    name, data = mesh_bytes(rng)
    ctx["aux"].append(MeshFile(name, data))
    shape = Obj([["mesh", Obj([["file", name]] + ([["scale", rng.choice([0.01, 0.1, 1e-300, 1e300])]]
                                                  if rng.random() < 0.4 else []))]])
    for entry in body:
        if entry[0] == "shape":
            entry[1] = shape
            break
    else:
        body.append(["shape", shape])
    return "mesh shape from %s" % name


def dem_bytes(rng, original):
    lines = original.split(b"\n")
    kind = rng.random()
    if kind < 0.25:
        return original[: rng.randrange(len(original))]
    if kind < 0.6:
        k = rng.randrange(min(6, len(lines)))
        words = lines[k].split()
        if len(words) >= 2:
            words[1] = rng.choice([b"0", b"-1", b"1e308", b"nan", b"4294967297", b"x", b"1e999", b"2.5", b""])
        lines[k] = b" ".join(words)
        return b"\n".join(lines)
    if kind < 0.8:
        k = rng.randrange(6, max(7, len(lines)))
        if k < len(lines):
            lines[k] = rng.choice([b"nan nan", b"1e999", b"x", b"", b"-9999 " * 500])
        return b"\n".join(lines)
    return b"\n".join(lines[:6])


def m_dem(rng, doc, ctx):
    if not ctx.get("dem"):
        return "no DEM"
    ctx["dem_bytes"] = dem_bytes(rng, ctx["dem"])
    return "mutated the DEM"


MUTATIONS = [(m_delete, 10), (m_duplicate, 5), (m_rename, 6), (m_retype, 10), (m_extreme, 14), (m_scale, 10),
             (m_string, 5), (m_huge_array, 2), (m_deep, 2), (m_swap, 5), (m_crossover, 8), (m_array_edit, 5),
             (m_add_key, 4), (m_periodic, 4), (m_probes, 5), (m_writer_fields, 3), (m_mesh_shape, 3), (m_dem, 2)]


def text_mutation(rng, text):
    """Byte-level damage: truncation, a bad token, a flipped or dropped byte."""
    data = text.encode("utf-8", "surrogatepass")
    kind = rng.random()
    if kind < 0.45:
        return data[: rng.randrange(len(data))], "truncated"
    if kind < 0.7:
        # A bad token in place of a number or literal.
        spots = [i for i in range(len(data) - 1) if data[i:i + 1] in (b":", b",", b"[") and data[i + 1:i + 2] == b" "]
        if spots:
            at = rng.choice(spots) + 2
            end = at
            while end < len(data) and data[end:end + 1] not in (b",", b"]", b"}", b"\n"):
                end += 1
            tok = rng.choice(BAD_TOKENS).encode("utf-8", "surrogatepass")
            return data[:at] + tok + data[end:], "bad token %r" % tok
    if kind < 0.85:
        at = rng.randrange(len(data))
        return data[:at] + bytes([rng.randrange(256)]) + data[at + 1:], "flipped a byte"
    at = rng.randrange(len(data))
    return data[:at] + data[at + rng.randint(1, 40):], "dropped bytes"


def mutate(rng, doc, ctx):
    """Applies 1-3 structural mutations, then sometimes text damage. Returns (bytes, notes)."""
    notes = []
    names = [m for m, _ in MUTATIONS]
    weights = [w for _, w in MUTATIONS]
    for _ in range(rng.choice([1, 1, 1, 2, 2, 3])):
        fn = rng.choices(names, weights)[0]
        notes.append(fn(rng, doc, ctx))
    if ctx.get("prepare"):
        ctx["prepare"](doc)
    text = dump(doc) + "\n"
    if rng.random() < 0.12:
        data, note = text_mutation(rng, text)
        notes.append(note)
        return data, notes
    return text.encode("utf-8", "surrogatepass"), notes
